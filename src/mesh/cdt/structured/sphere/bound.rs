//! What every triangle of a sphere's rows must hold, and the zip of two rows
//! measured against it: part of `structured::sphere`, between the layout
//! (`layout`, which raises each next row as far as these verdicts allow) and
//! the sphere's geometry (vertices on the sphere of radius r about the origin,
//! the pole on +Z).
//!
//! Every vertex lies on the sphere, so a flat triangle's largest distance to
//! it is r − |q|, q the triangle's point nearest the centre: r − √(r² − ρ²)
//! with ρ its circumradius when the centre's projection falls inside it, the
//! bound of its longest edge otherwise. The bound holds for every point of the
//! triangle, not for probes.

use std::f64::consts::TAU;

use glam::DVec3;

use super::row::{Row, Spacing};
use crate::mesh::TessellationOptions;

/// Share of the tolerance the rows aim at: room for the evaluated vertices'
/// rounding against the ideal points the rows are chosen on.
const SHARE: f64 = 0.9999;

/// What every triangle of the rows must hold on the sphere of radius `r`
/// about the origin: the chordal tolerance (its [`SHARE`]) and, as an edge
/// length, the angle limit (the normals at an edge's ends, exact on a sphere,
/// turn by the edge's central angle 2·asin(c / 2r)) and the edge length limit.
pub(super) struct Bound {
    pub r: f64,
    pub tolerance: f64,
    pub max_chord: f64,
}

impl Bound {
    pub fn new(r: f64, options: &TessellationOptions) -> Self {
        let by_angle = options
            .angle_tolerance
            .map(f64::to_radians)
            .filter(|a| *a < std::f64::consts::PI)
            .map_or(f64::INFINITY, |a| 2.0 * r * (0.5 * a).sin());
        let max_chord = by_angle.min(options.max_edge_length.unwrap_or(f64::INFINITY));
        Self {
            r,
            tolerance: SHARE * options.tolerance.min(r),
            max_chord: max_chord * SHARE,
        }
    }

    /// How far triangle `p` is within the limits, in mm (negative: beyond
    /// them): the least of the tolerance less its deviation and the edge
    /// limit less its longest edge.
    #[inline]
    pub fn slack(&self, p: [DVec3; 3]) -> f64 {
        let longest = (0..3)
            .map(|i| p[i].distance_squared(p[(i + 1) % 3]))
            .fold(0.0, f64::max)
            .sqrt();
        (self.tolerance - deviation(self.r, p)).min(self.max_chord - longest)
    }

    /// The circumradius of a triangle on the sphere at the tolerance.
    fn rho(&self) -> f64 {
        let t = self.tolerance;
        (2.0 * self.r * t - t * t).max(0.0).sqrt()
    }

    /// The largest distance from an edge of length `c` to the opposite vertex
    /// of a triangle within the limits: with its circumradius at most ρ when
    /// acute (the apex at most ρ + √(ρ² − c²/4) from the edge), its longest
    /// edge at most 2ρ when not (less), every edge at most `max_chord`;
    /// `None` when the edge alone is beyond them.
    pub fn reach(&self, c: f64) -> Option<f64> {
        let rho = self.rho();
        let half = 0.5 * c;
        (half <= rho && c <= self.max_chord)
            .then(|| (rho + (rho * rho - half * half).sqrt()).min(self.max_chord))
    }
}

/// The least [`Bound::slack`] of the triangles of the zip of rows `a` and `b`
/// (each seam to seam, by the shorter diagonal as `structured::zip` takes
/// it); with `first_failure`, the first negative slack met instead, if any
/// (a cheaper "no").
///
/// Both rows are uniform, so a turn by 2π/g (g the greatest common divisor of
/// their counts) maps the pair onto itself away from the seam's extra
/// vertices, and the zip's choices (by lengths alone) with it: the zip is
/// followed over the first such period and two steps, then carried whole
/// periods on (every triangle skipped is a turn of one measured) to two steps
/// before the seam's end, and followed again from there.
pub(super) fn zip_slack(
    bound: &Bound,
    (ra, sa): (Row, &Spacing),
    (rb, sb): (Row, &Spacing),
    first_failure: bool,
) -> f64 {
    let (at, bt) = (sa.at(bound.r, ra.phi), sb.at(bound.r, rb.phi));
    let a = |i: usize| sa.vertex(at, i);
    let b = |j: usize| sb.vertex(bt, j);
    let (na, nb) = (sa.segments(), sb.segments());
    let step = TAU / ra.count.min(rb.count) as f64;
    let g = gcd(ra.count, rb.count);
    let period = TAU / g as f64;
    let (from, to) = (period + 2.0 * step, TAU - 2.0 * step);
    let (per_a, per_b) = (ra.count / g, rb.count / g);
    let (mut i, mut j) = (0usize, 0usize);
    let mut carried = false;
    let mut least = f64::INFINITY;
    while i < na || j < nb {
        if !carried && sa.lams[i] > from && sb.lams[j] > from {
            carried = true;
            let ahead = sa.lams[i].max(sb.lams[j]);
            let k = ((to - 2.0 * step - ahead) / period).floor();
            if k >= 1.0 {
                i += k as usize * per_a;
                j += k as usize * per_b;
            }
        }
        let advance_a = if i == na {
            false
        } else if j == nb {
            true
        } else {
            a(i + 1).distance_squared(b(j)) <= a(i).distance_squared(b(j + 1))
        };
        let tri = if advance_a {
            i += 1;
            [a(i - 1), a(i), b(j)]
        } else {
            j += 1;
            [a(i), b(j), b(j - 1)]
        };
        least = least.min(bound.slack(tri));
        if first_failure && least < 0.0 {
            break;
        }
    }
    least
}

/// The greatest common divisor of `a` and `b`.
fn gcd(mut a: usize, mut b: usize) -> usize {
    while b != 0 {
        (a, b) = (b, a % b);
    }
    a.max(1)
}

/// The largest distance from the flat triangle `p` (vertices on the sphere of
/// radius `r` about the origin) to the sphere: `r` less the distance from the
/// origin to the triangle's nearest point.
fn deviation(r: f64, p: [DVec3; 3]) -> f64 {
    r - nearest_to_origin(p).length()
}

/// The point of triangle `p` nearest the origin (Ericson, *Real-Time
/// Collision Detection*, 5.1.5).
fn nearest_to_origin([a, b, c]: [DVec3; 3]) -> DVec3 {
    let (ab, ac, ap) = (b - a, c - a, -a);
    let (d1, d2) = (ab.dot(ap), ac.dot(ap));
    if d1 <= 0.0 && d2 <= 0.0 {
        return a;
    }
    let bp = -b;
    let (d3, d4) = (ab.dot(bp), ac.dot(bp));
    if d3 >= 0.0 && d4 <= d3 {
        return b;
    }
    let vc = d1 * d4 - d3 * d2;
    if vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0 {
        return a + ab * (d1 / (d1 - d3));
    }
    let cp = -c;
    let (d5, d6) = (ab.dot(cp), ac.dot(cp));
    if d6 >= 0.0 && d5 <= d6 {
        return c;
    }
    let vb = d5 * d2 - d1 * d6;
    if vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0 {
        return a + ac * (d2 / (d2 - d6));
    }
    let va = d3 * d6 - d5 * d4;
    if va <= 0.0 && d4 - d3 >= 0.0 && d5 - d6 >= 0.0 {
        return b + (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6)));
    }
    let denom = 1.0 / (va + vb + vc);
    a + ab * (vb * denom) + ac * (vc * denom)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The deviation is the closed form R − √(R² − ρ²) for an acute triangle
    /// (ρ its circumradius) and the longest edge's for an obtuse one.
    #[test]
    fn deviation_is_the_whole_triangle_bound() {
        let r = 1000.0;
        let at = |phi: f64, lam: f64| {
            DVec3::new(
                r * phi.sin() * lam.cos(),
                r * phi.sin() * lam.sin(),
                r * phi.cos(),
            )
        };
        // Equilateral about the pole: circumradius r·sin φ.
        let phi = 0.1;
        let tri = [0.0, TAU / 3.0, 2.0 * TAU / 3.0].map(|l| at(phi, l));
        let rho = r * phi.sin();
        let expected = r - (r * r - rho * rho).sqrt();
        assert!((deviation(r, tri) - expected).abs() < 1e-9);
        // Obtuse: two close points and one far round the parallel; the
        // longest edge's half-length decides.
        let tri = [at(phi, 0.0), at(phi, 0.01), at(phi, 2.0)];
        let half = 0.5 * tri[0].distance(tri[2]);
        let expected = r - (r * r - half * half).sqrt();
        assert!((deviation(r, tri) - expected).abs() < 1e-9);
    }

    /// The reach of an edge is where an isosceles triangle on it meets the
    /// tolerance.
    #[test]
    fn an_isosceles_triangle_at_the_reach_is_at_the_tolerance() {
        let bound = Bound {
            r: 1000.0,
            tolerance: 1.0,
            max_chord: f64::INFINITY,
        };
        let c = 50.0;
        let y = bound.reach(c).unwrap();
        // The triangle in a plane at distance d from the centre: its
        // circumcircle there has radius √(r² − d²).
        let d = (bound.r * bound.r - bound.rho() * bound.rho()).sqrt();
        let tri = |y: f64| {
            let k = y - bound.rho();
            [
                DVec3::new(-0.5 * c, -k, d),
                DVec3::new(0.5 * c, -k, d),
                DVec3::new(0.0, y - k, d),
            ]
        };
        for p in tri(y) {
            assert!((p.length() - bound.r).abs() < 1e-9, "{p}");
        }
        assert!(bound.slack(tri(y)).abs() < 1e-9);
    }
}
