//! ASME B16.5 pipe flange dimensions for Classes 150, 300, 600 and 900,
//! NPS 1/2 through 24: the typed lookup [`flange`], the [`FlangeClass`] key
//! and the [`raised_face_height`] rule. The numbers themselves live in
//! `flange/data.rs`.
//!
//! # Edition and raised-face convention
//!
//! Values follow the metric tables of ASME B16.5-2013 / -2017 / -2020 (these
//! editions print the same dimensions; the convention below dates from
//! B16.5-2003). In these editions, for **every** class, the minimum flange
//! thickness `tf` ([`FlangeDimensions::thickness`]) and both lengths through
//! hub `Y` ([`FlangeDimensions::weld_neck_length`],
//! [`FlangeDimensions::slip_on_length`]) **exclude** the raised face: they
//! are measured from the flange face the raised face stands on. The raised
//! face of height [`raised_face_height`] — 2 mm for Classes 150 and 300,
//! 7 mm for Class 400 and above — is *in addition to* them. So a raised-face
//! flange measures `thickness + raised_face_height(class)` from the nut
//! bearing surface to the gasket surface, and a weld-neck flange measures
//! `weld_neck_length + raised_face_height(class)` from the weld bevel to the
//! gasket surface.
//!
//! Editions up to B16.5-1996 differed for Classes 150 and 300 only: their
//! thickness `C` and hub lengths included the 1.6 mm (0.06 in) raised face,
//! which is why older tables give Class 150 NPS 4 as 24 mm (0.94 in) thick
//! where the current tables give 22.3 mm (0.88 in). Class 400 and above
//! always excluded the 6.4 mm (0.25 in) raised face.

use std::fmt;

mod data;
use super::pipe::{Nps, TableError};

/// A B16.5 pressure class covered by the tables.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum FlangeClass {
    /// Class 150.
    C150,
    /// Class 300.
    C300,
    /// Class 600.
    C600,
    /// Class 900. B16.5 gives NPS 1/2 through 2-1/2 Class 900 flanges the
    /// Class 1500 dimensions, and lists no NPS 3-1/2.
    C900,
}

impl FlangeClass {
    /// Every class the tables cover, lowest rating first.
    pub const ALL: [FlangeClass; 4] = [
        FlangeClass::C150,
        FlangeClass::C300,
        FlangeClass::C600,
        FlangeClass::C900,
    ];

    /// The class for a numeric rating: 150, 300, 600 or 900.
    ///
    /// # Errors
    ///
    /// [`TableError::UnknownRating`] for any other number.
    pub fn try_from_rating(rating: u32) -> Result<FlangeClass, TableError> {
        FlangeClass::ALL
            .into_iter()
            .find(|class| class.rating() == rating)
            .ok_or(TableError::UnknownRating { rating })
    }

    /// The numeric rating, e.g. 300 for [`FlangeClass::C300`].
    pub fn rating(self) -> u32 {
        match self {
            FlangeClass::C150 => 150,
            FlangeClass::C300 => 300,
            FlangeClass::C600 => 600,
            FlangeClass::C900 => 900,
        }
    }
}

impl fmt::Display for FlangeClass {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "Class {}", self.rating())
    }
}

/// Dimensions of one B16.5 flange size and class, all in mm except
/// [`bolt_size_in`](Self::bolt_size_in). Letters in brackets are B16.5's own.
///
/// See the module documentation for how [`thickness`](Self::thickness) and
/// the hub lengths relate to the raised face (they exclude it).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FlangeDimensions {
    /// Flange outside diameter (O).
    pub outside_diameter: f64,
    /// Minimum flange thickness (tf), raised face not included.
    pub thickness: f64,
    /// Hub diameter at the base, where the hub meets the flange back (X).
    pub hub_base_diameter: f64,
    /// Weld-neck hub diameter at the welding point (A); equals the B36.10M
    /// pipe outside diameter.
    pub hub_weld_diameter: f64,
    /// Length through hub of a weld-neck flange (Y), from the flange face
    /// (base of the raised face) to the weld end; raised face not included.
    pub weld_neck_length: f64,
    /// Length through hub of a slip-on flange (Y), from the flange face
    /// (base of the raised face) to the hub end; raised face not included.
    pub slip_on_length: f64,
    /// Raised-face diameter (R).
    pub raised_face_diameter: f64,
    /// Bolt-circle diameter (W).
    pub bolt_circle_diameter: f64,
    /// Number of bolts (and bolt holes).
    pub bolt_count: u32,
    /// Bolt-hole diameter, mm: B16.5 gives holes in inches (e.g. 3/4 in), and
    /// this is that value times 25.4 without rounding (19.05 mm).
    pub bolt_hole_diameter: f64,
    /// Nominal bolt diameter in inches (e.g. 0.625 for 5/8 in), as B16.5 gives it.
    pub bolt_size_in: f64,
}

/// The B16.5 dimensions of a `class` flange of size `nps`.
///
/// Class 900 NPS 1/2 through 2-1/2 come back with the Class 1500
/// dimensions, as B16.5 prescribes.
///
/// # Errors
///
/// [`TableError::FlangeNotListed`] where B16.5 lists no such flange: among
/// the sizes and classes here that is only NPS 3-1/2 in Class 900 (B16.5
/// lists NPS 3-1/2 only up to Class 600).
pub fn flange(nps: Nps, class: FlangeClass) -> Result<&'static FlangeDimensions, TableError> {
    data::rows(class)
        .iter()
        .find(|row| row.nps == nps.inches())
        .map(|row| &row.dims)
        .ok_or(TableError::FlangeNotListed {
            nps_inches: nps.inches(),
            class: class.rating(),
        })
}

/// Height of the standard raised face, mm: 2 mm for Classes 150 and 300
/// (B16.5's metric value for the 0.06 in / 1.6 mm face) and 7 mm for Class
/// 600 and above (for the 0.25 in / 6.4 mm face).
///
/// In the tables used here this height is never part of
/// [`FlangeDimensions::thickness`] or the hub lengths: add it to get the
/// overall thickness or length of a raised-face flange (see the module
/// documentation).
pub fn raised_face_height(class: FlangeClass) -> f64 {
    match class {
        FlangeClass::C150 | FlangeClass::C300 => 2.0,
        FlangeClass::C600 | FlangeClass::C900 => 7.0,
    }
}

#[cfg(test)]
mod tests {
    use super::super::pipe::pipe;
    use super::*;

    fn nps(inches: f64) -> Nps {
        Nps::try_new(inches).expect("test size is a table size")
    }

    fn get(inches: f64, class: FlangeClass) -> &'static FlangeDimensions {
        flange(nps(inches), class).expect("test flange is listed")
    }

    /// Every listed (size, class) pair with its dimensions.
    fn all_listed() -> Vec<(Nps, FlangeClass, &'static FlangeDimensions)> {
        FlangeClass::ALL
            .into_iter()
            .flat_map(|c| Nps::all().filter_map(move |n| flange(n, c).ok().map(|d| (n, c, d))))
            .collect()
    }

    #[test]
    fn ratings_round_trip_and_unknown_ratings_are_errors() {
        for class in FlangeClass::ALL {
            assert_eq!(FlangeClass::try_from_rating(class.rating()), Ok(class));
        }
        for bad in [0, 125, 400, 1500, 2500, u32::MAX] {
            assert_eq!(
                FlangeClass::try_from_rating(bad),
                Err(TableError::UnknownRating { rating: bad })
            );
        }
        let message = FlangeClass::try_from_rating(400).unwrap_err().to_string();
        assert_eq!(
            message,
            "Class 400 is not a supported flange rating; expected 150, 300, 600 or 900"
        );
        assert_eq!(FlangeClass::C600.to_string(), "Class 600");
    }

    #[test]
    fn only_class_900_nps_3_half_is_missing() {
        let missing: Vec<_> = FlangeClass::ALL
            .into_iter()
            .flat_map(|c| Nps::all().map(move |n| (n, c)))
            .filter(|&(n, c)| flange(n, c).is_err())
            .map(|(n, c)| (n.inches(), c))
            .collect();
        assert_eq!(missing, vec![(3.5, FlangeClass::C900)]);
        let err = flange(nps(3.5), FlangeClass::C900).unwrap_err();
        assert_eq!(
            err,
            TableError::FlangeNotListed {
                nps_inches: 3.5,
                class: 900
            }
        );
        let message = err.to_string();
        assert!(message.contains("Class 900") && message.contains("NPS 3-1/2"));
        assert!(message.contains("only up to Class 600"));
    }

    #[test]
    fn every_row_is_physically_consistent() {
        // 4 classes x 20 sizes, less Class 900 NPS 3-1/2.
        assert_eq!(all_listed().len(), 79);
        for (n, c, d) in all_listed() {
            let ctx = format!("{c} {n}: {d:?}");
            // Radial order: O > W > R, and the hub sits inside the bolt circle.
            assert!(d.outside_diameter > d.bolt_circle_diameter, "O > W, {ctx}");
            assert!(
                d.bolt_circle_diameter > d.raised_face_diameter,
                "W > R, {ctx}"
            );
            assert!(d.bolt_circle_diameter > d.hub_base_diameter, "W > X, {ctx}");
            assert!(d.hub_base_diameter > d.hub_weld_diameter, "X > A, {ctx}");
            // A is the pipe OD.
            let od = pipe(n).outside_diameter;
            assert!(
                (d.hub_weld_diameter - od).abs() <= 1.0,
                "A = pipe OD, {ctx}"
            );
            // Bolt holes clear the hub base and the raised face, and stay in the flange.
            let inner_edge = d.bolt_circle_diameter - d.bolt_hole_diameter;
            let outer_edge = d.bolt_circle_diameter + d.bolt_hole_diameter;
            assert!(inner_edge > d.hub_base_diameter, "holes clear hub, {ctx}");
            assert!(inner_edge > d.raised_face_diameter, "holes clear RF, {ctx}");
            assert!(outer_edge < d.outside_diameter, "holes inside O, {ctx}");
            // Every hole is 1/8" over its bolt (e.g. 2-1/2" bolts in 2-5/8" holes).
            let clearance_in = d.bolt_hole_diameter / 25.4 - d.bolt_size_in;
            assert!(
                (clearance_in - 0.125).abs() < 1e-9,
                "hole = bolt + 1/8\", {ctx}"
            );
            // Bolt counts are multiples of four, and the holes do not overlap.
            assert!(d.bolt_count >= 4 && d.bolt_count % 4 == 0, "{ctx}");
            let pitch = std::f64::consts::PI * d.bolt_circle_diameter / f64::from(d.bolt_count);
            assert!(pitch > 1.5 * d.bolt_hole_diameter, "hole pitch, {ctx}");
            // Hub lengths exceed the flange thickness; the weld neck is longer.
            assert!(d.slip_on_length > d.thickness, "Y(SO) > tf, {ctx}");
            assert!(
                d.weld_neck_length > d.slip_on_length,
                "Y(WN) > Y(SO), {ctx}"
            );
            assert!(d.thickness > 0.0, "{ctx}");
        }
    }

    #[test]
    fn raised_face_diameter_does_not_depend_on_class() {
        for n in Nps::all() {
            let r = get(n.inches(), FlangeClass::C150).raised_face_diameter;
            for c in FlangeClass::ALL {
                if let Ok(d) = flange(n, c) {
                    assert_eq!(d.raised_face_diameter, r, "{c} {n}");
                }
            }
        }
    }

    #[test]
    fn dimensions_grow_with_class_at_fixed_size() {
        for n in Nps::all() {
            let rows: Vec<_> = FlangeClass::ALL
                .into_iter()
                .filter_map(|c| flange(n, c).ok())
                .collect();
            for pair in rows.windows(2) {
                let (lo, hi) = (pair[0], pair[1]);
                assert!(hi.thickness > lo.thickness, "{n}: tf grows with class");
                assert!(hi.outside_diameter >= lo.outside_diameter, "{n}: O");
                assert!(hi.bolt_circle_diameter >= lo.bolt_circle_diameter, "{n}: W");
                assert!(hi.weld_neck_length >= lo.weld_neck_length, "{n}: Y(WN)");
            }
        }
    }

    #[test]
    fn dimensions_grow_with_size_at_fixed_class() {
        for c in FlangeClass::ALL {
            let rows: Vec<_> = Nps::all()
                .filter_map(|n| flange(n, c).ok().map(|d| (n, d)))
                .collect();
            for pair in rows.windows(2) {
                let ((n0, lo), (n1, hi)) = (pair[0], pair[1]);
                // The one B16.5 exception: Class 900 NPS 2-1/2 carries Class 1500
                // dimensions (O 245) and is bigger than Class 900 NPS 3 (O 240).
                if c == FlangeClass::C900 && n0.inches() == 2.5 {
                    assert_eq!((lo.outside_diameter, hi.outside_diameter), (245.0, 240.0));
                    continue;
                }
                assert!(
                    hi.outside_diameter > lo.outside_diameter,
                    "{c} {n0}->{n1}: O"
                );
                assert!(
                    hi.bolt_circle_diameter > lo.bolt_circle_diameter,
                    "{c} {n1}: W"
                );
                assert!(hi.hub_base_diameter > lo.hub_base_diameter, "{c} {n1}: X");
                assert!(
                    hi.raised_face_diameter > lo.raised_face_diameter,
                    "{c} {n1}: R"
                );
                assert!(hi.thickness >= lo.thickness, "{c} {n1}: tf");
                assert!(hi.bolt_size_in >= lo.bolt_size_in || hi.bolt_count > lo.bolt_count);
            }
        }
    }

    #[test]
    fn class_900_small_sizes_use_class_1500_dimensions() {
        // B16.5 Class 1500 NPS 2: O 215, tf 38.1, X 105, W 165.1, 8 x 7/8" bolts.
        let d = get(2.0, FlangeClass::C900);
        assert_eq!(
            (d.outside_diameter, d.thickness, d.hub_base_diameter),
            (215.0, 38.1, 105.0)
        );
        assert_eq!(
            (d.bolt_circle_diameter, d.bolt_count, d.bolt_size_in),
            (165.1, 8, 0.875)
        );
        // Class 1500 NPS 1/2: O 120, tf 22.3, 4 x 3/4" bolts in 7/8" holes.
        let d = get(0.5, FlangeClass::C900);
        assert_eq!(
            (d.outside_diameter, d.thickness, d.bolt_count),
            (120.0, 22.3, 4)
        );
        assert_eq!(d.bolt_size_in, 0.75);
        assert!((d.bolt_hole_diameter - 22.225).abs() < 1e-9);
    }

    #[test]
    fn well_known_values() {
        // Class 150 NPS 4 (O is 9 in = 228.6 mm, which the
        // metric table prints as 230).
        let d = get(4.0, FlangeClass::C150);
        assert_eq!(d.outside_diameter, 230.0);
        assert_eq!(d.thickness, 22.3);
        assert_eq!(d.bolt_circle_diameter, 190.5);
        assert_eq!(d.bolt_count, 8);
        assert!((d.bolt_hole_diameter - 19.05).abs() < 1e-9);
        assert_eq!(d.bolt_size_in, 0.625);
        assert_eq!((d.hub_base_diameter, d.hub_weld_diameter), (135.0, 114.3));
        assert_eq!((d.weld_neck_length, d.slip_on_length), (75.0, 32.0));
        assert_eq!(d.raised_face_diameter, 157.2);
        // Overall thickness with the 2 mm raised face; in inches 0.88 + 0.06 =
        // 0.94, the value pre-2003 editions printed as C.
        assert!((d.thickness + raised_face_height(FlangeClass::C150) - 24.3).abs() < 1e-9);

        // Class 300 NPS 6 (O is 12.5 in = 317.5 mm, printed as 320).
        let d = get(6.0, FlangeClass::C300);
        assert_eq!(d.outside_diameter, 320.0);
        assert_eq!(d.thickness, 35.0);
        assert_eq!(d.bolt_circle_diameter, 269.9);
        assert_eq!((d.bolt_count, d.bolt_size_in), (12, 0.75));

        // Class 150 NPS 2: O 150, W 120.7, 4 x 5/8" bolts.
        let d = get(2.0, FlangeClass::C150);
        assert_eq!((d.outside_diameter, d.bolt_circle_diameter), (150.0, 120.7));
        assert_eq!((d.bolt_count, d.bolt_size_in), (4, 0.625));

        // Class 600 NPS 4: O 275, tf 38.1, W 215.9, 8 x 7/8" bolts, Y(WN) 102.
        let d = get(4.0, FlangeClass::C600);
        assert_eq!((d.outside_diameter, d.thickness), (275.0, 38.1));
        assert_eq!((d.bolt_circle_diameter, d.bolt_count), (215.9, 8));
        assert_eq!((d.bolt_size_in, d.weld_neck_length), (0.875, 102.0));

        // Class 900 NPS 24: O 1040, tf 139.7, W 901.7, 20 x 2-1/2" bolts.
        let d = get(24.0, FlangeClass::C900);
        assert_eq!((d.outside_diameter, d.thickness), (1040.0, 139.7));
        assert_eq!((d.bolt_circle_diameter, d.bolt_count), (901.7, 20));
        assert_eq!(d.bolt_size_in, 2.5);

        // Class 300 NPS 24: 24 x 1-1/2" bolts on 812.8.
        let d = get(24.0, FlangeClass::C300);
        assert_eq!((d.bolt_circle_diameter, d.bolt_count), (812.8, 24));
        assert_eq!(d.bolt_size_in, 1.5);
    }

    #[test]
    fn raised_face_heights() {
        assert_eq!(raised_face_height(FlangeClass::C150), 2.0);
        assert_eq!(raised_face_height(FlangeClass::C300), 2.0);
        assert_eq!(raised_face_height(FlangeClass::C600), 7.0);
        assert_eq!(raised_face_height(FlangeClass::C900), 7.0);
    }
}
