//! The exact curves of the welds round openings: where a nozzle's (or boot's)
//! neck meets its host's outside surface and where a pad's outside edge does,
//! marched by the same routine the cutter uses (`mesh::cut_opening`), here to
//! [`WELD_TOLERANCE`].
//!
//! A weld's length is the length of the sampled loop with each chord taken as
//! the circular arc of the curvature at its ends ([`closed_length`]). The
//! marcher bounds the true curve's distance from every chord by the tolerance
//! (sagitta s); a bare chord c is short of its arc by about 8s²/(3c), 2.4e-6 of
//! a NPS 8 nozzle's loop at 1 µm, which the arc correction removes
//! (`tests/fab_process.rs` holds a radial nozzle's weld and its pad's to the
//! integral of their intersection curves within 1e-8).

use glam::{DAffine3, DVec3};

use crate::constraints::ResolvedVessel;
use crate::mesh::cut_opening;
use crate::parts::Patch;

/// Chordal tolerance of the weld curves, mm.
pub const WELD_TOLERANCE: f64 = 1e-3;

/// The loops of one opening, vessel frame.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct OpeningCurves {
    /// Neck outside surface ∩ host outside surface.
    pub neck: Vec<DVec3>,
    /// Pad outside edge ∩ host outside surface.
    pub pad: Option<Vec<DVec3>>,
}

/// Curvature of the circle through three points (0 when collinear), 1/mm.
fn curvature(a: DVec3, b: DVec3, c: DVec3) -> f64 {
    let denominator = a.distance(b) * b.distance(c) * a.distance(c);
    if denominator <= 0.0 {
        return 0.0;
    }
    2.0 * (b - a).cross(c - a).length() / denominator
}

/// Length of the closed curve sampled by `points`, mm: each chord taken as the
/// circular arc of the curvature at its two ends (the circle through each
/// sample and its neighbours), `2/κ · asin(cκ/2)`, which removes the chord's
/// shortfall c³κ²/24 to leading order.
pub fn closed_length(points: &[DVec3]) -> f64 {
    let n = points.len();
    if n < 3 {
        return (0..n)
            .map(|i| points[i].distance(points[(i + 1) % n]))
            .sum();
    }
    let at = |i: usize| points[i % n];
    let kappa: Vec<f64> = (0..n)
        .map(|i| curvature(at(i + n - 1), at(i), at(i + 1)))
        .collect();
    (0..n)
        .map(|i| {
            let c = at(i).distance(at(i + 1));
            let k = 0.5 * (kappa[i] + kappa[(i + 1) % n]);
            let half = 0.5 * c * k;
            if half <= 1e-12 || half >= 1.0 {
                c
            } else {
                2.0 / k * half.asin()
            }
        })
        .sum()
}

/// Marches the loops of a neck (first patch of `neck_patches`, in `neck_frame`)
/// in the host part `host` of `vessel`.
fn cut(
    vessel: &ResolvedVessel,
    neck_patches: &[Patch],
    neck_frame: &DAffine3,
    host: usize,
    pad_od: Option<f64>,
) -> Result<OpeningCurves, String> {
    let host = vessel
        .parts
        .get(host)
        .ok_or_else(|| "host part missing".to_string())?;
    let host_patches = host.geometry.patches().map_err(|e| e.to_string())?;
    let hosts: Vec<&Patch> = host_patches.iter().collect();
    let neck = neck_patches
        .first()
        .ok_or_else(|| "no neck patch".to_string())?;
    let c = cut_opening(
        neck,
        pad_od,
        neck_frame,
        &host.frame,
        &hosts,
        WELD_TOLERANCE,
    )
    .map_err(|e| e.to_string())?;
    let to_vessel = |pts: &[DVec3]| -> Vec<DVec3> {
        pts.iter()
            .map(|p| host.frame.transform_point3(*p))
            .collect()
    };
    Ok(OpeningCurves {
        neck: to_vessel(&c.neck.points),
        pad: c.pad.as_ref().map(|l| to_vessel(&l.points)),
    })
}

/// The loops of nozzle `index` of `vessel`.
///
/// # Errors
///
/// Why the nozzle's patches cannot be built or its opening cut.
pub fn nozzle_curves(vessel: &ResolvedVessel, index: usize) -> Result<OpeningCurves, String> {
    let n = vessel
        .nozzles
        .get(index)
        .ok_or_else(|| "nozzle missing".to_string())?;
    let patches = n.geometry.patches().map_err(|e| e.to_string())?;
    cut(vessel, &patches, &n.frame, n.host, n.pad.map(|p| p.0))
}

/// The loop of a boot (part `index`, cut into its host course).
///
/// # Errors
///
/// Why the boot's patches cannot be built or its opening cut; a part that
/// is not cut into a host.
pub fn boot_curve(vessel: &ResolvedVessel, index: usize) -> Result<Vec<DVec3>, String> {
    let p = vessel
        .parts
        .get(index)
        .ok_or_else(|| "part missing".to_string())?;
    let host = p.host.ok_or_else(|| "not cut into a host".to_string())?;
    let patches = p.geometry.patches().map_err(|e| e.to_string())?;
    cut(vessel, &patches, &p.frame, host, None).map(|c| c.neck)
}
