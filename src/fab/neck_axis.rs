//! The neck's axis and its cutting cylinder's crossing with a course
//! (a cylinder about the part's +Z), in surface coordinates: what the
//! openings on courses ([`super::openings`]) and on cones
//! ([`super::cone_openings`]) are sampled from.

use std::f64::consts::{PI, TAU};

use glam::{DAffine3, DVec2, DVec3};

/// A neck axis in a course's local frame.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct NeckAxis {
    /// Neck start (nozzle local origin), mm.
    pub origin: DVec3,
    /// Unit radial directions of the neck's φ = 0 and φ = 90°.
    pub e1: DVec3,
    /// See `e1`.
    pub e2: DVec3,
    /// Unit axis direction, outwards.
    pub axis: DVec3,
}

impl NeckAxis {
    /// The axis of a nozzle whose local frame maps by `nozzle` into the
    /// vessel frame, seen from a part whose frame is `part`.
    pub fn new(part: DAffine3, nozzle: DAffine3) -> Self {
        let m = part.inverse() * nozzle;
        NeckAxis {
            origin: m.translation,
            e1: m.matrix3.x_axis.normalize(),
            e2: m.matrix3.y_axis.normalize(),
            axis: m.matrix3.z_axis.normalize(),
        }
    }

    /// The point at angle `phi` of the cylinder of radius `rho` about the
    /// axis that lies on the cylinder of radius `big` about local +Z (the
    /// outer crossing), and its distance along the axis; `None` where that
    /// line misses the cylinder.
    pub fn crossing(&self, rho: f64, big: f64, phi: f64) -> Option<(DVec3, f64)> {
        let a = self.origin + rho * (phi.cos() * self.e1 + phi.sin() * self.e2);
        let (ax, bx) = (a.truncate(), self.axis.truncate());
        let qa = bx.length_squared();
        let qb = 2.0 * ax.dot(bx);
        let qc = ax.length_squared() - big * big;
        let disc = qb * qb - 4.0 * qa * qc;
        if qa <= 0.0 || disc < 0.0 {
            return None;
        }
        // The larger root, written without cancellation.
        let root = disc.sqrt();
        let s = if qb >= 0.0 {
            (-qb - root) / (2.0 * qa)
        } else {
            2.0 * qc / (-qb + root)
        };
        let other = if qb >= 0.0 {
            2.0 * qc / (-qb - root)
        } else {
            (-qb + root) / (2.0 * qa)
        };
        let s = s.max(other);
        Some((a + s * self.axis, s))
    }
}

/// A closed curve on a course in surface coordinates `(θ, z)`: θ in radians
/// about the part's axis from its +X, unwrapped to be continuous about the
/// curve's centre; z along the part's axis, mm.
pub type SurfaceLoop = Vec<DVec2>;

/// Samples for a curve of radius `rho` within `tolerance` (chord sagitta),
/// with a factor of two to spare for the shell's curvature.
pub fn samples(rho: f64, tolerance: f64) -> usize {
    let ratio = (1.0 - tolerance / rho.max(tolerance)).clamp(-1.0, 1.0);
    let n = (2.0 * PI / ratio.acos()).ceil() * 2.0;
    (n as usize).clamp(32, 20_000)
}

/// θ of `p` unwrapped to within π of `about`.
pub fn theta_near(p: DVec3, about: f64) -> f64 {
    let t = p.y.atan2(p.x);
    about + (t - about + PI).rem_euclid(TAU) - PI
}
