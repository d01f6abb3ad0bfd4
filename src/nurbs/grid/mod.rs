//! Batched evaluation of a surface on a tensor grid of parameters: the mesher's hot
//! path.
//!
//! Evaluating `S(u, v)` point by point recomputes the same basis functions for every
//! row and column and contracts `(p + 1)(q + 1)` control points per point. On a grid
//! `us × vs` the work factors:
//!
//! 1. [`GridBasis`]: the basis values and first derivatives of each direction are
//!    computed once per grid parameter (not once per point);
//! 2. per u row, the control net is contracted with that row's u basis into the
//!    homogeneous control points of the isocurve `S(u_i, ·)` (and with the u-derivative
//!    basis, for normals);
//! 3. per grid point only a `(q + 1)`-term contraction with the precomputed v basis
//!    and one projective division remain (for normals: value, ∂/∂u and ∂/∂v, the
//!    quotient rule, a cross product and a normalization).
//!
//! Results equal [`NurbsSurface::point`](super::NurbsSurface::point) and
//! [`NurbsSurface::normal`](super::NurbsSurface::normal) to rounding, including the
//! limit normals at degenerate edges. Output is row-major, `index = i * vs.len() + j`.

mod basis;
mod evaluate;
mod kernel;
mod normals;

pub use basis::GridBasis;

use thiserror::Error;

/// What can be wrong with precomputed grid bases handed to a surface.
#[derive(Debug, Error, Clone, PartialEq, Eq)]
pub enum GridError {
    /// A [`GridBasis`] was computed for another knot vector than the surface's.
    #[error("the {direction} grid basis was computed for another knot vector than the surface's")]
    KnotsMismatch {
        /// `"u"` or `"v"`.
        direction: &'static str,
    },
}
