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
    /// The meridian's ends (radius, height) when it is a straight segment
    /// linear in v (a course or a concentric cone: degree 1, two control
    /// points): its closest point is then closed form.
    line: Option<(DVec2, DVec2)>,
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
        let h = curve.homogeneous_points();
        let line = (curve.degree() == 1 && h.len() == 2 && h[0].w == h[1].w).then(|| {
            let (a, b) = (curve.point(v0), curve.point(v1));
            (DVec2::new(a.x, a.z), DVec2::new(b.x, b.z))
        });
        Some(Self {
            curve,
            samples,
            line,
        })
    }

    /// The closest point of the patch to `p` (local frame).
    pub fn project(&self, p: DVec3) -> LocalFoot {
        let r = DVec2::new(p.x, p.y).length();
        match self.line {
            Some(line) => self.project_on_line(p, r, line),
            None => self.project_by_newton(p, r),
        }
    }

    /// Newton on the meridian from the nearest sample.
    fn project_by_newton(&self, p: DVec3, r: f64) -> LocalFoot {
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
        self.foot(p, r, v, DVec2::new(d.point.x, d.point.z), tangent)
    }

    /// [`project`](Self::project) on a straight meridian from `a` to `b`
    /// (radius, height), linear in v: the foot's v in closed form.
    fn project_on_line(&self, p: DVec3, r: f64, (a, b): (DVec2, DVec2)) -> LocalFoot {
        let (v0, v1) = self.curve.domain();
        let q = DVec2::new(r, p.z);
        let axis = b - a;
        let t = ((q - a).dot(axis) / axis.length_squared()).clamp(0.0, 1.0);
        // The ends exactly, as Newton's clamp gives them (`inside` compares).
        let v = if t >= 1.0 { v1 } else { v0 + (v1 - v0) * t };
        let foot = a + axis * t;
        let tangent = axis * (1.0 / (v1 - v0));
        self.foot(p, r, v, foot, tangent)
    }

    /// The local foot at meridian parameter `v` (point `at`, tangent `tangent`
    /// in radius and height) of the query `p` at radius `r`.
    fn foot(&self, p: DVec3, r: f64, v: f64, at: DVec2, tangent: DVec2) -> LocalFoot {
        let (v0, v1) = self.curve.domain();
        let normal2 = DVec2::new(tangent.y, -tangent.x).normalize_or_zero();
        let offset = DVec2::new(r - at.x, p.z - at.y);
        let along = offset.dot(tangent.normalize_or_zero());
        let scale = 1e-9 * (1.0 + at.length());
        let inside = !((v <= v0 && along < -scale) || (v >= v1 && along > scale));
        let theta = if r > 0.0 { p.y.atan2(p.x) } else { 0.0 };
        let (sn, cs) = theta.sin_cos();
        let point = DVec3::new(at.x * cs, at.x * sn, at.y);
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

    /// The closed form on a course and a cone agrees with Newton on the same
    /// meridian to 1e-9 relative, inside, beyond either end and on the axis.
    #[test]
    fn a_straight_meridian_projects_as_newton_does() {
        use crate::parts::{Reducer, ReducerAlignment, Shell};
        let course = Shell {
            outside_diameter: 2000.0,
            length: 3000.0,
        }
        .patches()
        .unwrap();
        let cone = Reducer {
            large_diameter: 2000.0,
            small_diameter: 1400.0,
            length: 900.0,
            alignment: ReducerAlignment::Concentric,
        }
        .patches()
        .unwrap();
        let mut checked = 0;
        for patch in course.iter().chain(&cone) {
            let Some(profile) = Profile::of_patch(patch) else {
                continue;
            };
            assert!(profile.line.is_some(), "{} is straight", patch.name);
            for i in 0..200 {
                let t = i as f64 * 0.731;
                let rho = 300.0 * (i % 9) as f64;
                let p = DVec3::new(rho * t.cos(), rho * t.sin(), -400.0 + 19.0 * i as f64);
                let r = DVec2::new(p.x, p.y).length();
                let fast = profile.project(p);
                let slow = profile.project_by_newton(p, r);
                let scale = 1.0 + p.length();
                assert!((fast.v - slow.v).abs() <= 1e-9, "{p} {fast:?} {slow:?}");
                assert!((fast.point - slow.point).length() <= 1e-9 * scale, "{p}");
                assert!(
                    (fast.deviation - slow.deviation).abs() <= 1e-9 * scale,
                    "{p}"
                );
                assert!((fast.normal - slow.normal).length() <= 1e-9, "{p}");
                assert_eq!(fast.inside, slow.inside, "{p}");
                assert_eq!(fast.u, slow.u);
                checked += 1;
            }
        }
        assert_eq!(checked, 400, "a course and a cone patch");
    }

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
