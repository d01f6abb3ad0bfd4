//! The analytic surfaces vessel patches lie on, with distance queries.
//!
//! Every [`Patch`](super::Patch) carries one. Tests use [`Analytic::distance`] to show
//! that NURBS points lie on the exact surface; views can use it for exact silhouettes
//! and intersections for closed-form seeds.

use glam::{DVec2, DVec3};

/// An analytic surface in a part's local frame. Axes are unit vectors.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Analytic {
    /// The plane through `point` with unit `normal`.
    Plane {
        /// A point on the plane.
        point: DVec3,
        /// Unit normal.
        normal: DVec3,
    },
    /// The circular cylinder of `radius` about the axis through `point` along `axis`.
    Cylinder {
        /// A point on the axis.
        point: DVec3,
        /// Unit axis.
        axis: DVec3,
        /// Radius in mm.
        radius: f64,
    },
    /// The right circular cone with `apex`, opening along `axis` with `half_angle`
    /// (radians) between axis and generatrix.
    Cone {
        /// The apex.
        apex: DVec3,
        /// Unit axis pointing from the apex into the cone.
        axis: DVec3,
        /// Half-angle in radians, 0 < α < π/2.
        half_angle: f64,
    },
    /// An oblique circular cone: all lines from `apex` through the circle of `radius`
    /// about `base_center` in the plane with unit normal `base_normal`.
    ObliqueCone {
        /// The apex.
        apex: DVec3,
        /// Centre of a circular section.
        base_center: DVec3,
        /// Normal of the section's plane.
        base_normal: DVec3,
        /// Radius of the section.
        radius: f64,
    },
    /// The sphere of `radius` about `center`.
    Sphere {
        /// Centre.
        center: DVec3,
        /// Radius in mm.
        radius: f64,
    },
    /// The torus about the axis through `center` along `axis`: a circle of radius
    /// `minor` whose centre runs on the circle of radius `major`.
    Torus {
        /// Centre (on the axis, in the plane of the centre circle).
        center: DVec3,
        /// Unit axis.
        axis: DVec3,
        /// Radius of the circle of tube centres.
        major: f64,
        /// Tube radius.
        minor: f64,
    },
    /// The ellipsoid of revolution about `axis` through `center`, with semi-axis
    /// `equatorial` across the axis and `polar` along it.
    Spheroid {
        /// Centre.
        center: DVec3,
        /// Unit axis of revolution.
        axis: DVec3,
        /// Semi-axis across the axis.
        equatorial: f64,
        /// Semi-axis along the axis.
        polar: f64,
    },
    /// A head's knuckle and the dished piece beyond its seam as one surface (a
    /// reinforcing pad across the seam lies on both): the torus about the axis
    /// through `center` along `axis` (tube centres on the circle of radius
    /// `major`, tube radius `minor`) up to the seam, where the tube's meridian
    /// circle is at angle `seam` (radians from the plane of the centre circle,
    /// towards `axis`), and beyond it the surface of revolution tangent to the
    /// torus along the seam whose meridian is the circle of radius `beyond` (a
    /// sphere centred on the axis) or, for `beyond` = ∞, the tangent line (a
    /// cone or a plane).
    Knuckled {
        /// Centre of the torus (on the axis, in the plane of its centre circle).
        center: DVec3,
        /// Unit axis.
        axis: DVec3,
        /// Radius of the circle of tube centres.
        major: f64,
        /// Tube radius.
        minor: f64,
        /// Angle of the seam on the tube's meridian circle, radians.
        seam: f64,
        /// Meridian radius beyond the seam, mm (∞: a straight meridian).
        beyond: f64,
    },
}

/// (radial, axial) coordinates of `p` about the axis through `origin` along `axis`.
fn radial_axial(p: DVec3, origin: DVec3, axis: DVec3) -> DVec2 {
    let d = p - origin;
    let h = d.dot(axis);
    DVec2::new((d - axis * h).length(), h)
}

/// Distance from (x, y), x, y ≥ 0, to the ellipse x²/a² + y²/b² = 1.
///
/// On an axis the foot point is in closed form. Inside the quadrant it is the one
/// root in (0, π/2) of the distance's derivative in the angle t, found by Newton
/// from a good seed; if plain Newton does not settle on a minimum in the quadrant
/// within a few steps (deep inside a flat ellipse, near the major axis, it could
/// settle on the axis, where the distance is a maximum), Newton kept inside a
/// bracket, with bisection whenever a step would leave it, finds it. The angle is
/// carried as its cosine and sine as well: each step turns them by a rotation (the
/// step's cosine and sine by their Taylor series once it is small), so points
/// near the ellipse, where the meshers probe, cost no trigonometric call. The
/// distance is stationary at the foot point, so an angle within [`FOOT_ANGLE`] of
/// it gives the distance to far below rounding; the iteration stops there.
fn ellipse_distance(q: DVec2, a: f64, b: f64) -> f64 {
    if q.y <= 0.0 {
        return axis_distance(q.x, a, b);
    }
    if q.x <= 0.0 {
        return axis_distance(q.y, b, a);
    }
    let seed = DVec2::new(q.x * b, q.y * a).normalize();
    quick_foot(q, a, b, seed).unwrap_or_else(|| bracketed_foot(q, a, b, seed))
}

/// Cosine and sine of `t − step` from those of `t` (`cs`).
fn turn(cs: DVec2, step: f64) -> DVec2 {
    let (sin, cos) = if step.abs() < 1e-2 {
        let s2 = step * step;
        (
            step * (1.0 - s2 / 6.0 * (1.0 - s2 / 20.0)),
            1.0 - s2 / 2.0 * (1.0 - s2 / 12.0 * (1.0 - s2 / 30.0)),
        )
    } else {
        step.sin_cos()
    };
    let turned = DVec2::new(cs.x * cos + cs.y * sin, cs.y * cos - cs.x * sin);
    turned / turned.length()
}

/// One Newton step of [`ellipse_distance`] at the angle whose cosine and sine are
/// `cs`: the offset from `q`, the derivative of the squared distance (halved) and
/// its derivative.
fn newton_terms(q: DVec2, a: f64, b: f64, cs: DVec2) -> (DVec2, f64, f64) {
    let e = DVec2::new(a * cs.x, b * cs.y);
    let de = DVec2::new(-a * cs.y, b * cs.x);
    let r = e - q;
    (r, r.dot(de), de.dot(de) - r.dot(e))
}

/// Plain Newton from `seed`, a few steps: the distance if it settles on a minimum
/// inside the quadrant, else `None`.
fn quick_foot(q: DVec2, a: f64, b: f64, seed: DVec2) -> Option<f64> {
    let mut cs = seed;
    for _ in 0..8 {
        let (r, f, df) = newton_terms(q, a, b, cs);
        if df <= 0.0 || cs.x < 0.0 || cs.y < 0.0 {
            return None;
        }
        let step = f / df;
        if step.abs() < FOOT_ANGLE {
            return Some(r.length());
        }
        cs = turn(cs, step);
    }
    None
}

/// Newton kept inside a bracket of the root in (0, π/2), bisecting whenever a
/// step would leave it.
fn bracketed_foot(q: DVec2, a: f64, b: f64, seed: DVec2) -> f64 {
    let (mut lo, mut hi) = (0.0, std::f64::consts::FRAC_PI_2);
    let mut cs = seed;
    let mut t = cs.y.atan2(cs.x);
    let mut r = DVec2::ZERO;
    for _ in 0..200 {
        let (offset, f, df) = newton_terms(q, a, b, cs);
        r = offset;
        if f < 0.0 {
            lo = t;
        } else {
            hi = t;
        }
        let next = t - f / df;
        if df > 0.0 && next > lo && next < hi {
            if (t - next).abs() < FOOT_ANGLE {
                return r.length();
            }
            cs = turn(cs, t - next);
            t = next;
        } else {
            if hi - lo < FOOT_ANGLE {
                return r.length();
            }
            t = 0.5 * (lo + hi);
            let (s, c) = t.sin_cos();
            cs = DVec2::new(c, s);
        }
    }
    r.length()
}

/// Distance from (x, 0), x ≥ 0, to the ellipse x²/a² + y²/b² = 1: the vertex
/// (a, 0) unless x lies inside that vertex's centre of curvature, a − b²/a, where
/// the foot point leaves the axis.
fn axis_distance(x: f64, a: f64, b: f64) -> f64 {
    let d2 = a * a - b * b;
    if d2 > 0.0 && x * a < d2 {
        let x0 = a * a * x / d2;
        let y0 = b * (1.0 - (x0 / a) * (x0 / a)).max(0.0).sqrt();
        DVec2::new(x0 - x, y0).length()
    } else {
        (a - x).abs()
    }
}

/// Angle step (radians) below which [`ellipse_distance`]'s foot point is taken as
/// found: the distance then errs by about `a²·step²/(2d)`, under 1e-12 mm for the
/// largest heads.
const FOOT_ANGLE: f64 = 1e-10;

impl Analytic {
    /// Distance from `p` to the surface (for the oblique cone, to its nearest
    /// generatrix line: exact near the surface, see `oblique_cone_distance`).
    pub fn distance(&self, p: DVec3) -> f64 {
        match *self {
            Analytic::Plane { point, normal } => (p - point).dot(normal).abs(),
            Analytic::Cylinder {
                point,
                axis,
                radius,
            } => (radial_axial(p, point, axis).x - radius).abs(),
            Analytic::Cone {
                apex,
                axis,
                half_angle,
            } => {
                let q = radial_axial(p, apex, axis);
                let (s, c) = half_angle.sin_cos();
                if q.x * s + q.y * c < 0.0 {
                    // Behind the apex: the nearest point is the apex.
                    q.length()
                } else {
                    (q.x * c - q.y * s).abs()
                }
            }
            Analytic::ObliqueCone {
                apex,
                base_center,
                base_normal,
                radius,
            } => oblique_cone_distance(p, apex, base_center, base_normal, radius),
            Analytic::Sphere { center, radius } => ((p - center).length() - radius).abs(),
            Analytic::Torus {
                center,
                axis,
                major,
                minor,
            } => {
                let q = radial_axial(p, center, axis);
                (DVec2::new(q.x - major, q.y).length() - minor).abs()
            }
            Analytic::Spheroid {
                center,
                axis,
                equatorial,
                polar,
            } => {
                let q = radial_axial(p, center, axis);
                ellipse_distance(DVec2::new(q.x, q.y.abs()), equatorial, polar)
            }
            Analytic::Knuckled {
                center,
                axis,
                major,
                minor,
                seam,
                beyond,
            } => {
                // In the meridian half-plane: the tube's circle up to the normal
                // line through the seam, the piece beyond past it.
                let q = radial_axial(p, center, axis);
                let tube = DVec2::new(major, 0.0);
                let normal = DVec2::from_angle(seam);
                let d = q - tube;
                if normal.perp_dot(d) <= 0.0 {
                    return (d.length() - minor).abs();
                }
                let at = tube + minor * normal;
                if beyond.is_finite() {
                    ((q - (at - beyond * normal)).length() - beyond).abs()
                } else {
                    (q - at).dot(normal).abs()
                }
            }
        }
    }

    /// The knuckle `knuckle` (a torus) and the piece `next` beyond its seam (a
    /// sphere centred on the torus's axis, a cone or a plane, tangent to it
    /// there) as one [`Analytic::Knuckled`] surface, the seam passing through
    /// `seam_point`; `None` for any other pair.
    pub fn knuckled(knuckle: &Analytic, next: &Analytic, seam_point: DVec3) -> Option<Analytic> {
        let Analytic::Torus {
            center,
            axis,
            major,
            minor,
        } = *knuckle
        else {
            return None;
        };
        let beyond = match *next {
            Analytic::Sphere { radius, .. } => radius,
            Analytic::Cone { .. } | Analytic::Plane { .. } => f64::INFINITY,
            _ => return None,
        };
        let d = radial_axial(seam_point, center, axis) - DVec2::new(major, 0.0);
        Some(Analytic::Knuckled {
            center,
            axis,
            major,
            minor,
            seam: d.y.atan2(d.x),
            beyond,
        })
    }
}

/// Newton steps of [`oblique_cone_distance`] (three are usual to rounding).
const OBLIQUE_STEPS: usize = 8;

/// The distance from `p` to the oblique cone through `apex` and the circle of
/// `radius` about `center` in the plane of unit normal `normal`: the distance to
/// its nearest generatrix, the line from the apex through the circle's point at
/// the angle θ where (w·d)²/|d|² peaks (w = p − apex, d(θ) the generatrix's
/// direction), found by Newton steps from the angle where the line from the
/// apex through `p` meets the circle's plane. Every θ tried gives the distance to
/// a line on the cone, so the least is never below the true distance, and at the
/// peak it is the true distance.
fn oblique_cone_distance(p: DVec3, apex: DVec3, center: DVec3, normal: DVec3, radius: f64) -> f64 {
    let w = p - apex;
    let (e1, e2) = normal.any_orthonormal_pair();
    let m = center - apex;
    let to_line = |theta: f64| {
        let (s, c) = theta.sin_cos();
        let d = m + (e1 * c + e2 * s) * radius;
        w.cross(d).length() / d.length()
    };
    let denom = w.dot(normal);
    let q = if denom.abs() < f64::MIN_POSITIVE {
        w
    } else {
        w * (m.dot(normal) / denom) - m
    };
    let mut theta = q.dot(e2).atan2(q.dot(e1));
    let mut best = to_line(theta);
    for _ in 0..OBLIQUE_STEPS {
        let (s, c) = theta.sin_cos();
        let u = e1 * c + e2 * s;
        let d = m + u * radius;
        let d1 = (e2 * c - e1 * s) * radius;
        let d2 = -u * radius;
        let (a, a1, a2) = (w.dot(d), w.dot(d1), w.dot(d2));
        let (b, b1, b2) = (d.dot(d), 2.0 * d.dot(d1), 2.0 * (d1.dot(d1) + d.dot(d2)));
        // (A²/B)' = A (2A'B − AB') / B²: the root of the second factor.
        let f = 2.0 * a1 * b - a * b1;
        let f1 = 2.0 * a2 * b + a1 * b1 - a * b2;
        if !(f1.is_finite() && f1 != 0.0) {
            break;
        }
        let step = f / f1;
        theta -= step;
        best = best.min(to_line(theta));
        if step.abs() <= 1e-15 {
            break;
        }
    }
    best
}

impl Analytic {
    /// The same surface after a rigid motion `m` (rotation and translation; a
    /// scale would change radii and is not supported: the linear part must be
    /// orthonormal).
    pub fn transformed(&self, m: &glam::DAffine3) -> Analytic {
        let p = |x: DVec3| m.transform_point3(x);
        let v = |x: DVec3| m.transform_vector3(x).normalize_or_zero();
        match *self {
            Analytic::Plane { point, normal } => Analytic::Plane {
                point: p(point),
                normal: v(normal),
            },
            Analytic::Cylinder {
                point,
                axis,
                radius,
            } => Analytic::Cylinder {
                point: p(point),
                axis: v(axis),
                radius,
            },
            Analytic::Cone {
                apex,
                axis,
                half_angle,
            } => Analytic::Cone {
                apex: p(apex),
                axis: v(axis),
                half_angle,
            },
            Analytic::ObliqueCone {
                apex,
                base_center,
                base_normal,
                radius,
            } => Analytic::ObliqueCone {
                apex: p(apex),
                base_center: p(base_center),
                base_normal: v(base_normal),
                radius,
            },
            Analytic::Sphere { center, radius } => Analytic::Sphere {
                center: p(center),
                radius,
            },
            Analytic::Torus {
                center,
                axis,
                major,
                minor,
            } => Analytic::Torus {
                center: p(center),
                axis: v(axis),
                major,
                minor,
            },
            Analytic::Spheroid {
                center,
                axis,
                equatorial,
                polar,
            } => Analytic::Spheroid {
                center: p(center),
                axis: v(axis),
                equatorial,
                polar,
            },
            Analytic::Knuckled {
                center,
                axis,
                major,
                minor,
                seam,
                beyond,
            } => Analytic::Knuckled {
                center: p(center),
                axis: v(axis),
                major,
                minor,
                seam,
                beyond,
            },
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    /// The foot point by bisection on the angle (the derivative of the squared
    /// distance changes sign once on the quarter arc for a point in the quadrant),
    /// then the distance: slow and plain, for comparison.
    fn ellipse_distance_by_bisection(q: DVec2, a: f64, b: f64) -> f64 {
        let slope = |t: f64| {
            let (s, c) = t.sin_cos();
            (DVec2::new(a * c, b * s) - q).dot(DVec2::new(-a * s, b * c))
        };
        let (mut lo, mut hi) = (0.0, std::f64::consts::FRAC_PI_2);
        for _ in 0..200 {
            let mid = 0.5 * (lo + hi);
            if slope(mid) < 0.0 {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        let t = 0.5 * (lo + hi);
        (DVec2::new(a * t.cos(), b * t.sin()) - q).length()
    }

    proptest! {
        /// Near the ellipse (where the meshers probe) and far from it, inside and
        /// out, the Newton distance equals the bisection's to 1e-9 of the size.
        #[test]
        fn ellipse_distance_matches_bisection(
            t in 0.0f64..std::f64::consts::FRAC_PI_2,
            offset in prop_oneof![-2.0f64..2.0, -800.0f64..3000.0],
            ratio in prop_oneof![1.2f64..4.0, 0.3f64..0.9],
            on_axis in proptest::bool::weighted(0.1),
        ) {
            let (a, b) = (5000.0, 5000.0 / ratio);
            let foot = DVec2::new(a * t.cos(), b * t.sin());
            let normal = DVec2::new(b * t.cos(), a * t.sin()).normalize();
            let q = (foot + offset * normal).max(DVec2::ZERO);
            let q = if on_axis { DVec2::new(q.x, 0.0) } else { q };
            let expected = ellipse_distance_by_bisection(q, a, b);
            prop_assert!((ellipse_distance(q, a, b) - expected).abs() <= 1e-9 * a);
        }
    }

    #[test]
    fn distances_of_known_points() {
        let s = Analytic::Spheroid {
            center: DVec3::ZERO,
            axis: DVec3::Z,
            equatorial: 2.0,
            polar: 1.0,
        };
        assert!(s.distance(DVec3::new(2.0, 0.0, 0.0)) < 1e-15);
        assert!((s.distance(DVec3::new(0.0, 0.0, 3.0)) - 2.0).abs() < 1e-12);
        assert!((s.distance(DVec3::new(0.0, 3.0, 0.0)) - 1.0).abs() < 1e-12);
        let c = Analytic::Cone {
            apex: DVec3::ZERO,
            axis: DVec3::Z,
            half_angle: std::f64::consts::FRAC_PI_4,
        };
        assert!(c.distance(DVec3::new(1.0, 0.0, 1.0)) < 1e-15);
        assert!((c.distance(DVec3::new(0.0, 0.0, 1.0)) - 0.5f64.sqrt()).abs() < 1e-15);
    }
}
