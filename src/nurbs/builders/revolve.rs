//! Surfaces of revolution (P&T A8.1): a profile curve swept about an axis.
//!
//! u runs along the circles (rational quadratic, segments ≤ 90°, the first circle
//! point is the profile itself), v along the profile. A profile point on the axis
//! gives a degenerate row of coincident control points: the pole of a head or the
//! apex of a cone. With a profile whose interior lies on its left in the (radial,
//! axial) half-plane, `S_u × S_v` points outward.

use std::f64::consts::{FRAC_PI_2, TAU};

use glam::{DVec3, DVec4};

use super::{direction, finite_vec};
use crate::nurbs::{KnotVector, NurbsCurve, NurbsError, NurbsSurface, euclidean, homogeneous};

/// Distance below which a profile control point counts as lying on the axis, relative
/// to the profile's size.
const ON_AXIS: f64 = 1e-14;

/// The u knots of a full turn (four quarter arcs), as [`revolve`] gives them for
/// an angle of 2π: what the meshers check before treating a curve or surface
/// as a full circle of turned quarters.
pub const FULL_TURN_KNOTS: [f64; 12] = [
    0.0, 0.0, 0.0, 0.25, 0.25, 0.5, 0.5, 0.75, 0.75, 1.0, 1.0, 1.0,
];

/// The surface swept by `profile` turning by `angle` radians (0 < |angle| ≤ 2π)
/// about the axis through `axis_point` along `axis_direction` (right-handed).
pub fn revolve(
    profile: &NurbsCurve,
    axis_point: DVec3,
    axis_direction: DVec3,
    angle: f64,
) -> Result<NurbsSurface, NurbsError> {
    let s = finite_vec("axis point", axis_point)?;
    let t = direction("axis direction", axis_direction)?;
    if !angle.is_finite() || angle == 0.0 || angle.abs() > TAU * (1.0 + 1e-12) {
        return Err(NurbsError::InvalidGeometry {
            what: "revolution angle",
            value: angle,
            rule: "must be non-zero and at most 2π",
        });
    }
    let segments = ((angle.abs() / FRAC_PI_2) - 1e-9).ceil().max(1.0) as usize;
    let delta = angle / segments as f64;
    let w_mid = (delta / 2.0).cos();
    let mut u_knots = vec![0.0; 3];
    for s in 1..segments {
        let k = s as f64 / segments as f64;
        u_knots.extend([k, k]);
    }
    u_knots.extend([1.0; 3]);
    let u_knots = KnotVector::try_new(2, u_knots)?;

    let profile_points = profile.homogeneous_points();
    let size = profile_points
        .iter()
        .map(|&p| (euclidean(p) - s).length())
        .fold(0.0, f64::max)
        .max(1.0);
    let nu = 2 * segments + 1;
    let nv = profile_points.len();
    let mut points = vec![DVec4::ZERO; nu * nv];
    for (j, &pw) in profile_points.iter().enumerate() {
        let p = euclidean(pw);
        let o = s + t * (p - s).dot(t);
        let radial = p - o;
        let r = radial.length();
        let (x, y) = if r > ON_AXIS * size {
            let x = radial / r;
            (x, t.cross(x))
        } else {
            (DVec3::ZERO, DVec3::ZERO)
        };
        for i in 0..nu {
            let theta = delta * (i / 2) as f64 + if i % 2 == 1 { delta / 2.0 } else { 0.0 };
            let (scale, wc) = if i % 2 == 1 {
                (1.0 / w_mid, w_mid)
            } else {
                (1.0, 1.0)
            };
            let q = if i == 0 {
                p
            } else {
                o + (x * theta.cos() + y * theta.sin()) * (r * scale)
            };
            points[i * nv + j] = homogeneous(q, wc * pw.w);
        }
    }
    NurbsSurface::try_new(u_knots, profile.knots().clone(), points)
}
