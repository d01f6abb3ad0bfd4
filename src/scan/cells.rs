//! A least-squares round's samples sorted by the knot cell they fall in, so the
//! fit ([`super::fit`]) reads each cell's control points, knots and
//! normal-equation block once for all of its points.
//!
//! Between projection and the banded solve: each round of the fit refines the
//! net, sorts the samples by its cells (a stable counting sort: the order within
//! a cell is the input's), sums each cell's block of the normal equations in
//! parallel, adds the blocks into the band in cell order, and reads the
//! residuals cell by cell. Summing per cell, not per point into the band, keeps
//! a point's 45 products (biquadratic) in registers instead of scattered over
//! the band's rows, and makes the sums independent of the thread count.

use glam::DVec3;
use rayon::prelude::*;

use super::band::Band;
use super::sample::Sample;
use crate::nurbs::{KnotVector, MAX_ORDER, NurbsSurface, basis_functions};

/// The normal equations of one round: `matrix · D = rhs` for the control
/// displacements D (x, y, z), unknowns v-major.
pub(super) struct NormalEquations {
    /// Σ R_k R_l over the samples, banded.
    pub matrix: Band,
    /// Σ R_k · offset, per coordinate.
    pub rhs: Vec<Vec<f64>>,
    /// Σ R_k: zero for a basis function without data in its support.
    pub support: Vec<f64>,
}

/// The residuals of one knot cell.
#[derive(Clone, Copy, Debug, Default)]
pub(super) struct CellResidual {
    /// Samples in the cell.
    pub points: usize,
    /// Σ r² of their normal residuals, mm².
    pub squares: f64,
    /// Largest |r|, mm.
    pub max: f64,
    /// Residuals past the far limit.
    pub far: usize,
}

/// Buckets per knot span of an [`Axis`]'s lookup table.
const BUCKETS_PER_SPAN: usize = 4;

/// The knot spans of one parameter direction inside the domain, with a bucket
/// table that finds a parameter's span in a step or two.
#[derive(Clone, Debug)]
pub(super) struct Axis {
    /// Distinct knots in the domain.
    distinct: Vec<f64>,
    /// The knot vector's span index (`find_span`'s) of each cell.
    spans: Vec<usize>,
    /// A cell at or before the one holding each bucket's parameters.
    table: Vec<usize>,
    /// Buckets per unit parameter.
    scale: f64,
}

impl Axis {
    fn new(knots: &KnotVector) -> Self {
        let (a, b) = knots.domain();
        let all = knots.as_slice();
        let distinct: Vec<f64> = knots
            .distinct()
            .into_iter()
            .filter(|&k| k >= a && k <= b)
            .collect();
        let cells = distinct.len().saturating_sub(1).max(1);
        let spans = (0..cells)
            .map(|c| all.partition_point(|&k| k <= distinct[c]) - 1)
            .collect();
        let buckets = BUCKETS_PER_SPAN * cells;
        let scale = buckets as f64 / (b - a);
        let table = (0..buckets)
            .map(|i| {
                let t = a + i as f64 / scale;
                distinct
                    .partition_point(|&k| k <= t)
                    .saturating_sub(2)
                    .min(cells - 1)
            })
            .collect();
        Self {
            distinct,
            spans,
            table,
            scale,
        }
    }

    /// Number of cells.
    pub(super) fn cells(&self) -> usize {
        self.spans.len()
    }

    /// The cell holding `t`: the span `[k_c, k_{c+1})`, the last one at the
    /// domain's end; `t` is clamped to the domain (NaN to its start), as
    /// [`KnotVector::find_span`] does.
    #[inline]
    pub(super) fn cell(&self, t: f64) -> usize {
        let d = &self.distinct;
        let (a, b) = (d[0], d[d.len() - 1]);
        let t = if t.is_nan() { a } else { t.clamp(a, b) };
        let bucket = (((t - a) * self.scale) as usize).min(self.table.len() - 1);
        let mut c = self.table[bucket];
        while c > 0 && d[c] > t {
            c -= 1;
        }
        while c + 1 < self.spans.len() && d[c + 1] <= t {
            c += 1;
        }
        c
    }

    /// The knot vector's span index of cell `c`.
    #[inline]
    pub(super) fn span(&self, c: usize) -> usize {
        self.spans[c]
    }
}

/// Samples sorted by cell, cells v-major (the unknowns' order).
pub(super) struct Sorted {
    /// u direction.
    pub u: Axis,
    /// v direction.
    pub v: Axis,
    /// The samples, cell by cell.
    pub samples: Vec<Sample>,
    /// `starts[c]..starts[c + 1]` are cell `c`'s samples.
    pub starts: Vec<usize>,
}

impl Sorted {
    /// `samples` sorted by the cells of `surface`'s knots (stable).
    pub(super) fn new(surface: &NurbsSurface, samples: &[Sample]) -> Self {
        let u = Axis::new(surface.u_knots());
        let v = Axis::new(surface.v_knots());
        let cu = u.cells();
        let keys: Vec<u32> = samples
            .par_iter()
            .with_min_len(4096)
            .map(|s| (v.cell(s.v) * cu + u.cell(s.u)) as u32)
            .collect();
        let mut starts = vec![0usize; cu * v.cells() + 1];
        for &k in &keys {
            starts[k as usize + 1] += 1;
        }
        for c in 1..starts.len() {
            starts[c] += starts[c - 1];
        }
        let mut next = starts.clone();
        let mut sorted = samples.to_vec();
        for (s, &k) in samples.iter().zip(&keys) {
            let at = &mut next[k as usize];
            sorted[*at] = *s;
            *at += 1;
        }
        Self {
            u,
            v,
            samples: sorted,
            starts,
        }
    }

    /// Number of cells.
    pub(super) fn cells(&self) -> usize {
        self.starts.len() - 1
    }

    /// Cell `c`'s samples.
    pub(super) fn of(&self, c: usize) -> &[Sample] {
        &self.samples[self.starts[c]..self.starts[c + 1]]
    }

    /// Cell `c`'s knot spans (u, v).
    pub(super) fn spans(&self, c: usize) -> (usize, usize) {
        let cu = self.u.cells();
        (self.u.span(c % cu), self.v.span(c / cu))
    }
}

impl Sorted {
    /// The normal equations of `base` (whose knots sorted the samples) with
    /// `width` sub-diagonals: each cell's block summed over its samples in
    /// parallel, then the blocks added in cell order.
    pub(super) fn normal_equations(&self, base: &NurbsSurface, width: usize) -> NormalEquations {
        let m = (base.u_degree() + 1) * (base.v_degree() + 1);
        // Per cell: the lower triangle of its block, then the right-hand sides
        // (x, y, z) and each basis function's support.
        let triangle = m * (m + 1) / 2;
        let stride = triangle + 4 * m;
        let mut sums = vec![0.0; self.cells() * stride];
        sums.par_chunks_mut(stride)
            .enumerate()
            .with_min_len(16)
            .for_each(|(c, out)| {
                let data = self.of(c);
                if data.is_empty() {
                    return;
                }
                let cell = CellBasis::new(base, self.spans(c));
                let mut r = [0.0; MAX_ORDER * MAX_ORDER];
                let (gram, rest) = out.split_at_mut(triangle);
                let (rx, rest) = rest.split_at_mut(m);
                let (ry, rest) = rest.split_at_mut(m);
                let (rz, support) = rest.split_at_mut(m);
                for s in data {
                    cell.values(s.u, s.v, &mut r);
                    let mut e = 0;
                    for t in 0..m {
                        let a = r[t];
                        for (g, &b) in gram[e..=e + t].iter_mut().zip(&r[..=t]) {
                            *g += a * b;
                        }
                        e += t + 1;
                        rx[t] += a * s.offset.x;
                        ry[t] += a * s.offset.y;
                        rz[t] += a * s.offset.z;
                        support[t] += a;
                    }
                }
            });
        let size = base.u_count() * base.v_count();
        let mut matrix = Band::zeros(size, width);
        let mut rhs = vec![vec![0.0; size]; 3];
        let mut support = vec![0.0; size];
        let mut unknowns = vec![0; m];
        for (c, block) in sums.chunks_exact(stride).enumerate() {
            if self.of(c).is_empty() {
                continue;
            }
            let cell = CellBasis::new(base, self.spans(c));
            for (t, k) in unknowns.iter_mut().enumerate() {
                *k = cell.unknown(t);
            }
            let mut e = 0;
            for t in 0..m {
                for t2 in 0..=t {
                    matrix.add(unknowns[t], unknowns[t2], block[e]);
                    e += 1;
                }
            }
            for (t, &k) in unknowns.iter().enumerate() {
                for (axis, r) in rhs.iter_mut().enumerate() {
                    r[k] += block[triangle + axis * m + t];
                }
                support[k] += block[triangle + 3 * m + t];
            }
        }
        NormalEquations {
            matrix,
            rhs,
            support,
        }
    }

    /// Each cell's normal residuals `(offset − Σ R_k D_k)·normal` for the
    /// solved displacements (`displacements[axis][unknown]`), counting those
    /// past `far`.
    pub(super) fn residuals(
        &self,
        base: &NurbsSurface,
        displacements: &[Vec<f64>],
        far: f64,
    ) -> Vec<CellResidual> {
        let m = (base.u_degree() + 1) * (base.v_degree() + 1);
        (0..self.cells())
            .into_par_iter()
            .with_min_len(16)
            .map(|c| {
                let data = self.of(c);
                if data.is_empty() {
                    return CellResidual::default();
                }
                let cell = CellBasis::new(base, self.spans(c));
                let mut moved = [DVec3::ZERO; MAX_ORDER * MAX_ORDER];
                for (t, d) in moved[..m].iter_mut().enumerate() {
                    let k = cell.unknown(t);
                    *d = DVec3::new(
                        displacements[0][k],
                        displacements[1][k],
                        displacements[2][k],
                    );
                }
                let mut r = [0.0; MAX_ORDER * MAX_ORDER];
                let mut out = CellResidual {
                    points: data.len(),
                    ..CellResidual::default()
                };
                for s in data {
                    cell.values(s.u, s.v, &mut r);
                    let mut fitted = DVec3::ZERO;
                    for (a, d) in r[..m].iter().zip(&moved[..m]) {
                        fitted += *a * *d;
                    }
                    let residual = (s.offset - fitted).dot(s.normal);
                    out.squares += residual * residual;
                    out.max = out.max.max(residual.abs());
                    out.far += usize::from(residual.abs() > far);
                }
                out
            })
            .collect()
    }
}

/// The rational basis of one cell of a surface: its spans, degrees and the
/// weights of its `(p + 1)(q + 1)` control points, b-major (`t = b·(p+1) + a`
/// for control point `(span_u − p + a, span_v − q + b)`).
pub(super) struct CellBasis<'a> {
    surface: &'a NurbsSurface,
    span: (usize, usize),
    weights: [f64; MAX_ORDER * MAX_ORDER],
}

impl<'a> CellBasis<'a> {
    /// The cell with knot spans `span` (u, v).
    pub(super) fn new(surface: &'a NurbsSurface, span: (usize, usize)) -> Self {
        let (p, q) = (surface.u_degree(), surface.v_degree());
        let mut weights = [0.0; MAX_ORDER * MAX_ORDER];
        for b in 0..=q {
            for a in 0..=p {
                weights[b * (p + 1) + a] = surface
                    .homogeneous_point_at(span.0 - p + a, span.1 - q + b)
                    .w;
            }
        }
        Self {
            surface,
            span,
            weights,
        }
    }

    /// The unknown (v-major: `j·n_u + i`) of basis function `t`.
    pub(super) fn unknown(&self, t: usize) -> usize {
        let (p, q) = (self.surface.u_degree(), self.surface.v_degree());
        let (a, b) = (t % (p + 1), t / (p + 1));
        (self.span.1 - q + b) * self.surface.u_count() + self.span.0 - p + a
    }

    /// The rational basis functions at (u, v) into `out[..len]`.
    #[inline]
    pub(super) fn values(&self, u: f64, v: f64, out: &mut [f64; MAX_ORDER * MAX_ORDER]) {
        let s = self.surface;
        let (p, q) = (s.u_degree(), s.v_degree());
        let (uk, vk) = (s.u_knots(), s.v_knots());
        let (u, v) = (uk.clamp(u), vk.clamp(v));
        let nu: [f64; MAX_ORDER] = basis_functions(uk.as_slice(), self.span.0, u, p);
        let nv: [f64; MAX_ORDER] = basis_functions(vk.as_slice(), self.span.1, v, q);
        let mut total = 0.0;
        for (b, nv_b) in nv.iter().enumerate().take(q + 1) {
            for (a, nu_a) in nu.iter().enumerate().take(p + 1) {
                let t = b * (p + 1) + a;
                let w = self.weights[t] * nu_a * nv_b;
                total += w;
                out[t] = w;
            }
        }
        let inverse = 1.0 / total;
        for x in &mut out[..(p + 1) * (q + 1)] {
            *x *= inverse;
        }
    }
}

#[cfg(test)]
#[expect(
    clippy::needless_range_loop,
    reason = "a dense reference assembly by index"
)]
mod tests {
    use super::*;

    /// The per-cell sums equal the normal equations summed point by point
    /// (each point's spans by `find_span`, its rational basis from the
    /// surface's own weights), on a refined full-turn course patch with
    /// random samples, corners and knots included.
    #[test]
    fn cell_sums_are_the_normal_equations() {
        use crate::parts::Shell;
        let patch = Shell {
            outside_diameter: 2000.0,
            length: 3000.0,
        }
        .patches()
        .unwrap()
        .remove(0);
        let base = patch
            .surface
            .elevate_degree_v(1)
            .unwrap()
            .refine_knots_u(&[0.1, 0.3, 0.6, 0.9])
            .unwrap()
            .refine_knots_v(&[0.2, 0.5, 0.7])
            .unwrap();
        let ((u0, u1), (v0, v1)) = base.domain();
        let mut random = crate::scan::Random::new(7);
        let mut samples: Vec<Sample> = (0..3000)
            .map(|_| Sample {
                u: u0 + (u1 - u0) * random.uniform(),
                v: v0 + (v1 - v0) * random.uniform(),
                offset: DVec3::new(random.normal(), random.normal(), random.normal()),
                normal: DVec3::X,
            })
            .collect();
        for (u, v) in [(u0, v0), (u1, v1), (0.5, 0.5), (0.25, v1), (0.3, 0.2)] {
            samples.push(Sample {
                u,
                v,
                offset: DVec3::ONE,
                normal: DVec3::X,
            });
        }
        let (nu, nv) = (base.u_count(), base.v_count());
        let (p, q) = (base.u_degree(), base.v_degree());
        let size = nu * nv;
        let mut dense = vec![vec![0.0; size]; size];
        let mut rhs = vec![vec![0.0; size]; 3];
        for s in &samples {
            let (su, sv) = (base.u_knots().find_span(s.u), base.v_knots().find_span(s.v));
            let bu: [f64; MAX_ORDER] = basis_functions(base.u_knots().as_slice(), su, s.u, p);
            let bv: [f64; MAX_ORDER] = basis_functions(base.v_knots().as_slice(), sv, s.v, q);
            let mut terms = Vec::new();
            for a in 0..=p {
                for b in 0..=q {
                    let (i, j) = (su - p + a, sv - q + b);
                    terms.push((
                        j * nu + i,
                        base.homogeneous_point_at(i, j).w * bu[a] * bv[b],
                    ));
                }
            }
            let total: f64 = terms.iter().map(|t| t.1).sum();
            for &(k, a) in &terms {
                for (axis, r) in rhs.iter_mut().enumerate() {
                    r[k] += a / total * s.offset[axis];
                }
                for &(l, b) in &terms {
                    dense[k][l] += a * b / (total * total);
                }
            }
        }
        let width = (q * nu + p).max(2 * nu);
        let sorted = Sorted::new(&base, &samples);
        let equations = sorted.normal_equations(&base, width);
        let mut compared = 0;
        for k in 0..size {
            for l in k.saturating_sub(width)..=k {
                let expected = dense[k][l];
                let got = equations.matrix.entry(k, l);
                assert!(
                    (got - expected).abs() <= 1e-12 * (1.0 + expected.abs()),
                    "({k}, {l}): {got} vs {expected}"
                );
                compared += usize::from(expected != 0.0);
            }
            for axis in 0..3 {
                let (got, expected) = (equations.rhs[axis][k], rhs[axis][k]);
                assert!(
                    (got - expected).abs() <= 1e-10 * (1.0 + expected.abs()),
                    "rhs {axis} {k}"
                );
            }
        }
        assert!(compared > 5 * size, "{compared} nonzero entries compared");
        // Nothing outside the band.
        for k in 0..size {
            for l in 0..k.saturating_sub(width) {
                assert_eq!(dense[k][l], 0.0, "({k}, {l}) outside the band");
            }
        }
        assert_eq!(sorted.samples.len(), samples.len());
    }

    /// A cell agrees with the knot vector's `find_span` everywhere, knots and
    /// the domain's ends included, for repeated interior knots and uneven spans.
    #[test]
    fn cells_agree_with_find_span() {
        let knots = KnotVector::try_new(
            2,
            vec![
                0.0, 0.0, 0.0, 0.1, 0.25, 0.25, 0.3, 0.7, 0.75, 0.75, 0.9, 1.0, 1.0, 1.0,
            ],
        )
        .unwrap();
        let axis = Axis::new(&knots);
        let mut checked = 0;
        let mut ts: Vec<f64> = (0..=10_000).map(|i| i as f64 / 10_000.0).collect();
        ts.extend(knots.as_slice());
        ts.extend([-0.5, 1.5, f64::NAN, 0.25 - 1e-17, 0.75 + 1e-16]);
        for t in ts {
            let c = axis.cell(t);
            assert_eq!(axis.span(c), knots.find_span(t), "t = {t}");
            checked += 1;
        }
        assert!(checked > 10_000);
        assert_eq!(axis.cells(), 7);
    }
}
