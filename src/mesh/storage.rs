//! Storage precision: the chordal tolerance holds in the file, not only in the
//! model. The model keeps exact `f64` positions; glTF stores `f32` metres, whose
//! rounding moves each coordinate by up to half a unit in the last place — on a
//! 50 m tank's course (coordinates up to 25 m) about 0.001 mm per coordinate,
//! which took 23 % of a course's triangles to 1.006× the tolerance at 0.1 mm.
//!
//! Every point of a stored triangle is the same convex combination of its
//! rounded vertices as the exact point is of the exact ones, so it lies within
//! the vertices' largest rounding `δ` of it: a mesh made within `t − δ` is
//! stored within `t`. `δ` depends on the largest coordinate magnitude in a part's
//! frame, and only through its binade (a power of two in metres). The budget is
//! taken for at least [`STORAGE_FLOOR_EXTENT`] (the binade of 16–32 m, 0.00165
//! mm), so that a vessel's meshes do not depend on the other vessels of its plant
//! unless some part reaches beyond 32 m: [`storage_options`] changes the options
//! only when the largest part of such a plant crosses a power of two — then every
//! patch is meshed again. The extent is taken
//! over the patches' control points (a NURBS surface lies in their convex hull),
//! in their parts' frames, over every patch of every part and nozzle (pads lie on
//! their hosts, inside the hosts' extents).

use super::options::MIN_TOLERANCE;
pub use super::options::STORAGE_FLOOR_EXTENT;
use super::{OptionsError, TessellationOptions};
use crate::parts::Patch;

/// Millimetres per metre: glTF positions are metres.
const MM_PER_M: f64 = 1e3;

/// The largest distance, mm, that storing a point as `f32` metres moves it,
/// for a point whose coordinates are all at most `extent` mm in magnitude:
/// `√3` times half the `f32` spacing at the largest coordinate (the mm → m
/// product, in `f64`, adds rounding far below it, covered by a factor).
pub fn f32_rounding_bound(extent: f64) -> f64 {
    let metres = extent.abs() / MM_PER_M;
    if !(metres.is_finite() && metres > 0.0) {
        return 0.0;
    }
    // The binade [2^k, 2^(k+1)) of the largest coordinate; half an f32 ulp there
    // is 2^(k − 24).
    let mut k = metres.log2().floor();
    if 2f64.powf(k + 1.0) <= metres {
        k += 1.0;
    }
    let half_ulp = 2f64.powf(k - 24.0);
    3f64.sqrt() * half_ulp * MM_PER_M * (1.0 + 1e-9)
}

/// `options` with the tolerance less the `f32` rounding bound of parts whose
/// coordinates reach `extent` mm, so that the stored mesh holds
/// `options.tolerance`. When the rounding takes half the tolerance or more
/// (a tolerance of hundredths of a millimetre on parts tens of metres across),
/// `f32` cannot hold it: the mesh is then made to half the tolerance and the
/// file holds `t/2 + δ`.
pub fn storage_options(options: &TessellationOptions, extent: f64) -> TessellationOptions {
    let rounding = f32_rounding_bound(extent.max(STORAGE_FLOOR_EXTENT));
    let tolerance = if rounding < 0.5 * options.tolerance {
        options.tolerance - rounding
    } else {
        0.5 * options.tolerance
    };
    TessellationOptions {
        tolerance,
        ..*options
    }
}

/// The smallest tolerance whose [`storage_options`] for parts reaching
/// `extent` mm the mesher takes (at least `MIN_TOLERANCE`): twice the floor
/// wherever the rounding is at least the floor — for every design, since the
/// rounding is budgeted for `STORAGE_FLOOR_EXTENT` at least — as the
/// patches are then meshed to half the tolerance.
pub fn smallest_storable_tolerance(extent: f64) -> f64 {
    let rounding = f32_rounding_bound(extent.max(STORAGE_FLOOR_EXTENT));
    let mut smallest = if rounding >= MIN_TOLERANCE {
        2.0 * MIN_TOLERANCE
    } else {
        MIN_TOLERANCE + rounding
    };
    // `t − δ` may round below the floor at `floor + δ`.
    while storage_options(&TessellationOptions::chord(smallest), extent).tolerance < MIN_TOLERANCE {
        smallest = smallest.next_up();
    }
    smallest
}

/// Checks that `options`' tolerance, less the `f32` rounding of parts reaching
/// `extent` mm (`None`: the design is not known yet; the check is the same for
/// every design up to 32 m, and larger ones differ only in the rounding
/// named), is one the mesher takes: an error up front instead of one failure
/// per patch.
///
/// # Errors
///
/// [`OptionsError::BelowStorageFloor`] naming the tolerance, the extent, the
/// rounding and the smallest tolerance allowed.
pub fn check_storable(
    options: &TessellationOptions,
    extent: Option<f64>,
) -> Result<(), OptionsError> {
    let at = extent.unwrap_or(0.0);
    let meshed = storage_options(options, at).tolerance;
    // NaN and out-of-range tolerances are `validate`'s to name.
    if !(meshed < MIN_TOLERANCE && options.tolerance >= MIN_TOLERANCE) {
        return Ok(());
    }
    Err(OptionsError::BelowStorageFloor {
        tolerance: options.tolerance,
        extent,
        rounding: f32_rounding_bound(at.max(STORAGE_FLOOR_EXTENT)),
        meshed,
        smallest: smallest_storable_tolerance(at),
    })
}

/// The largest coordinate magnitude, mm, of any point of `patch`'s surface in
/// its part's frame (from its control points).
pub fn patch_extent(patch: &Patch) -> f64 {
    patch
        .surface
        .homogeneous_points()
        .iter()
        .map(|p| (p.truncate() / p.w).abs().max_element())
        .fold(0.0, f64::max)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The bound covers the real rounding of coordinates across binades.
    #[test]
    fn the_bound_covers_f32_rounding() {
        for extent in [
            0.7, 1.0, 999.0, 1000.0, 1024.0, 25_000.0, 32_768.0, 40_000.0,
        ] {
            let bound = f32_rounding_bound(extent);
            let mut worst: f64 = 0.0;
            for i in 0..2000 {
                let c = extent * (i as f64 / 1999.0);
                let stored = f64::from((c / MM_PER_M) as f32) * MM_PER_M;
                worst = worst.max((stored - c).abs());
            }
            assert!(3f64.sqrt() * worst <= bound, "{extent}: {worst} > {bound}");
            assert!(
                3f64.sqrt() * worst >= 0.4 * bound,
                "{extent}: {worst} ≪ {bound}"
            );
        }
        assert_eq!(f32_rounding_bound(0.0), 0.0);
    }

    #[test]
    fn the_tolerance_is_budgeted_and_never_gives_out() {
        let options = TessellationOptions::chord(0.1);
        let stored = storage_options(&options, 25_000.0);
        let rounding = f32_rounding_bound(25_000.0);
        assert!((stored.tolerance + rounding - 0.1).abs() < 1e-15);
        assert!(rounding > 0.001 && rounding < 0.002, "{rounding}");
        let fine = storage_options(&TessellationOptions::chord(1e-4), 25_000.0);
        assert_eq!(fine.tolerance, 0.5e-4);
        assert_eq!(fine.angle_tolerance, options.angle_tolerance);
        // A small vessel's budget is the floor's: the same as in a plant of
        // parts up to 32 m.
        assert_eq!(
            storage_options(&options, 800.0),
            storage_options(&options, 31_000.0)
        );
        assert!(storage_options(&options, 40_000.0).tolerance < stored.tolerance);
    }

    /// The smallest storable tolerance is the first the mesher takes once the
    /// rounding is taken off, at every size; below it the check names it.
    #[test]
    fn the_storage_floor_is_the_first_tolerance_the_mesher_takes() {
        for extent in [0.0, 800.0, 16_000.0, 31_000.0, 50_000.0, 1e6] {
            let smallest = smallest_storable_tolerance(extent);
            assert_eq!(smallest, 2.0 * MIN_TOLERANCE, "{extent}");
            let at = |t: f64| storage_options(&TessellationOptions::chord(t), extent);
            assert!(at(smallest).validate().is_ok(), "{extent}");
            assert!(at(smallest.next_down()).validate().is_err(), "{extent}");
            assert_eq!(
                check_storable(&TessellationOptions::chord(smallest), Some(extent)),
                Ok(())
            );
            let Err(OptionsError::BelowStorageFloor {
                tolerance,
                extent: named,
                meshed,
                smallest: named_smallest,
                ..
            }) = check_storable(&TessellationOptions::chord(1e-6), Some(extent))
            else {
                panic!("1e-6 mm is below the storage floor at {extent} mm");
            };
            assert_eq!((tolerance, named, meshed), (1e-6, Some(extent), 0.5e-6));
            assert_eq!(named_smallest, smallest);
        }
        // Invalid tolerances are `validate`'s to name.
        for t in [f64::NAN, 0.0, -1.0, 1e-7] {
            assert_eq!(check_storable(&TessellationOptions::chord(t), None), Ok(()));
        }
    }
}
