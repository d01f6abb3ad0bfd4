//! Point inversion: the closest point of a curve or surface to a given point
//! (Piegl & Tiller §6.1), with the parameters where it lies.
//!
//! Queries come from picking, snapping and tests that recover parameters of points
//! on a patch. Each query samples the curve or surface on a grid of a few points per
//! Bézier span, starts a Newton iteration from the best local minima of the sampled
//! distance, and returns the best result. Newton minimizes ½|S − P|²: steps are
//! damped by backtracking so the distance never increases (beyond rounding), parameters stay in the
//! domain (a step that leaves it is projected onto the boundary, and a variable held
//! at a bound by the gradient is dropped from the Newton system) and wrap around on
//! a closed direction (the u seam of a revolved patch). Seeds are moved off
//! degenerate edges (a head's pole, where S_u = 0) onto the nearest sample ring, and
//! where the Hessian is not positive definite the Gauss–Newton matrix, or its
//! diagonal, is used instead.
//!
//! `search` holds what both share: tolerances, domain handling, sampling and the
//! line search; `curve` and `surface` the two queries.

mod curve;
mod search;
mod surface;

pub use curve::CurveProjection;
pub use surface::SurfaceProjection;
