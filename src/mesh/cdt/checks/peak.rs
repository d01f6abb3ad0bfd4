//! Where between its probes a flat triangle departs most from a curved surface:
//! the probe that makes the chordal measure hold on every point of the triangle,
//! not only at its centroid and edge midpoints.
//!
//! **The quadratic model.** Let T have its vertices `p_i` on the surface and unit
//! normal `n`. Near T the surface is the graph of a height `f` over T's plane,
//! `f(p_i) = 0`, and a point `x` of T is at most `|f(x)|` from the surface (the
//! point `x + f(x) n` is on it). To second order `f` is a quadratic `q`; vanishing
//! at the vertices, `q` is fixed by its values `m_i` at the three edge midpoints
//! (the quadratic Lagrange element): in barycentric coordinates
//! `q = 4 (m_0 λ_0 λ_1 + m_1 λ_1 λ_2 + m_2 λ_2 λ_0)`, `m_i` the midpoint of the edge
//! from vertex `i` to `i + 1`. On an edge `q = 4 m t (1 − t)` peaks at the
//! midpoint. Inside, `q`'s Hessian is `H`, the surface's second fundamental form
//! seen from the plane; `q = ½ (R² − |x − c|²_H)` for the circumcircle `(c, R)`
//! of T in the metric `|H|`. When `H` is indefinite (a saddle) the only
//! stationary point is a saddle and `|q|` peaks on the boundary, at a midpoint.
//! When it is definite (every head: spheres, spheroids, the outer half of a
//! torus) `|q|` peaks at the metric circumcentre `c` if T (in that metric) is
//! acute, with value `½ R²`, else at the longest edge's midpoint.
//!
//! **Why the centroid and midpoints miss it.** For an acute triangle with
//! angles `α ≥ β ≥ γ` in the metric, a midpoint sees `½ R² sin²` of its opposite
//! angle and the centroid `½ R² · 4 (sin²α + sin²β + sin²γ) / 9` (Euler:
//! `|c − g|² = R² − (a² + b² + c²) / 9`). The larger of these is smallest,
//! `15/16` of the peak, for the isosceles triangle with `sin² α = 15/16`
//! (α = β ≈ 75.5°, γ ≈ 29°): probes held to the tolerance let the triangle reach
//! `16/15 ≈ 1.067` times it. Metric-Delaunay meshes are full of such triangles;
//! measured, the worst were 1.048× (issue 30).
//!
//! **Beyond the quadratic.** Where the curvature changes across a triangle (a
//! 2:1 ellipsoid near its knuckle, where it changes eightfold from the pole to
//! the equator; a knuckle's parallels) the cubic part of `f` shifts the peak
//! off the midpoint of an edge and off the quadratic's centre: a triangle whose
//! midpoints measured 0.996, 0.660 and 0.543 of the tolerance and its centroid
//! 0.977 reached 1.027 (the quadratic model through the midpoints predicted 0.81).
//!
//! **The peak probe.** So a triangle whose plain probes (centroid, midpoints)
//! pass [`PEAK_GATE`] of the tolerance, or that has a loop segment (whose
//! midpoint is not probed), gets a cubic model of `f`: the cubic Lagrange
//! element, through its vertices (height 0), the signed heights of S over its
//! plane at the third points of every edge and its centroid's ([`Cubic`]). The
//! model's largest `|f|` is found on the polynomial alone, exactly up to
//! rounding (closed form on the edges, Newton's method inside from the best
//! of a few lattice points: [`Cubic::peak`]), and the surface's true distance
//! is then measured at that point like at any probe. The model equals `f` up to `r = O(h⁴)` (h the
//! triangle's size), so at the true maximiser `x̂` and the probe `x*`:
//! `f(x̂) ≤ p(x̂) + |r| ≤ p(x*) + |r| ≤ f(x*) + 2|r|`: the measure at the peak
//! misses the largest deviation by `O(h⁴)`, two orders below the deviation
//! itself (`O(h²)`), where the centroid and midpoints missed a sixteenth of it
//! and more. A triangle whose plain probes stay under the gate is not modelled:
//! its quadratic part peaks at most 16/15 of the gate, 0.853 of the tolerance.
//! The dense check (`tests/mesh_chordal.rs`: 45 barycentric points per
//! triangle, then a local climb to the maximum, every head kind at 5, 1, 0.1
//! and 0.01 mm) measures what remains. Planes, cylinders and spheres need none
//! of this: their closed-form bound (`certify`) is the largest distance itself.

use glam::{DVec2, DVec3};

/// Share of the tolerance the plain probes must pass before the cubic model is
/// built and its peak probed: under it, the quadratic part's peak is at most
/// 16/15 of it, 0.853 of the tolerance, leaving 15 % for the cubic and higher
/// terms.
pub(in crate::mesh::cdt) const PEAK_GATE: f64 = 0.8;

/// Where on an edge the cubic model is sampled, from its first vertex.
pub(in crate::mesh::cdt) const THIRDS: [f64; 2] = [1.0 / 3.0, 2.0 / 3.0];

/// The cubic vanishing at a triangle's vertices through given heights at its
/// edges' third points and its centroid (the cubic Lagrange element):
/// `f = Σ λ_i λ_j (a_ij λ_i + b_ij λ_j) + c λ_0 λ_1 λ_2` over the edges
/// `i → j = i + 1`.
#[derive(Clone, Copy, Debug)]
pub(in crate::mesh::cdt) struct Cubic {
    /// Per edge `i → i + 1`, the coefficients of `λ_i² λ_j` and `λ_i λ_j²`.
    edges: [[f64; 2]; 3],
    /// The coefficient of the bubble `λ_0 λ_1 λ_2`.
    bubble: f64,
}

impl Cubic {
    /// The cubic with heights `thirds[i]` at [`THIRDS`] along edge `i → i + 1`
    /// and `centroid` at the centroid. Along an edge `f = s (1 − s)(a (1 − s) + b s)`,
    /// so `f(⅓) = 2 (2a + b) / 27` and `f(⅔) = 2 (a + 2b) / 27`; at the centroid
    /// `f = (Σ (a + b) + c) / 27`.
    pub fn new(thirds: [[f64; 2]; 3], centroid: f64) -> Self {
        let edges = thirds.map(|[f1, f2]| [4.5 * (2.0 * f1 - f2), 4.5 * (2.0 * f2 - f1)]);
        let sum: f64 = edges.iter().map(|[a, b]| a + b).sum();
        Self {
            edges,
            bubble: 27.0 * centroid - sum,
        }
    }

    /// The model's value at barycentric coordinates `l`.
    pub fn value(&self, l: [f64; 3]) -> f64 {
        let mut f = self.bubble * l[0] * l[1] * l[2];
        for (i, [a, b]) in self.edges.iter().enumerate() {
            let (x, y) = (l[i], l[(i + 1) % 3]);
            f += x * y * (a * x + b * y);
        }
        f
    }

    /// The model's gradient and Hessian in the homogeneous barycentric
    /// coordinates at `l` (each `λ_k` taken as free).
    fn derivatives(&self, l: [f64; 3]) -> ([f64; 3], [[f64; 3]; 3]) {
        let c = self.bubble;
        let mut g = [c * l[1] * l[2], c * l[0] * l[2], c * l[0] * l[1]];
        let mut h = [
            [0.0, c * l[2], c * l[1]],
            [c * l[2], 0.0, c * l[0]],
            [c * l[1], c * l[0], 0.0],
        ];
        for (i, [a, b]) in self.edges.iter().enumerate() {
            let j = (i + 1) % 3;
            let (x, y) = (l[i], l[j]);
            g[i] += 2.0 * a * x * y + b * y * y;
            g[j] += a * x * x + 2.0 * b * x * y;
            h[i][i] += 2.0 * a * y;
            h[j][j] += 2.0 * b * x;
            let cross = 2.0 * (a * x + b * y);
            h[i][j] += cross;
            h[j][i] += cross;
        }
        (g, h)
    }

    /// Where `|f|` is largest over the triangle and its value there, exact up
    /// to rounding: the largest of the edges' stationary points (closed form:
    /// along an edge `f` is a cubic of one variable) and of the interior's,
    /// found by Newton's method on the gradient from the best point of a
    /// 6th-subdivision lattice (the model is a polynomial: no surface is
    /// evaluated). On a model that is nearly a quadratic (every triangle the
    /// screen meets) `|f|` has one interior stationary point, reached in a few
    /// steps from the lattice's best.
    pub fn peak(&self) -> ([f64; 3], f64) {
        let mut best = ([1.0 / 3.0; 3], self.value([1.0 / 3.0; 3]).abs());
        let consider = |l: [f64; 3], best: &mut ([f64; 3], f64)| {
            let f = self.value(l).abs();
            if f > best.1 {
                *best = (l, f);
            }
        };
        // Edges: f(s) = s (1 − s)(a (1 − s) + b s) from vertex i, whose
        // derivative is 3 (a − b) s² + (2b − 4a) s + a.
        for (i, &[a, b]) in self.edges.iter().enumerate() {
            let (qa, qb, qc) = (3.0 * (a - b), 2.0 * b - 4.0 * a, a);
            let roots = if qa.abs() <= 1e-12 * (a.abs() + b.abs()) {
                [-qc / qb, f64::NAN]
            } else {
                let disc = qb * qb - 4.0 * qa * qc;
                if disc < 0.0 {
                    [f64::NAN; 2]
                } else {
                    let r = disc.sqrt();
                    [(-qb - r) / (2.0 * qa), (-qb + r) / (2.0 * qa)]
                }
            };
            for s in roots {
                if (0.0..=1.0).contains(&s) {
                    let mut l = [0.0; 3];
                    l[i] = 1.0 - s;
                    l[(i + 1) % 3] = s;
                    consider(l, &mut best);
                }
            }
        }
        // Interior: the best interior point of the lattice, then Newton.
        const N: usize = 6;
        let mut seed = ([1.0 / 3.0; 3], self.value([1.0 / 3.0; 3]).abs());
        for i in 1..N {
            for j in 1..N - i {
                let l = [i, j, N - i - j].map(|x| x as f64 / N as f64);
                let f = self.value(l).abs();
                if f > seed.1 {
                    seed = (l, f);
                }
            }
        }
        consider(seed.0, &mut best);
        let mut l = seed.0;
        for _ in 0..8 {
            // In the plane Σλ = 1 along e1 = (−1, 1, 0) and e2 = (−1, 0, 1).
            let (g, h) = self.derivatives(l);
            let (g1, g2) = (g[1] - g[0], g[2] - g[0]);
            let h11 = h[1][1] - 2.0 * h[0][1] + h[0][0];
            let h22 = h[2][2] - 2.0 * h[0][2] + h[0][0];
            let h12 = h[1][2] - h[0][1] - h[0][2] + h[0][0];
            let det = h11 * h22 - h12 * h12;
            if det == 0.0 || !det.is_finite() {
                break;
            }
            let d1 = (h22 * g1 - h12 * g2) / det;
            let d2 = (h11 * g2 - h12 * g1) / det;
            let next = [l[0] + d1 + d2, l[1] - d1, l[2] - d2];
            if next.iter().any(|&x| x.is_nan() || x < 0.0) {
                break;
            }
            l = next;
            if d1.abs() + d2.abs() <= 1e-13 {
                break;
            }
        }
        consider(l, &mut best);
        best
    }
}

/// The 3D point of barycentric coordinates `l` in triangle `p`.
pub(in crate::mesh::cdt) fn point_at(p: [DVec3; 3], l: [f64; 3]) -> DVec3 {
    p[0] * l[0] + p[1] * l[1] + p[2] * l[2]
}

/// The parameters of barycentric coordinates `l` among `uv`.
pub(in crate::mesh::cdt) fn uv_at(uv: [DVec2; 3], l: [f64; 3]) -> DVec2 {
    uv[0] * l[0] + uv[1] * l[1] + uv[2] * l[2]
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The largest |f| over the unit-coordinate triangle by dense sampling.
    fn sampled_max(f: &impl Fn([f64; 3]) -> f64) -> f64 {
        let n = 600;
        let mut best: f64 = 0.0;
        for i in 0..=n {
            for j in 0..=n - i {
                let l = [i, j, n - i - j].map(|x| x as f64 / n as f64);
                best = best.max(f(l).abs());
            }
        }
        best
    }

    /// The model built from a cubic's own values is that cubic, and its peak
    /// is the cubic's largest |value| over the triangle: bowls, saddles and
    /// lopsided cubics.
    #[test]
    fn the_model_of_a_cubic_is_exact_and_its_peak_the_maximum() {
        let cubics: [fn([f64; 3]) -> f64; 4] = [
            |l| l[0] * l[1] + l[1] * l[2] + l[2] * l[0],
            |l| l[0] * l[1] - 0.7 * l[1] * l[2] + 0.2 * l[2] * l[0],
            |l| {
                l[0] * l[1] * (3.0 * l[0] + 0.2 * l[1])
                    + 0.5 * l[1] * l[2]
                    + 4.0 * l[0] * l[1] * l[2]
            },
            |l| -(l[0] * l[1] * l[1]) + 2.0 * l[2] * l[2] * l[0] - l[0] * l[1] * l[2],
        ];
        for f in cubics {
            let at = |i: usize, s: f64| {
                let mut l = [0.0; 3];
                l[i] = 1.0 - s;
                l[(i + 1) % 3] = s;
                f(l)
            };
            let thirds = [0, 1, 2].map(|i| THIRDS.map(|s| at(i, s)));
            let model = Cubic::new(thirds, f([1.0 / 3.0; 3]));
            for l in [[0.2, 0.3, 0.5], [0.6, 0.1, 0.3], [0.0, 0.25, 0.75]] {
                assert!((model.value(l) - f(l)).abs() < 1e-12);
            }
            let (l, value) = model.peak();
            let sampled = sampled_max(&f);
            assert!((f(l).abs() - value).abs() < 1e-12);
            assert!(value >= sampled - 1e-9, "{value} < {sampled}");
        }
    }

    /// The triangle that hides most from the centroid and midpoints: on a
    /// paraboloid they see 15/16 of its peak, which the model finds.
    #[test]
    fn probes_alone_miss_a_sixteenth() {
        // Isosceles with sin²α = 15/16 at the base angles, on the unit circle
        // (central angles twice the opposite angles).
        let alpha = (15.0f64 / 16.0).sqrt().asin();
        let gamma = std::f64::consts::PI - 2.0 * alpha;
        let a = [0.0, 2.0 * alpha, 2.0 * alpha + 2.0 * gamma];
        let p = a.map(|t: f64| DVec2::new(t.cos(), t.sin()));
        let height = |x: DVec2| 0.5 * (1.0 - x.length_squared());
        let f = |l: [f64; 3]| height(p[0] * l[0] + p[1] * l[1] + p[2] * l[2]);
        let along = |i: usize, s: f64| height(p[i] * (1.0 - s) + p[(i + 1) % 3] * s);
        let probes = [0, 1, 2]
            .map(|i| along(i, 0.5))
            .into_iter()
            .fold(f([1.0 / 3.0; 3]), f64::max);
        let model = Cubic::new(
            [0, 1, 2].map(|i| THIRDS.map(|s| along(i, s))),
            f([1.0 / 3.0; 3]),
        );
        let (_, value) = model.peak();
        assert!((value - 0.5).abs() < 1e-12, "{value}");
        assert!(
            (probes / value - 15.0 / 16.0).abs() < 1e-5,
            "{}",
            probes / value
        );
    }

    /// On models like the screen's (a quadratic bowl or saddle from three
    /// midpoint heights, plus a cubic part up to a third of it) the peak is the
    /// largest |value| over the triangle to rounding, not to a search's step:
    /// checked against dense sampling climbed by Newton's method's own
    /// stationarity (the gradient along the triangle vanishes at an interior
    /// peak).
    #[test]
    fn the_peak_is_exact_on_near_quadratic_models() {
        let mut state = 0x9e37_79b9_7f4a_7c15_u64;
        let mut random = || {
            state = state
                .wrapping_mul(6_364_136_223_846_793_005)
                .wrapping_add(1_442_695_040_888_963_407);
            (state >> 11) as f64 / (1u64 << 53) as f64
        };
        for case in 0..500 {
            let m = [0, 1, 2].map(|_| {
                if case % 5 == 0 {
                    2.0 * random() - 1.0
                } else {
                    0.3 + random()
                }
            });
            let cubic: [f64; 10] = std::array::from_fn(|_| (2.0 * random() - 1.0) / 3.0);
            let f = |l: [f64; 3]| {
                let quadratic =
                    4.0 * (m[0] * l[0] * l[1] + m[1] * l[1] * l[2] + m[2] * l[2] * l[0]);
                let mut third = cubic[9] * l[0] * l[1] * l[2];
                for i in 0..3 {
                    let (x, y) = (l[i], l[(i + 1) % 3]);
                    third += x * y * (cubic[2 * i] * x + cubic[2 * i + 1] * y);
                }
                quadratic + third
            };
            let at = |i: usize, s: f64| {
                let mut l = [0.0; 3];
                l[i] = 1.0 - s;
                l[(i + 1) % 3] = s;
                f(l)
            };
            let model = Cubic::new(
                [0, 1, 2].map(|i| THIRDS.map(|s| at(i, s))),
                f([1.0 / 3.0; 3]),
            );
            let (l, value) = model.peak();
            assert!((f(l).abs() - value).abs() < 1e-12);
            let sampled = sampled_max(&f);
            assert!(value >= sampled - 1e-12, "case {case}: {value} < {sampled}");
            // Interior: the gradient along the triangle vanishes there.
            if l.iter().all(|&x| x > 1e-9) {
                let (g, _) = model.derivatives(l);
                let scale = m.iter().fold(1.0f64, |s, x| s.max(x.abs()));
                assert!(
                    (g[1] - g[0]).abs() < 1e-10 * scale && (g[2] - g[0]).abs() < 1e-10 * scale,
                    "case {case}: not stationary at {l:?}: {g:?}"
                );
            }
        }
    }
}
