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
}

/// (radial, axial) coordinates of `p` about the axis through `origin` along `axis`.
fn radial_axial(p: DVec3, origin: DVec3, axis: DVec3) -> DVec2 {
    let d = p - origin;
    let h = d.dot(axis);
    DVec2::new((d - axis * h).length(), h)
}

/// Distance from (x, y), x, y ≥ 0, to the ellipse x²/a² + y²/b² = 1 (Newton on the
/// angle parameter from a good seed).
fn ellipse_distance(q: DVec2, a: f64, b: f64) -> f64 {
    let mut t = (q.y * a).atan2(q.x * b);
    for _ in 0..50 {
        let (s, c) = t.sin_cos();
        let e = DVec2::new(a * c, b * s);
        let de = DVec2::new(-a * s, b * c);
        let dde = DVec2::new(-a * c, -b * s);
        let r = e - q;
        let f = r.dot(de);
        let df = de.dot(de) + r.dot(dde);
        if df.abs() < f64::MIN_POSITIVE {
            break;
        }
        let step = f / df;
        t -= step;
        if step.abs() < 1e-16 {
            break;
        }
    }
    (DVec2::new(a * t.cos(), b * t.sin()) - q).length()
}

impl Analytic {
    /// Distance from `p` to the surface (for the oblique cone, the offset within the
    /// section plane scaled back to `p`'s distance from the apex, which is zero exactly
    /// on the surface and within a constant factor of the distance near it).
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
            } => {
                let d = p - apex;
                let denom = d.dot(base_normal);
                if denom.abs() < f64::MIN_POSITIVE {
                    return d.length();
                }
                let t = (base_center - apex).dot(base_normal) / denom;
                let q = apex + d * t;
                ((q - base_center).length() - radius).abs() / t.abs()
            }
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
        }
    }
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
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

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
