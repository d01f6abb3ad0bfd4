//! Planar patches: disks and annuli (revolved segments) and bilinear quads.

use std::f64::consts::TAU;

use glam::DVec3;

use super::{direction, finite_vec, line, positive, revolve};
use crate::nurbs::{KnotVector, NurbsError, NurbsSurface};

/// The disk of `radius` about `center` whose outward normal is `normal`. The profile
/// runs from the rim to the centre, so the centre is a pole at v = 1.
pub fn disk(center: DVec3, normal: DVec3, radius: f64) -> Result<NurbsSurface, NurbsError> {
    let c = finite_vec("disk centre", center)?;
    let n = direction("disk normal", normal)?;
    let r = positive("disk radius", radius)?;
    let x = n.any_orthonormal_vector();
    let profile = line(c + x * r, c)?;
    revolve(&profile, c, n, TAU)
}

/// The annulus between `inner` and `outer` radii about `center`, outward normal
/// `normal`. The profile runs from the outer to the inner rim.
pub fn annulus(
    center: DVec3,
    normal: DVec3,
    inner: f64,
    outer: f64,
) -> Result<NurbsSurface, NurbsError> {
    let c = finite_vec("annulus centre", center)?;
    let n = direction("annulus normal", normal)?;
    let ri = positive("annulus inner radius", inner)?;
    let ro = positive("annulus outer radius", outer)?;
    if ri >= ro {
        return Err(NurbsError::InvalidGeometry {
            what: "annulus inner radius",
            value: ri,
            rule: "must be smaller than the outer radius",
        });
    }
    let x = n.any_orthonormal_vector();
    let profile = line(c + x * ro, c + x * ri)?;
    revolve(&profile, c, n, TAU)
}

/// The bilinear patch with corners `p00` (u=0,v=0), `p10` (u=1,v=0), `p01`, `p11`.
/// Planar when the four corners are; its normal is `(p10 − p00) × (p01 − p00)`.
pub fn planar_quad(
    p00: DVec3,
    p10: DVec3,
    p01: DVec3,
    p11: DVec3,
) -> Result<NurbsSurface, NurbsError> {
    let pts = [
        finite_vec("quad corner", p00)?,
        finite_vec("quad corner", p01)?,
        finite_vec("quad corner", p10)?,
        finite_vec("quad corner", p11)?,
    ];
    let k = KnotVector::new(1, vec![0.0, 0.0, 1.0, 1.0]);
    NurbsSurface::try_new(k.clone(), k, pts.iter().map(|p| p.extend(1.0)).collect())
}
