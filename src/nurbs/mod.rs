//! The NURBS kernel: knot vectors, basis functions, rational curves and surfaces.
//!
//! This is the bottom of the data flow: it knows nothing of ECS or vessels. Part
//! builders (`crate::parts`) turn parameters into [`NurbsSurface`] patches with the
//! [`builders`]; the mesher samples them with the batched [`grid`] evaluators; the
//! exporters write their knots and homogeneous control points as they are.
//!
//! Everything is concrete `f64` (`glam::DVec3`/`DVec4`). Rational geometry is stored
//! as B-splines over homogeneous points `(w·x, w·y, w·z, w)`.

mod basis;
pub mod builders;
mod compatible;
mod curve;
mod error;
mod knots;
mod surface;

pub use basis::{MAX_ORDER, basis_derivatives, basis_functions};
pub use compatible::make_compatible;
pub use curve::{CurveDerivatives, NurbsCurve, euclidean, homogeneous};
pub use error::NurbsError;
pub use knots::KnotVector;
pub use surface::{NurbsSurface, Side, SurfaceDerivatives};

/// Highest degree the kernel evaluates (fixed-size stack buffers are sized from it).
pub const MAX_DEGREE: usize = 12;
