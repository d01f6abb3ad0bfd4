//! Gauss–Legendre quadrature rules.
//!
//! The kernel's integrals (curve arc length, surface area, the volume flux of a
//! patch) are sums of Gauss–Legendre rules over Bézier spans, where the integrands
//! are smooth. A rule of order n integrates polynomials of degree 2n − 1 exactly.
//! Nodes and weights are computed once per rule by Newton's method on the Legendre
//! polynomial Pₙ (three-term recurrence), accurate to a few ulps.

use super::NurbsError;

/// Newton iterations allowed per node (convergence takes 3–6 from the Chebyshev-like
/// initial guess).
const NEWTON_ITERATIONS: usize = 100;

/// An n-point Gauss–Legendre rule on [−1, 1], mapped onto any interval on use.
#[derive(Clone, Debug, PartialEq)]
pub struct GaussLegendre {
    nodes: Vec<f64>,
    weights: Vec<f64>,
}

/// Pₙ(x) and Pₙ′(x) by the three-term recurrence, for |x| < 1.
fn legendre(n: usize, x: f64) -> (f64, f64) {
    let (mut previous, mut current) = (1.0, x);
    for k in 2..=n {
        let k = k as f64;
        let next = ((2.0 * k - 1.0) * x * current - (k - 1.0) * previous) / k;
        previous = current;
        current = next;
    }
    let derivative = n as f64 * (x * current - previous) / (x * x - 1.0);
    (current, derivative)
}

impl GaussLegendre {
    /// Largest order (number of nodes) [`try_new`](Self::try_new) accepts.
    pub const MAX_ORDER: usize = 64;

    /// The rule with `order` nodes, 1 ≤ `order` ≤ [`MAX_ORDER`](Self::MAX_ORDER).
    pub fn try_new(order: usize) -> Result<Self, NurbsError> {
        if order == 0 || order > Self::MAX_ORDER {
            return Err(NurbsError::QuadratureOrderOutOfRange {
                order,
                max: Self::MAX_ORDER,
            });
        }
        let n = order;
        let mut nodes = vec![0.0; n];
        let mut weights = vec![0.0; n];
        for i in 0..n.div_ceil(2) {
            // i-th largest root; initial guess from the asymptotic formula.
            let mut x = (std::f64::consts::PI * (i as f64 + 0.75) / (n as f64 + 0.5)).cos();
            for _ in 0..NEWTON_ITERATIONS {
                let (p, dp) = legendre(n, x);
                let step = p / dp;
                x -= step;
                if step.abs() <= 1e-17 {
                    break;
                }
            }
            if n % 2 == 1 && i == n / 2 {
                x = 0.0;
            }
            let (_, dp) = legendre(n, x);
            let w = 2.0 / ((1.0 - x * x) * dp * dp);
            nodes[n - 1 - i] = x;
            nodes[i] = -x;
            weights[n - 1 - i] = w;
            weights[i] = w;
        }
        Ok(Self { nodes, weights })
    }

    /// The rule with `order` nodes.
    ///
    /// # Panics
    /// If `order` is 0 or above [`MAX_ORDER`](Self::MAX_ORDER): for orders the
    /// program itself chooses, never for user data.
    pub fn new(order: usize) -> Self {
        match Self::try_new(order) {
            Ok(rule) => rule,
            Err(e) => panic!("invalid quadrature rule: {e}"),
        }
    }

    /// Number of nodes.
    #[inline]
    pub fn order(&self) -> usize {
        self.nodes.len()
    }

    /// Nodes on [−1, 1], increasing.
    #[inline]
    pub fn nodes(&self) -> &[f64] {
        &self.nodes
    }

    /// Weights of the nodes on [−1, 1] (they sum to 2).
    #[inline]
    pub fn weights(&self) -> &[f64] {
        &self.weights
    }

    /// Nodes and weights mapped onto [`a`, `b`]: pairs `(x, w)` with
    /// `∫ₐᵇ f ≈ Σ w f(x)`.
    pub fn points_on(&self, a: f64, b: f64) -> impl Iterator<Item = (f64, f64)> + '_ {
        let (mid, half) = (0.5 * (a + b), 0.5 * (b - a));
        self.nodes
            .iter()
            .zip(&self.weights)
            .map(move |(&x, &w)| (mid + half * x, half * w))
    }

    /// The rule's estimate of `∫ₐᵇ f(x) dx`.
    pub fn integrate(&self, a: f64, b: f64, mut f: impl FnMut(f64) -> f64) -> f64 {
        self.points_on(a, b).map(|(x, w)| w * f(x)).sum()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn five_point_rule_matches_the_closed_form() {
        let rule = GaussLegendre::new(5);
        let x2 = (5.0 - 2.0 * (10.0f64 / 7.0).sqrt()).sqrt() / 3.0;
        let w2 = (322.0 + 13.0 * 70f64.sqrt()) / 900.0;
        assert!((rule.nodes()[3] - x2).abs() < 1e-16);
        assert!((rule.weights()[3] - w2).abs() < 1e-15);
        assert_eq!(rule.nodes()[2], 0.0);
        assert!((rule.weights()[2] - 128.0 / 225.0).abs() < 1e-15);
    }

    #[test]
    fn integrates_polynomials_of_degree_2n_minus_1_exactly() {
        for n in 1..=GaussLegendre::MAX_ORDER {
            let rule = GaussLegendre::new(n);
            assert!(
                (rule.weights().iter().sum::<f64>() - 2.0).abs() < 1e-14,
                "{n}"
            );
            assert!(rule.nodes().windows(2).all(|w| w[0] < w[1]));
            for k in [2 * n - 1, (2 * n - 2).min(20)] {
                let k = k as i32;
                let exact = (3f64.powi(k + 1) - 1.0) / (k + 1) as f64;
                let got = rule.integrate(1.0, 3.0, |x| x.powi(k));
                assert!((got - exact).abs() <= 1e-13 * exact, "n={n} k={k}");
            }
        }
    }

    #[test]
    fn rejects_bad_orders() {
        assert!(GaussLegendre::try_new(0).is_err());
        assert!(GaussLegendre::try_new(GaussLegendre::MAX_ORDER + 1).is_err());
    }
}
