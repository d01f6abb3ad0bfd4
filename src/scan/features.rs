//! The scan's asymmetric features, for the turn about the vessel's axis.
//!
//! Courses, heads and cones are bodies of revolution: every turn about the axis
//! fits them alike, and only what stands off them — nozzles, manways — tells the
//! turns apart. On a large vessel those are a fraction of a per cent of the
//! points: on the 6 m two-nozzle tank of `tests/scan_register` at 200
//! points/m², 53 of 21 773 (nozzle N1's; N2 is hidden), five in the even
//! 2000-point subsample the turns are first ranked on. So the points the
//! envelope does not explain are picked from the whole scan once, and the
//! turns are ranked on them as well.

use glam::{DAffine3, DVec3};
use rayon::prelude::*;

use super::envelope::Envelope;
use super::project::Targets;

/// Points examined for features (an even stride of the scan).
const EXAMINED: usize = 200_000;

/// Features kept (an even stride of those found).
const MAX_FEATURES: usize = 4_000;

/// Distance off the envelope past which a point is a feature, mm: past a
/// settled tank's tilt (tens of mm at its rim) and the envelope's fit.
const FEATURE_GAP: f64 = 60.0;

/// How far the nozzles stand out of the envelope's box, mm (half as much
/// again: a nozzle's reach along a box axis is shorter than along its own).
fn nozzle_reach(envelope: &Envelope) -> f64 {
    let boxes = |nozzles: bool| {
        envelope
            .surfaces
            .iter()
            .filter(|s| envelope.parts[s.part].role.is_envelope() != nozzles)
            .fold(
                (DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY)),
                |(lo, hi), s| (lo.min(s.bbox.min), hi.max(s.bbox.max)),
            )
    };
    let (lo, hi) = boxes(false);
    let (nlo, nhi) = boxes(true);
    if !(nlo.is_finite() && nhi.is_finite()) {
        return 0.0;
    }
    1.5 * (nhi - hi).max(lo - nlo).max_element().max(0.0)
}

/// The points of `points` (site frame) that lie at `pose` farther than
/// [`FEATURE_GAP`] from every course, head and cone but within `margin` and
/// the nozzles' reach of one, as an even stride of at most [`MAX_FEATURES`].
pub(super) fn off_envelope(
    envelope: &Envelope,
    points: &[DVec3],
    pose: DAffine3,
    margin: f64,
) -> Vec<DVec3> {
    let margin = margin + nozzle_reach(envelope);
    let step = points.len().div_ceil(EXAMINED).max(1);
    let found: Vec<DVec3> = points
        .par_iter()
        .step_by(step)
        .with_min_len(1024)
        .filter(|&&p| {
            envelope
                .project(pose.transform_point3(p), Targets::Envelope, margin)
                .is_some_and(|f| f.deviation.abs() > FEATURE_GAP)
        })
        .copied()
        .collect();
    let keep = found.len().div_ceil(MAX_FEATURES).max(1);
    found.into_iter().step_by(keep).collect()
}
