//! Basis functions of one parameter direction, evaluated once for a whole grid.
//!
//! A [`GridBasis`] holds, for every grid parameter along one direction, the index of
//! the first control point its basis functions touch, the `p + 1` non-zero basis
//! values and their first derivatives. Values are stored basis-function-major
//! (`values[k * len + j]`) so that the grid kernels read them as contiguous streams.
//! Consecutive parameters in the same knot span are grouped into [`Run`]s: inside a
//! run the control points are fixed and only the basis values change.

use crate::nurbs::KnotVector;
use crate::nurbs::basis::basis_derivatives;

/// Consecutive grid parameters whose basis functions touch the same control points.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) struct Run {
    /// Index of the first of the `p + 1` control points.
    pub first: usize,
    /// First grid index of the run.
    pub start: usize,
    /// One past the last grid index of the run.
    pub end: usize,
}

/// Non-zero basis functions and first derivatives of one knot vector at a list of
/// parameters: one direction of a tensor grid, computed once and reused for every
/// row or column of the grid (and for every surface with the same knot vector).
///
/// Parameters are clamped into the knot vector's domain exactly as
/// [`NurbsSurface::point`](crate::nurbs::NurbsSurface::point) does (NaN maps to the
/// domain start). Any order is accepted; increasing parameters are evaluated fastest,
/// because neighbours in one knot span share their control points.
///
/// Cost: one span search and one basis evaluation (P&T A2.3) per parameter, and
/// `2 (p + 1)` floats of storage per parameter.
#[derive(Clone, Debug, PartialEq)]
pub struct GridBasis {
    knots: KnotVector,
    params: Vec<f64>,
    runs: Vec<Run>,
    values: Vec<f64>,
    derivatives: Vec<f64>,
}

impl GridBasis {
    /// The basis of `knots` at every parameter of `params` (clamped to the domain).
    pub fn new(knots: &KnotVector, params: &[f64]) -> Self {
        let p = knots.degree();
        let order = p + 1;
        let len = params.len();
        let mut clamped = Vec::with_capacity(len);
        let mut runs: Vec<Run> = Vec::new();
        let mut values = vec![0.0; order * len];
        let mut derivatives = vec![0.0; order * len];
        for (j, &raw) in params.iter().enumerate() {
            let t = knots.clamp(raw);
            let span = knots.find_span(t);
            let [value, derivative] = basis_derivatives::<2>(knots.as_slice(), span, t, p);
            for k in 0..order {
                values[k * len + j] = value[k];
                derivatives[k * len + j] = derivative[k];
            }
            let first = span - p;
            match runs.last_mut() {
                Some(run) if run.first == first => run.end = j + 1,
                _ => runs.push(Run {
                    first,
                    start: j,
                    end: j + 1,
                }),
            }
            clamped.push(t);
        }
        Self {
            knots: knots.clone(),
            params: clamped,
            runs,
            values,
            derivatives,
        }
    }

    /// The knot vector the basis was computed for.
    #[inline]
    pub fn knots(&self) -> &KnotVector {
        &self.knots
    }

    /// True when this basis was computed for `knots` (and so fits a surface direction
    /// with that knot vector).
    #[inline]
    pub fn fits(&self, knots: &KnotVector) -> bool {
        self.knots == *knots
    }

    /// The grid parameters, clamped to the domain.
    #[inline]
    pub fn params(&self) -> &[f64] {
        &self.params
    }

    /// Number of grid parameters.
    #[inline]
    pub fn len(&self) -> usize {
        self.params.len()
    }

    /// True when the grid has no parameter in this direction.
    #[inline]
    pub fn is_empty(&self) -> bool {
        self.params.is_empty()
    }

    /// Number of non-zero basis functions per parameter: degree + 1.
    #[inline]
    pub(super) fn order(&self) -> usize {
        self.knots.degree() + 1
    }

    /// The runs of parameters sharing their control points, in grid order.
    #[inline]
    pub(super) fn runs(&self) -> &[Run] {
        &self.runs
    }

    /// Basis values, `values[k * len + j]` for function `k` at parameter `j`.
    #[inline]
    pub(super) fn values(&self) -> &[f64] {
        &self.values
    }

    /// First derivatives, laid out like [`values`](Self::values).
    #[inline]
    pub(super) fn derivatives(&self) -> &[f64] {
        &self.derivatives
    }
}
