//! The NURBS kernel: knot vectors, basis functions, rational curves and surfaces.
//!
//! This is the bottom of the data flow: it knows nothing of ECS or vessels. Part
//! builders (`crate::parts`) turn parameters into [`NurbsSurface`] patches with the
//! [`builders`]; the mesher samples them with the batched [`grid`] evaluators; the
//! exporters write their knots and homogeneous control points as they are.
//!
//! Everything is concrete `f64` (`glam::DVec3`/`DVec4`). Rational geometry is stored
//! as B-splines over homogeneous points `(w·x, w·y, w·z, w)`.

mod arc_length;
mod basis;
mod bbox;
pub mod builders;
mod compatible;
mod curve;
mod elevate;
mod error;
mod gauss;
pub mod grid;
mod integrals;
pub mod intersect;
mod inversion;
mod join;
mod knots;
mod refine;
mod row;
mod surface;
mod transform;

pub use basis::{MAX_ORDER, SMALL_ORDER, basis_derivatives, basis_derivatives_in, basis_functions};
pub use bbox::Aabb;
pub use compatible::make_compatible;
pub use curve::{CurveDerivatives, NurbsCurve, euclidean, homogeneous};
pub use error::NurbsError;
pub use gauss::GaussLegendre;
pub use intersect::{
    GeneratorHit, IntersectionLoop, MAX_TURNING_ANGLE, intersect_generator, neck_host_intersection,
};
pub use inversion::{CurveProjection, SurfaceProjection};
pub use knots::KnotVector;
pub use row::SurfaceRow;
pub use surface::{FirstDerivatives, NurbsSurface, Side, SurfaceDerivatives};
pub use transform::{MIN_PROJECTION_COSINE, ParallelProjection};

/// Highest degree the kernel evaluates (fixed-size stack buffers are sized from it).
pub const MAX_DEGREE: usize = 12;
