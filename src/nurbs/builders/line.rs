//! The straight segment as a degree-1 B-spline: knots {0,0,1,1}, weights 1.

use glam::DVec3;

use super::finite_vec;
use crate::nurbs::{KnotVector, NurbsCurve, NurbsError};

/// The segment from `a` to `b` on the domain [0, 1]. `a == b` is allowed (a
/// degenerate segment is a valid profile piece at a pole).
pub fn line(a: DVec3, b: DVec3) -> Result<NurbsCurve, NurbsError> {
    let a = finite_vec("line start", a)?;
    let b = finite_vec("line end", b)?;
    NurbsCurve::try_polynomial(KnotVector::new(1, vec![0.0, 0.0, 1.0, 1.0]), &[a, b])
}
