//! Closed-form chordal bounds for triangles on a plane, a circular cylinder or a
//! sphere: the screen's shortcut past its probes on the surfaces most patches
//! lie on (courses, nozzle necks, flange faces, spherical crowns).
//!
//! A triangle whose vertices lie on a circular cylinder lies inside it (the
//! cylinder's cross-section is convex), so its farthest point from the surface is
//! its point nearest the axis: the deviation is `r − ρ_min`, where `ρ_min` is the
//! distance from the axis to the triangle projected along it (a triangle in the
//! cross-section's plane, worked in two coordinates; zero when it surrounds the
//! axis). On a sphere it is `r − d_min`, `d_min` the
//! distance from the centre to the triangle. Conversely every point of the
//! surface lies radially outside some triangle of a mesh that covers it, no
//! farther from it than that triangle's bound: the largest bound over a mesh is
//! its two-sided distance to the surface, which the screen's probes only sample.
//! On a plane the bound is the vertices' own distance to it (rounding).
//!
//! Sits inside `screen` and `refine::assess`: on these surfaces the bound is the
//! verdict — a triangle is within exactly when its bound is, with no probes. (It
//! used to pass only triangles within 0.99 of the tolerance and leave the rest
//! to the centroid and midpoint probes, which see as little as 15/16 of the
//! largest distance, see `peak`: hemispheres came out up to 1.035× the
//! tolerance.)

use glam::{DVec2, DVec3};

use crate::parts::Analytic;

/// The closed-form bound of one analytic surface (set up once per screen).
#[derive(Clone, Copy, Debug)]
pub(in crate::mesh::cdt) enum Bound {
    Plane {
        point: DVec3,
        normal: DVec3,
    },
    /// A cylinder: `point` on its axis, `across` two unit vectors square to the
    /// axis and to each other (the cross-section's plane).
    Cylinder {
        point: DVec3,
        across: (DVec3, DVec3),
        radius: f64,
    },
    Sphere {
        center: DVec3,
        radius: f64,
    },
}

impl Bound {
    /// The bound of `analytic`, `None` for a surface without one.
    pub fn of(analytic: &Analytic) -> Option<Self> {
        match *analytic {
            Analytic::Plane { point, normal } => Some(Self::Plane { point, normal }),
            Analytic::Cylinder {
                point,
                axis,
                radius,
            } => Some(Self::Cylinder {
                point,
                across: axis.normalize().any_orthonormal_pair(),
                radius,
            }),
            Analytic::Sphere { center, radius } => Some(Self::Sphere { center, radius }),
            _ => None,
        }
    }

    /// The largest distance from a point of triangle `p` to the surface, given
    /// that its vertices lie on it (up to rounding, which the bound includes);
    /// infinite for a triangle round a cylinder's axis.
    pub fn deviation(&self, p: [DVec3; 3]) -> f64 {
        match *self {
            Self::Plane { point, normal } => p
                .iter()
                .map(|&x| (x - point).dot(normal).abs())
                .fold(0.0, f64::max),
            Self::Cylinder {
                point,
                across: (e1, e2),
                radius,
            } => {
                // The corners seen along the axis: in the cross-section's plane.
                let q = p.map(|x| {
                    let d = x - point;
                    DVec2::new(d.dot(e1), d.dot(e2))
                });
                // Round the axis: no point of the cylinder's surface is near.
                let sides = [0, 1, 2].map(|i| q[i].perp_dot(q[(i + 1) % 3]));
                if sides.iter().all(|&s| s > 0.0) || sides.iter().all(|&s| s < 0.0) {
                    return f64::INFINITY;
                }
                let nearest = (0..3)
                    .map(|i| segment_distance_squared(q[i], q[(i + 1) % 3]))
                    .fold(f64::INFINITY, f64::min)
                    .sqrt();
                let farthest = q
                    .iter()
                    .map(|x| x.length_squared())
                    .fold(0.0, f64::max)
                    .sqrt();
                (radius - nearest).max(farthest - radius)
            }
            Self::Sphere { center, radius } => {
                let q = p.map(|x| x - center);
                let nearest = triangle_distance(q);
                let farthest = q.iter().map(|x| x.length()).fold(0.0, f64::max);
                (radius - nearest).max(farthest - radius)
            }
        }
    }
}

/// Distance from the origin to the triangle `q` (its nearest point by the
/// Voronoi regions of its vertices, edges and face; Ericson, *Real-Time
/// Collision Detection*, 5.1.5).
fn triangle_distance(q: [DVec3; 3]) -> f64 {
    let [a, b, c] = q;
    let (ab, ac, ap) = (b - a, c - a, -a);
    let (d1, d2) = (ab.dot(ap), ac.dot(ap));
    if d1 <= 0.0 && d2 <= 0.0 {
        return a.length();
    }
    let bp = -b;
    let (d3, d4) = (ab.dot(bp), ac.dot(bp));
    if d3 >= 0.0 && d4 <= d3 {
        return b.length();
    }
    let vc = d1 * d4 - d3 * d2;
    if vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0 {
        return (a + ab * (d1 / (d1 - d3))).length();
    }
    let cp = -c;
    let (d5, d6) = (ab.dot(cp), ac.dot(cp));
    if d6 >= 0.0 && d5 <= d6 {
        return c.length();
    }
    let vb = d5 * d2 - d1 * d6;
    if vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0 {
        return (a + ac * (d2 / (d2 - d6))).length();
    }
    let va = d3 * d6 - d5 * d4;
    if va <= 0.0 && d4 - d3 >= 0.0 && d5 - d6 >= 0.0 {
        return (b + (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6)))).length();
    }
    let denom = va + vb + vc;
    if denom == 0.0 || !denom.is_finite() {
        // Collinear corners: the nearest of the three edges.
        return [(a, b), (b, c), (c, a)]
            .iter()
            .map(|&(x, y)| segment_distance(x, y))
            .fold(f64::INFINITY, f64::min);
    }
    let (v, w) = (vb / denom, vc / denom);
    (a + ab * v + ac * w).length()
}

/// Squared distance from the origin to the segment `a b` in a plane.
fn segment_distance_squared(a: DVec2, b: DVec2) -> f64 {
    let d = b - a;
    (a + nearest(a.dot(d), d.length_squared()) * d).length_squared()
}

/// Distance from the origin to the segment `a b`.
fn segment_distance(a: DVec3, b: DVec3) -> f64 {
    let d = b - a;
    (a + nearest(a.dot(d), d.length_squared()) * d).length()
}

/// Where on a segment `a + t d`, `t` in [0, 1], the origin's nearest point
/// lies, from `a · d` and `|d|²` (its start when the segment is a point).
fn nearest(a_dot_d: f64, len2: f64) -> f64 {
    if len2 > 0.0 {
        (-a_dot_d / len2).clamp(0.0, 1.0)
    } else {
        0.0
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn cylinder(radius: f64) -> Bound {
        Bound::of(&Analytic::Cylinder {
            point: DVec3::new(10.0, -5.0, 3.0),
            axis: DVec3::Z,
            radius,
        })
        .expect("a cylinder has a bound")
    }

    fn on(radius: f64, angle: f64, z: f64) -> DVec3 {
        DVec3::new(
            10.0 + radius * angle.cos(),
            -5.0 + radius * angle.sin(),
            3.0 + z,
        )
    }

    /// The bound equals the largest distance to the cylinder found by sampling the
    /// triangle densely, for lattice-like and skewed triangles.
    #[test]
    fn the_cylinder_bound_is_the_largest_distance_over_the_triangle() {
        let r = 750.0;
        let cases = [
            [(0.0, 0.0), (0.08, 0.0), (0.04, 300.0)],
            [(1.0, -20.0), (1.05, 40.0), (0.97, 10.0)],
            [(2.0, 0.0), (2.3, 500.0), (2.1, 100.0)],
            [(-0.5, 7.0), (-0.45, 7.0), (-0.52, -100.0)],
        ];
        for case in cases {
            let p = case.map(|(a, z)| on(r, a, z));
            let bound = cylinder(r).deviation(p);
            let mut sampled: f64 = 0.0;
            let n = 400;
            for i in 0..=n {
                for j in 0..=n - i {
                    let (s, t) = (i as f64 / n as f64, j as f64 / n as f64);
                    let x = p[0] + s * (p[1] - p[0]) + t * (p[2] - p[0]);
                    let rho = (glam::DVec2::new(x.x - 10.0, x.y + 5.0)).length();
                    sampled = sampled.max((r - rho).abs());
                }
            }
            assert!(bound >= sampled - 1e-9 * r, "{bound} < {sampled}");
            assert!(bound <= sampled * 1.001 + 1e-9 * r, "{bound} ≫ {sampled}");
        }
    }

    /// On a sphere too: the bound matches dense sampling, including a triangle
    /// whose nearest point to the centre is on an edge or a vertex.
    #[test]
    fn the_sphere_bound_is_the_largest_distance_over_the_triangle() {
        let (center, r) = (DVec3::new(1.0, 2.0, -3.0), 1200.0);
        let sphere = Bound::of(&Analytic::Sphere { center, radius: r }).expect("bound");
        let at = |theta: f64, phi: f64| {
            center + r * DVec3::new(phi.sin() * theta.cos(), phi.sin() * theta.sin(), phi.cos())
        };
        let cases = [
            [at(0.0, 0.3), at(0.1, 0.3), at(0.05, 0.38)],
            [at(1.0, 0.02), at(2.0, 0.025), at(3.5, 0.03)],
            [at(0.0, 1.0), at(0.6, 1.0), at(0.3, 1.02)],
        ];
        for p in cases {
            let bound = sphere.deviation(p);
            let mut sampled: f64 = 0.0;
            let n = 400;
            for i in 0..=n {
                for j in 0..=n - i {
                    let (s, t) = (i as f64 / n as f64, j as f64 / n as f64);
                    let x = p[0] + s * (p[1] - p[0]) + t * (p[2] - p[0]);
                    sampled = sampled.max((r - (x - center).length()).abs());
                }
            }
            assert!(bound >= sampled - 1e-9 * r, "{bound} < {sampled}");
            assert!(bound <= sampled * 1.001 + 1e-9 * r, "{bound} ≫ {sampled}");
        }
    }

    #[test]
    fn a_triangle_round_the_axis_or_off_the_surface_is_not_passed() {
        let r = 100.0;
        let round = [0.0, 2.1, 4.2].map(|a| on(r, a, 0.0));
        assert!(cylinder(r).deviation(round).is_infinite());
        // Vertices off the surface count: the bound covers them.
        let mut p = [0.0, 0.01, 0.02].map(|a| on(r, a, 0.0));
        p[1] = on(r + 0.5, 0.01, 0.0);
        assert!(cylinder(r).deviation(p) >= 0.5 - 1e-9);
        let plane = Bound::of(&Analytic::Plane {
            point: DVec3::ZERO,
            normal: DVec3::Z,
        })
        .expect("a plane has a bound");
        let flat = [DVec3::X, DVec3::Y, DVec3::new(1.0, 1.0, 0.25)];
        assert_eq!(plane.deviation(flat), 0.25);
    }
}
