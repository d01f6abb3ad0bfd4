//! Ruled surfaces between two curves, and extrusions of a curve along a vector.
//!
//! u runs along the curves, v (degree 1) from the first curve to the second. A ruled
//! surface needs two curves of one degree on one knot vector; curves that differ are
//! first made compatible (degree elevation and knot refinement, which change no
//! shape).

use glam::DVec3;

use super::finite_vec;
use crate::nurbs::{KnotVector, NurbsCurve, NurbsError, NurbsSurface};

/// The ruled surface `S(u, v) = (1 − v) a(u) + v b(u)` in homogeneous space.
/// Curves of different degree or knots are made compatible first (their domains are
/// mapped to [0, 1]).
pub fn ruled(a: &NurbsCurve, b: &NurbsCurve) -> Result<NurbsSurface, NurbsError> {
    let (a, b) = if a.knots() == b.knots() {
        (a.clone(), b.clone())
    } else {
        crate::nurbs::make_compatible(a, b)?
    };
    let nu = a.homogeneous_points().len();
    let mut points = Vec::with_capacity(nu * 2);
    for i in 0..nu {
        points.push(a.homogeneous_points()[i]);
        points.push(b.homogeneous_points()[i]);
    }
    NurbsSurface::try_new(
        a.knots().clone(),
        KnotVector::new(1, vec![0.0, 0.0, 1.0, 1.0]),
        points,
    )
}

/// The surface swept by `curve` moving along `offset`: `S(u, v) = C(u) + v · offset`.
pub fn extrude(curve: &NurbsCurve, offset: DVec3) -> Result<NurbsSurface, NurbsError> {
    let d = finite_vec("extrusion offset", offset)?;
    let moved = curve.map_points(|p| p + (d * p.w).extend(0.0));
    ruled(curve, &moved)
}
