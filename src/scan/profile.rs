//! The meridian of a patch swept a full turn about its local +Z, and the exact
//! closest point of such a patch by it.
//!
//! For a surface of revolution the closest point to P lies in the meridian
//! half-plane through P, so point inversion splits into the angle of P (closed
//! form) and the closest point of the meridian curve to P's (radius, height):
//! a one-variable Newton on the exact rational profile, started from the nearest
//! of a table of samples. The revolution's u parameter of an angle is closed form
//! too: on each quarter arc of [`revolve`](crate::nurbs::builders::revolve)
//! (weights 1, √2/2, 1) the angle's tangent is a ratio of quadratics in the
//! arc's local parameter.

use std::f64::consts::{FRAC_PI_2, TAU};

use glam::{DVec2, DVec3};

use crate::nurbs::NurbsCurve;
use crate::nurbs::builders::FULL_TURN_KNOTS;
use crate::parts::Patch;

/// Samples of the meridian per knot span, for Newton's start.
const SAMPLES_PER_SPAN: usize = 24;

/// Newton steps on the meridian.
const MAX_STEPS: usize = 30;

/// A patch's meridian: the curve at u = 0, in the local XZ plane (x = radius).
#[derive(Clone, Debug)]
pub struct Profile {
    curve: NurbsCurve,
    samples: Vec<(f64, DVec2)>,
}

/// The closest point of a surface of revolution, in its local frame.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LocalFoot {
    /// u of the patch (around the axis).
    pub u: f64,
    /// v of the patch (along the meridian).
    pub v: f64,
    /// The closest point.
    pub point: DVec3,
    /// Unit outward normal there.
    pub normal: DVec3,
    /// Signed distance along the normal, positive outside.
    pub deviation: f64,
    /// False where the closest point of the meridian is one of its ends and the
    /// query lies beyond it (the point belongs to a neighbouring patch).
    pub inside: bool,
}

impl Profile {
    /// The meridian of `patch` if it is swept a full turn about its local +Z
    /// (checked at sample points), else `None`.
    pub fn of_patch(patch: &Patch) -> Option<Self> {
        let s = &patch.surface;
        if s.u_knots().as_slice() != FULL_TURN_KNOTS {
            return None;
        }
        let curve = s.isocurve_u(0.0);
        let (v0, v1) = curve.domain();
        let size = s
            .control_points()
            .iter()
            .map(|p| p.length())
            .fold(1.0, f64::max);
        for (k, t) in [0.13, 0.5, 0.87].into_iter().enumerate() {
            let v = v0 + (v1 - v0) * t;
            let c = curve.point(v);
            if c.y.abs() > 1e-9 * size {
                return None;
            }
            let u = [0.07, 0.41, 0.83][k];
            let theta = angle_of_u(u);
            let (sn, cs) = theta.sin_cos();
            let expected = DVec3::new(c.x * cs, c.x * sn, c.z);
            if (s.point(u, v) - expected).length() > 1e-9 * size {
                return None;
            }
        }
        let mut samples = Vec::new();
        for (a, b) in curve.knots().spans() {
            for i in 0..SAMPLES_PER_SPAN {
                let v = a + (b - a) * i as f64 / SAMPLES_PER_SPAN as f64;
                let c = curve.point(v);
                samples.push((v, DVec2::new(c.x, c.z)));
            }
        }
        let c = curve.point(v1);
        samples.push((v1, DVec2::new(c.x, c.z)));
        Some(Self { curve, samples })
    }

    /// The closest point of the patch to `p` (local frame).
    pub fn project(&self, p: DVec3) -> LocalFoot {
        let r = DVec2::new(p.x, p.y).length();
        let q = DVec3::new(r, 0.0, p.z);
        let start = self
            .samples
            .iter()
            .min_by(|a, b| {
                (a.1 - DVec2::new(r, p.z))
                    .length_squared()
                    .total_cmp(&(b.1 - DVec2::new(r, p.z)).length_squared())
            })
            .map_or(0.0, |s| s.0);
        let (v0, v1) = self.curve.domain();
        let mut v = start;
        for _ in 0..MAX_STEPS {
            let d = self.curve.derivatives(v);
            let offset = d.point - q;
            let f = offset.dot(d.first);
            let mut df = d.first.length_squared() + offset.dot(d.second);
            if df <= 0.0 {
                df = d.first.length_squared();
            }
            if df <= 0.0 {
                break;
            }
            let next = (v - f / df).clamp(v0, v1);
            let step = (next - v).abs();
            v = next;
            if step <= 1e-15 * (v1 - v0) {
                break;
            }
        }
        let d = self.curve.derivatives(v);
        let tangent = DVec2::new(d.first.x, d.first.z);
        let normal2 = DVec2::new(tangent.y, -tangent.x).normalize_or_zero();
        let offset = DVec2::new(r - d.point.x, p.z - d.point.z);
        let along = offset.dot(tangent.normalize_or_zero());
        let scale = 1e-9 * (1.0 + d.point.length());
        let inside = !((v <= v0 && along < -scale) || (v >= v1 && along > scale));
        let theta = if r > 0.0 { p.y.atan2(p.x) } else { 0.0 };
        let (sn, cs) = theta.sin_cos();
        let point = DVec3::new(d.point.x * cs, d.point.x * sn, d.point.z);
        let normal = DVec3::new(normal2.x * cs, normal2.x * sn, normal2.y);
        let deviation = if inside {
            offset.dot(normal2)
        } else {
            let sign = if offset.dot(normal2) < 0.0 { -1.0 } else { 1.0 };
            sign * offset.length()
        };
        LocalFoot {
            u: u_of_angle(theta),
            v,
            point,
            normal,
            deviation,
            inside,
        }
    }
}

/// The angle (radians, in [0, 2π)) of the full-turn revolution's parameter `u`.
pub fn angle_of_u(u: f64) -> f64 {
    let w = std::f64::consts::FRAC_1_SQRT_2;
    let u = u.clamp(0.0, 1.0) * 4.0;
    let k = u.floor().min(3.0);
    let t = u - k;
    let x = (1.0 - t) * (1.0 - t) + 2.0 * t * (1.0 - t) * w;
    let y = 2.0 * t * (1.0 - t) * w + t * t;
    k * FRAC_PI_2 + y.atan2(x)
}

/// The full-turn revolution's parameter u of an angle (radians, any turn).
pub fn u_of_angle(theta: f64) -> f64 {
    let w = std::f64::consts::FRAC_1_SQRT_2;
    let theta = theta.rem_euclid(TAU);
    let k = (theta / FRAC_PI_2).floor().min(3.0);
    let phi = theta - k * FRAC_PI_2;
    let (s, c) = phi.sin_cos();
    // t²(c − s − a) + t(a + 2s) − s = 0 with a = 2w(c − s).
    let a = 2.0 * w * (c - s);
    let (qa, qb, qc) = (c - s - a, a + 2.0 * s, -s);
    let disc = (qb * qb - 4.0 * qa * qc).max(0.0);
    let t = if qb + disc.sqrt() == 0.0 {
        0.0
    } else {
        -2.0 * qc / (qb + disc.sqrt())
    };
    ((k + t.clamp(0.0, 1.0)) / 4.0).min(1.0)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn angle_and_u_are_inverse() {
        for i in 0..=400 {
            let u = i as f64 / 400.0;
            let back = u_of_angle(angle_of_u(u));
            let same = (back - u).abs() < 1e-12 || (u == 1.0 && back < 1e-12);
            assert!(same, "u {u} back {back}");
        }
    }
}
