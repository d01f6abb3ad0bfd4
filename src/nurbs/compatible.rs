//! Making two curves compatible: one degree, one knot vector, same shapes.
//!
//! Ruled surfaces and lofts need their section curves on a common basis. This
//! maps both domains to [0, 1], elevates the lower degree
//! ([`NurbsCurve::elevate_degree`]) and merges the knot vectors by refinement
//! ([`NurbsCurve::refine_knots`]): every knot value of either curve ends up in both
//! with the larger of its two multiplicities. No point of either curve moves, and
//! each keeps its parametrization up to the affine map onto [0, 1].

use super::{KnotVector, NurbsCurve, NurbsError};

/// Returns `a` and `b` re-expressed on a common degree and knot vector over [0, 1].
///
/// `result.0.point(t) == a.point(a0 + t (a1 − a0))` for `t` in [0, 1], and likewise
/// for `b`. Knots are compared exactly: two knots that differ by rounding stay two
/// knots (a short span), they are not merged. Errors if the common degree exceeds
/// [`MAX_DEGREE`](super::MAX_DEGREE), or if the merge would need an interior knot at
/// full multiplicity `degree + 1` in a curve that is continuous there.
pub fn make_compatible(
    a: &NurbsCurve,
    b: &NurbsCurve,
) -> Result<(NurbsCurve, NurbsCurve), NurbsError> {
    let a = a.reparametrized(0.0, 1.0)?;
    let b = b.reparametrized(0.0, 1.0)?;
    let degree = a.degree().max(b.degree());
    let a = a.elevate_degree(degree - a.degree())?;
    let b = b.elevate_degree(degree - b.degree())?;
    let a_missing = missing_knots(a.knots(), b.knots());
    let b_missing = missing_knots(b.knots(), a.knots());
    Ok((a.refine_knots(&a_missing)?, b.refine_knots(&b_missing)?))
}

/// The interior knots `own` must gain to contain `other`, sorted: each distinct
/// interior value of `other` repeated by how much its multiplicity exceeds `own`'s.
fn missing_knots(own: &KnotVector, other: &KnotVector) -> Vec<f64> {
    let (start, end) = other.domain();
    other
        .distinct()
        .into_iter()
        .filter(|&k| k > start && k < end)
        .flat_map(|k| {
            let count = other.multiplicity(k).saturating_sub(own.multiplicity(k));
            std::iter::repeat_n(k, count)
        })
        .collect()
}
