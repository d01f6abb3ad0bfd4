//! The ranges of head shape parameters that the geometry is built and tested
//! over, as rules.
//!
//! The parts accept any head whose profile exists (an ellipsoidal ratio from 0.1
//! to 100 — 7.75 already fails to mesh —, a knuckle of a thousandth of a millimetre, a knuckle leaving a torus of
//! 0.1 mm major radius), but such heads cannot be meshed within the vertex
//! budget, or not quickly: the design rules hold a head to the ranges below,
//! which real heads fall well inside (2:1 ellipsoidal, ASME F&D with a knuckle
//! of 6 % of the crown, flanged flat heads with a knuckle of a few plate
//! thicknesses), and which `tests/design_fuzz.rs` and `mesh_watertight.rs`
//! build at their ends on every head kind.

use super::Report;
use crate::parts::heads::HeadKind;

/// The smallest and largest ellipsoidal ratio (D / 2h).
pub(crate) const RATIO: (f64, f64) = (1.0, 3.0);
/// The smallest knuckle radius, as a fraction of the outside diameter.
pub(crate) const MIN_KNUCKLE: f64 = 0.01;
/// The largest knuckle radius, as a fraction of the outside diameter (the
/// torus's major radius D/2 − r stays at least a tenth of D).
pub(crate) const MAX_KNUCKLE: f64 = 0.4;
/// The largest crown radius of a torispherical head, as a multiple of the
/// outside diameter.
pub(crate) const MAX_CROWN: f64 = 3.0;

/// Records every shape parameter of `kind` (a head on outside diameter `od`,
/// at `path`) outside its range.
pub(crate) fn check(kind: &HeadKind, od: f64, path: &str, id: &str, report: &mut Report) {
    let knuckle = |r: f64, zero_allowed: bool, report: &mut Report| {
        let (lo, hi) = (MIN_KNUCKLE * od, MAX_KNUCKLE * od);
        if (zero_allowed && r == 0.0) || (lo..=hi).contains(&r) {
            return;
        }
        let none = if zero_allowed {
            "0 (no knuckle) or "
        } else {
            ""
        };
        report.push(
            format!("{path}.knuckle_radius"),
            Some(id),
            "knuckle_radius",
            r,
            format!(
                "must be {none}between {} % and {} % of the outside diameter {od} ({lo} to {hi} mm): \
                 the range the head's geometry is built and tested over",
                MIN_KNUCKLE * 100.0,
                MAX_KNUCKLE * 100.0
            ),
        );
    };
    match *kind {
        HeadKind::Ellipsoidal { ratio } if !(RATIO.0..=RATIO.1).contains(&ratio) => report.push(
            format!("{path}.ratio"),
            Some(id),
            "ratio",
            ratio,
            format!(
                "must be between {} and {} (2 for a 2:1 head): the range the head's geometry \
                 is built and tested over",
                RATIO.0, RATIO.1
            ),
        ),
        HeadKind::Torispherical {
            crown_radius,
            knuckle_radius,
        } => {
            if crown_radius > MAX_CROWN * od {
                report.push(
                    format!("{path}.crown_radius"),
                    Some(id),
                    "crown_radius",
                    crown_radius,
                    format!(
                        "must be at most {MAX_CROWN} × the outside diameter {od} ({} mm): \
                         the range the head's geometry is built and tested over",
                        MAX_CROWN * od
                    ),
                );
            }
            knuckle(knuckle_radius, false, report);
        }
        HeadKind::Toriconical { knuckle_radius, .. } => knuckle(knuckle_radius, false, report),
        HeadKind::Flat { knuckle_radius } => knuckle(knuckle_radius, true, report),
        _ => {}
    }
}
