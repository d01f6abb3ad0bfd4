//! Making two curves compatible: one degree, one knot vector, same shapes.
//!
//! Ruled surfaces and lofts need their section curves on a common basis. This
//! elevates the lower degree and merges the knot vectors by refinement.

use super::{NurbsCurve, NurbsError};

/// Returns `a` and `b` re-expressed on a common degree and knot vector over [0, 1].
pub fn make_compatible(
    a: &NurbsCurve,
    b: &NurbsCurve,
) -> Result<(NurbsCurve, NurbsCurve), NurbsError> {
    // Interim: only identical bases; replaced by elevation + refinement.
    if a.knots() == b.knots() {
        return Ok((a.clone(), b.clone()));
    }
    Err(NurbsError::InvalidGeometry {
        what: "degree",
        value: a.degree() as f64,
        rule: "curves must be compatible",
    })
}
