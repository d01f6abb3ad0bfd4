//! ASME B36.10M welded and seamless wrought steel pipe: the outside diameter
//! and the nominal wall thickness of each schedule the nozzle builder offers,
//! for the twenty nominal pipe sizes NPS 1/2 through 24 that the B16.5 flange
//! tables also cover. Values are the metric (mm) columns of B36.10M Table 1;
//! a schedule B36.10M does not list for a size is `None` in the data and a
//! [`TableError::ScheduleNotListed`] from [`PipeDimensions::wall`]. This file
//! also holds [`Nps`], the validated size key, and [`TableError`], the error
//! type shared by every lookup in `parts::tables`.

use std::fmt;

/// Every size the tables cover, in the order of [`Nps::ALL`], spelled the way
/// ASME prints it.
const SIZE_LABELS: [&str; 20] = [
    "1/2", "3/4", "1", "1-1/4", "1-1/2", "2", "2-1/2", "3", "3-1/2", "4", "5", "6", "8", "10",
    "12", "14", "16", "18", "20", "24",
];

/// The list of sizes quoted in [`TableError::UnknownNps`] messages.
const SIZE_LIST: &str = "1/2, 3/4, 1, 1-1/4, 1-1/2, 2, 2-1/2, 3, 3-1/2, 4, 5, 6, 8, 10, 12, 14, \
                         16, 18, 20, 24";

/// How far (in inches) a requested size may sit from a table size and still
/// be taken as that size; it only absorbs floating-point noise.
const NPS_TOLERANCE: f64 = 1e-6;

/// Nominal pipe size in inches, e.g. 0.5, 2.0, 24.0 — validated against the table.
///
/// An `Nps` always holds one of the twenty sizes in [`Nps::ALL`], so the pipe
/// lookup [`pipe`] cannot fail and the flange lookup only fails for
/// size/class combinations ASME B16.5 does not list.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Nps(f64);

impl Nps {
    /// Every size the tables cover, smallest first: NPS 1/2, 3/4, 1, 1-1/4,
    /// 1-1/2, 2, 2-1/2, 3, 3-1/2, 4, 5, 6, 8, 10, 12, 14, 16, 18, 20 and 24.
    pub const ALL: [Nps; 20] = [
        Nps(0.5),
        Nps(0.75),
        Nps(1.0),
        Nps(1.25),
        Nps(1.5),
        Nps(2.0),
        Nps(2.5),
        Nps(3.0),
        Nps(3.5),
        Nps(4.0),
        Nps(5.0),
        Nps(6.0),
        Nps(8.0),
        Nps(10.0),
        Nps(12.0),
        Nps(14.0),
        Nps(16.0),
        Nps(18.0),
        Nps(20.0),
        Nps(24.0),
    ];

    /// Validates a nominal size given in inches (1-1/2 is `1.5`).
    ///
    /// # Errors
    ///
    /// [`TableError::UnknownNps`] for any value that is not one of
    /// [`Nps::ALL`], including NaN and infinities.
    pub fn try_new(inches: f64) -> Result<Nps, TableError> {
        Nps::ALL
            .iter()
            .copied()
            .find(|nps| (nps.0 - inches).abs() <= NPS_TOLERANCE)
            .ok_or(TableError::UnknownNps { inches })
    }

    /// The nominal size in inches, exactly as listed in [`Nps::ALL`].
    pub fn inches(self) -> f64 {
        self.0
    }

    /// Iterates over [`Nps::ALL`], smallest size first.
    pub fn all() -> impl Iterator<Item = Nps> {
        Nps::ALL.into_iter()
    }

    /// The size as ASME prints it, e.g. `"1-1/2"`.
    pub fn label(self) -> &'static str {
        SIZE_LABELS[self.index()]
    }

    /// Position of this size in [`Nps::ALL`] (and in every table ordered like it).
    fn index(self) -> usize {
        Nps::ALL
            .iter()
            .position(|nps| nps.0 == self.0)
            .expect("an Nps can only be built from a value of Nps::ALL")
    }
}

impl fmt::Display for Nps {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "NPS {}", self.label())
    }
}

/// Spells a size in inches the way ASME does when it is a table size, and as
/// a plain number otherwise.
fn nps_label(inches: f64) -> String {
    Nps::try_new(inches).map_or_else(|_| inches.to_string(), |nps| nps.label().to_owned())
}

/// A wall-thickness designation of ASME B36.10M.
///
/// `Std` (standard weight), `Xs` (extra strong) and `Xxs` (double extra
/// strong) are the traditional weight classes; `S40`, `S80` and `S160` are
/// schedule numbers. They coincide for small sizes (STD = 40 through NPS 10,
/// XS = 80 through NPS 8) and part ways above.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum PipeSchedule {
    /// Standard weight (STD).
    Std,
    /// Extra strong (XS).
    Xs,
    /// Schedule 40.
    S40,
    /// Schedule 80.
    S80,
    /// Schedule 160.
    S160,
    /// Double extra strong (XXS).
    Xxs,
}

impl PipeSchedule {
    /// Every schedule the pipe table carries.
    pub const ALL: [PipeSchedule; 6] = [
        PipeSchedule::Std,
        PipeSchedule::Xs,
        PipeSchedule::S40,
        PipeSchedule::S80,
        PipeSchedule::S160,
        PipeSchedule::Xxs,
    ];

    /// The designation as B36.10M prints it: `STD`, `XS`, `40`, `80`, `160`, `XXS`.
    pub fn label(self) -> &'static str {
        match self {
            PipeSchedule::Std => "STD",
            PipeSchedule::Xs => "XS",
            PipeSchedule::S40 => "40",
            PipeSchedule::S80 => "80",
            PipeSchedule::S160 => "160",
            PipeSchedule::Xxs => "XXS",
        }
    }
}

impl fmt::Display for PipeSchedule {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.label())
    }
}

/// Why a table lookup failed. Every message names the offending value and the
/// rule of the standard it breaks.
#[derive(Debug, thiserror::Error, Clone, PartialEq)]
pub enum TableError {
    /// The size is not one of the twenty nominal pipe sizes the tables cover
    /// (also returned for NaN and infinite input).
    #[error("NPS {inches} is not a standard size; expected one of {list}", list = SIZE_LIST)]
    UnknownNps {
        /// The rejected size in inches.
        inches: f64,
    },
    /// The pressure rating is not one of the flange classes the tables cover.
    #[error("Class {rating} is not a supported flange rating; expected 150, 300, 600 or 900")]
    UnknownRating {
        /// The rejected rating.
        rating: u32,
    },
    /// ASME B36.10M lists no wall thickness for this schedule at this size.
    #[error(
        "ASME B36.10M lists no schedule {schedule} wall for NPS {nps} (it lists neither \
         schedule 160 nor XXS for NPS 3-1/2, and no XXS above NPS 12)",
        nps = nps_label(*.nps_inches)
    )]
    ScheduleNotListed {
        /// The size, in inches.
        nps_inches: f64,
        /// The schedule that is missing.
        schedule: PipeSchedule,
    },
    /// ASME B16.5 lists no flange of this class at this size.
    #[error(
        "ASME B16.5 lists no Class {class} flange for NPS {nps} (NPS 3-1/2 flanges are \
         listed only up to Class 600)",
        nps = nps_label(*.nps_inches)
    )]
    FlangeNotListed {
        /// The size, in inches.
        nps_inches: f64,
        /// The pressure class rating, e.g. 900.
        class: u32,
    },
}

/// Outside diameter and nominal wall thicknesses of one pipe size, in mm,
/// per ASME B36.10M. A `None` wall means B36.10M lists no pipe of that
/// schedule at this size.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PipeDimensions {
    /// The nominal size this row describes.
    pub nps: Nps,
    /// Outside diameter, mm (also dimension A of a B16.5 weld-neck flange).
    pub outside_diameter: f64,
    /// Standard-weight (STD) wall, mm.
    pub std: Option<f64>,
    /// Extra-strong (XS) wall, mm.
    pub xs: Option<f64>,
    /// Schedule 40 wall, mm.
    pub sch40: Option<f64>,
    /// Schedule 80 wall, mm.
    pub sch80: Option<f64>,
    /// Schedule 160 wall, mm.
    pub sch160: Option<f64>,
    /// Double-extra-strong (XXS) wall, mm.
    pub xxs: Option<f64>,
}

impl PipeDimensions {
    /// Nominal wall thickness in mm for `schedule`.
    ///
    /// # Errors
    ///
    /// [`TableError::ScheduleNotListed`] where B36.10M lists no wall for
    /// `schedule` at this size.
    pub fn wall(&self, schedule: PipeSchedule) -> Result<f64, TableError> {
        let wall = match schedule {
            PipeSchedule::Std => self.std,
            PipeSchedule::Xs => self.xs,
            PipeSchedule::S40 => self.sch40,
            PipeSchedule::S80 => self.sch80,
            PipeSchedule::S160 => self.sch160,
            PipeSchedule::Xxs => self.xxs,
        };
        wall.ok_or(TableError::ScheduleNotListed {
            nps_inches: self.nps.inches(),
            schedule,
        })
    }
}

/// The B36.10M row for `nps`. Every [`Nps`] has one.
pub fn pipe(nps: Nps) -> &'static PipeDimensions {
    &PIPES[nps.index()]
}

/// Builds one row; the walls are STD, XS, 40, 80, 160, XXS in that order.
const fn row(nps: Nps, outside_diameter: f64, walls: [Option<f64>; 6]) -> PipeDimensions {
    let [std, xs, sch40, sch80, sch160, xxs] = walls;
    PipeDimensions {
        nps,
        outside_diameter,
        std,
        xs,
        sch40,
        sch80,
        sch160,
        xxs,
    }
}

/// ASME B36.10M Table 1 (metric columns), in the order of [`Nps::ALL`].
#[rustfmt::skip]
static PIPES: [PipeDimensions; 20] = [
    //                      OD       STD          XS           40           80           160          XXS
    row(Nps(0.5),   21.3,  [Some(2.77), Some(3.73),  Some(2.77),  Some(3.73),  Some(4.78),  Some(7.47)]),
    row(Nps(0.75),  26.7,  [Some(2.87), Some(3.91),  Some(2.87),  Some(3.91),  Some(5.56),  Some(7.82)]),
    row(Nps(1.0),   33.4,  [Some(3.38), Some(4.55),  Some(3.38),  Some(4.55),  Some(6.35),  Some(9.09)]),
    row(Nps(1.25),  42.2,  [Some(3.56), Some(4.85),  Some(3.56),  Some(4.85),  Some(6.35),  Some(9.70)]),
    row(Nps(1.5),   48.3,  [Some(3.68), Some(5.08),  Some(3.68),  Some(5.08),  Some(7.14),  Some(10.15)]),
    row(Nps(2.0),   60.3,  [Some(3.91), Some(5.54),  Some(3.91),  Some(5.54),  Some(8.74),  Some(11.07)]),
    row(Nps(2.5),   73.0,  [Some(5.16), Some(7.01),  Some(5.16),  Some(7.01),  Some(9.53),  Some(14.02)]),
    row(Nps(3.0),   88.9,  [Some(5.49), Some(7.62),  Some(5.49),  Some(7.62),  Some(11.13), Some(15.24)]),
    row(Nps(3.5),   101.6, [Some(5.74), Some(8.08),  Some(5.74),  Some(8.08),  None,        None]),
    row(Nps(4.0),   114.3, [Some(6.02), Some(8.56),  Some(6.02),  Some(8.56),  Some(13.49), Some(17.12)]),
    row(Nps(5.0),   141.3, [Some(6.55), Some(9.53),  Some(6.55),  Some(9.53),  Some(15.88), Some(19.05)]),
    row(Nps(6.0),   168.3, [Some(7.11), Some(10.97), Some(7.11),  Some(10.97), Some(18.26), Some(21.95)]),
    row(Nps(8.0),   219.1, [Some(8.18), Some(12.70), Some(8.18),  Some(12.70), Some(23.01), Some(22.23)]),
    row(Nps(10.0),  273.0, [Some(9.27), Some(12.70), Some(9.27),  Some(15.09), Some(28.58), Some(25.40)]),
    row(Nps(12.0),  323.8, [Some(9.53), Some(12.70), Some(10.31), Some(17.48), Some(33.32), Some(25.40)]),
    row(Nps(14.0),  355.6, [Some(9.53), Some(12.70), Some(11.13), Some(19.05), Some(35.71), None]),
    row(Nps(16.0),  406.4, [Some(9.53), Some(12.70), Some(12.70), Some(21.44), Some(40.49), None]),
    row(Nps(18.0),  457.0, [Some(9.53), Some(12.70), Some(14.27), Some(23.83), Some(45.24), None]),
    row(Nps(20.0),  508.0, [Some(9.53), Some(12.70), Some(15.09), Some(26.19), Some(50.01), None]),
    row(Nps(24.0),  610.0, [Some(9.53), Some(12.70), Some(17.48), Some(30.96), Some(59.54), None]),
];

#[cfg(test)]
mod tests {
    use super::*;

    fn nps(inches: f64) -> Nps {
        Nps::try_new(inches).expect("test size is a table size")
    }

    #[test]
    fn every_size_round_trips_and_has_its_own_row() {
        assert_eq!(Nps::all().count(), 20);
        for (i, size) in Nps::all().enumerate() {
            assert_eq!(Nps::try_new(size.inches()), Ok(size));
            assert_eq!(pipe(size).nps, size, "row {i} is out of order");
            assert_eq!(size.label(), SIZE_LABELS[i]);
        }
        assert_eq!(nps(1.5).to_string(), "NPS 1-1/2");
        assert_eq!(nps(1.5 + 1e-9), nps(1.5));
    }

    #[test]
    fn unknown_sizes_are_rejected_without_panicking() {
        for bad in [
            2.2,
            0.0,
            -2.0,
            7.0,
            22.0,
            26.0,
            f64::NAN,
            f64::INFINITY,
            f64::NEG_INFINITY,
        ] {
            match Nps::try_new(bad) {
                Err(TableError::UnknownNps { inches }) => {
                    assert!(inches == bad || (inches.is_nan() && bad.is_nan()));
                }
                other => panic!("NPS {bad} should be unknown, got {other:?}"),
            }
        }
        let message = Nps::try_new(2.2).unwrap_err().to_string();
        assert!(message.starts_with("NPS 2.2 is not a standard size; expected one of 1/2, 3/4"));
        assert!(message.ends_with("20, 24"));
        assert!(
            Nps::try_new(f64::NAN)
                .unwrap_err()
                .to_string()
                .contains("NaN")
        );
    }

    #[test]
    fn outside_diameter_grows_with_size_and_walls_are_ordered() {
        for pair in PIPES.windows(2) {
            assert!(pair[0].nps.inches() < pair[1].nps.inches());
            assert!(pair[0].outside_diameter < pair[1].outside_diameter);
        }
        for p in &PIPES {
            let w = |s| p.wall(s).ok();
            let std = w(PipeSchedule::Std).expect("STD exists for every size");
            let xs = w(PipeSchedule::Xs).expect("XS exists for every size");
            let s40 = w(PipeSchedule::S40).expect("40 exists for every size");
            let s80 = w(PipeSchedule::S80).expect("80 exists for every size");
            assert!(std < xs, "{}: STD < XS", p.nps);
            assert!(std <= s40 && xs <= s80, "{}: weights vs schedules", p.nps);
            assert!(s40 < s80, "{}: 40 < 80", p.nps);
            if let Some(s160) = w(PipeSchedule::S160) {
                assert!(s80 < s160, "{}: 80 < 160", p.nps);
            }
            if let Some(xxs) = w(PipeSchedule::Xxs) {
                assert!(xs < xxs, "{}: XS < XXS", p.nps);
            }
            // Small sizes: STD is 40 and XS is 80. Large sizes: STD is a flat 3/8".
            if p.nps.inches() <= 8.0 {
                assert_eq!((std, xs), (s40, s80), "{}", p.nps);
            }
            if p.nps.inches() >= 12.0 {
                assert_eq!((std, xs), (9.53, 12.70), "{}", p.nps);
            }
            for s in PipeSchedule::ALL {
                if let Ok(t) = p.wall(s) {
                    // The bore is never less than a quarter of the OD (XXS NPS 1/2 is the extreme).
                    assert!(
                        t > 0.0 && 2.0 * t < 0.75 * p.outside_diameter,
                        "{} {s}",
                        p.nps
                    );
                }
            }
        }
    }

    #[test]
    fn well_known_values() {
        assert_eq!(pipe(nps(2.0)).outside_diameter, 60.3);
        assert_eq!(pipe(nps(24.0)).outside_diameter, 610.0);
        assert_eq!(pipe(nps(4.0)).outside_diameter, 114.3);
        assert_eq!(pipe(nps(2.0)).wall(PipeSchedule::S40), Ok(3.91));
        assert_eq!(pipe(nps(4.0)).wall(PipeSchedule::S80), Ok(8.56));
        assert_eq!(pipe(nps(6.0)).wall(PipeSchedule::Std), Ok(7.11));
        assert_eq!(pipe(nps(12.0)).wall(PipeSchedule::S40), Ok(10.31));
        // From NPS 8 up, XXS is thinner than schedule 160.
        assert_eq!(pipe(nps(8.0)).wall(PipeSchedule::Xxs), Ok(22.23));
        assert_eq!(pipe(nps(8.0)).wall(PipeSchedule::S160), Ok(23.01));
    }

    #[test]
    fn missing_schedules_are_typed_errors() {
        let err = pipe(nps(3.5)).wall(PipeSchedule::S160).unwrap_err();
        assert_eq!(
            err,
            TableError::ScheduleNotListed {
                nps_inches: 3.5,
                schedule: PipeSchedule::S160
            }
        );
        let message = err.to_string();
        assert!(message.contains("schedule 160") && message.contains("NPS 3-1/2"));
        let err = pipe(nps(14.0)).wall(PipeSchedule::Xxs).unwrap_err();
        assert!(err.to_string().contains("schedule XXS wall for NPS 14"));
        let missing: Vec<_> = Nps::all()
            .flat_map(|n| PipeSchedule::ALL.map(|s| (n, s)))
            .filter(|&(n, s)| pipe(n).wall(s).is_err())
            .map(|(n, s)| (n.inches(), s))
            .collect();
        let mut expected = vec![(3.5, PipeSchedule::S160), (3.5, PipeSchedule::Xxs)];
        expected.extend([14.0, 16.0, 18.0, 20.0, 24.0].map(|n| (n, PipeSchedule::Xxs)));
        assert_eq!(missing, expected);
    }
}
