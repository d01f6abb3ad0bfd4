//! Arc length of rational curves: ∫|C′(u)| du by Gauss–Legendre quadrature.
//!
//! The speed |C′| is smooth inside each Bézier span but not across knots, so the
//! integral is taken span by span, each span refined adaptively (halving until two
//! levels agree to [`RELATIVE_TOLERANCE`]). Consumers are measurement queries (profile
//! lengths, developed widths) and tests of the exact builders; nothing in the meshing
//! path depends on it.

use std::sync::OnceLock;

use glam::DVec3;

use super::{GaussLegendre, NurbsCurve};

/// Nodes of the rule applied to every interval.
const ORDER: usize = 16;

/// An interval is accepted when its estimate and the sum of its halves' estimates
/// differ by at most this fraction of the latter.
const RELATIVE_TOLERANCE: f64 = 1e-13;

/// Deepest halving of a span (a 2⁻²⁰ fraction of it): a bound on the work for
/// integrands that are not smooth (a cusp where C′ = 0).
const MAX_DEPTH: u32 = 20;

/// The rule shared by every arc-length query, computed on first use.
fn rule() -> &'static GaussLegendre {
    static RULE: OnceLock<GaussLegendre> = OnceLock::new();
    RULE.get_or_init(|| GaussLegendre::new(ORDER))
}

impl NurbsCurve {
    /// Length of the whole curve, to about 1e-13 relative.
    pub fn arc_length(&self) -> f64 {
        let (a, b) = self.domain();
        self.arc_length_between(a, b)
    }

    /// Length of the piece between parameters `u0` and `u1` (in either order; both
    /// are clamped to the domain), to about 1e-13 relative. NaN if either is NaN.
    pub fn arc_length_between(&self, u0: f64, u1: f64) -> f64 {
        if u0.is_nan() || u1.is_nan() {
            return f64::NAN;
        }
        let (a, b) = (self.knots().clamp(u0), self.knots().clamp(u1));
        let (low, high) = if a <= b { (a, b) } else { (b, a) };
        let mut total = 0.0;
        for (s0, s1) in self.knots().spans() {
            let (x0, x1) = (s0.max(low), s1.min(high));
            if x1 > x0 {
                let whole = rule().integrate(x0, x1, |u| self.speed(u));
                total += self.refine_length(x0, x1, whole, 0);
            }
        }
        total
    }

    /// |C′(u)| from the first homogeneous derivatives.
    fn speed(&self, u: f64) -> f64 {
        let [a0, a1] = self.homogeneous_derivatives::<2>(u);
        let point: DVec3 = a0.truncate() / a0.w;
        ((a1.truncate() - a1.w * point) / a0.w).length()
    }

    /// Adaptive refinement of one interval inside a span whose whole-interval
    /// estimate is `whole`.
    fn refine_length(&self, a: f64, b: f64, whole: f64, depth: u32) -> f64 {
        let m = 0.5 * (a + b);
        let left = rule().integrate(a, m, |u| self.speed(u));
        let right = rule().integrate(m, b, |u| self.speed(u));
        let halves = left + right;
        if depth >= MAX_DEPTH || (halves - whole).abs() <= RELATIVE_TOLERANCE * halves {
            halves
        } else {
            self.refine_length(a, m, left, depth + 1) + self.refine_length(m, b, right, depth + 1)
        }
    }
}

#[cfg(test)]
mod tests {
    use std::f64::consts::PI;

    use super::*;
    use crate::nurbs::builders::{circular_arc, line};

    #[test]
    fn quarter_arc_and_line() {
        let arc = circular_arc(DVec3::ZERO, DVec3::X, DVec3::Y, 2.0, 0.0, PI / 2.0).unwrap();
        assert!((arc.arc_length() - PI).abs() < 1e-14 * PI);
        let l = line(DVec3::ZERO, DVec3::new(3.0, 4.0, 0.0)).unwrap();
        assert!((l.arc_length() - 5.0).abs() < 1e-15);
        assert!((l.arc_length_between(0.8, 0.2) - 3.0).abs() < 1e-14);
        assert!(l.arc_length_between(f64::NAN, 0.5).is_nan());
    }
}
