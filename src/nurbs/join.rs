//! Joining surfaces end to end along v: one surface over the union of neighbouring
//! patches, for computing an opening that crosses the seam between them.
//!
//! Patches of a revolved part (a head's straight flange, knuckle and crown) share
//! their u parametrization, and each one's v-end row of control points is the next
//! one's v-start row. [`NurbsSurface::joined_v`] places them one after the other in
//! v: the lower v-degree is elevated, every patch keeps its own parametrization up
//! to a shift in v (returned, so (u, v) on the joined surface maps back to each
//! patch exactly), and the joint knot gets multiplicity `degree`, so the joined
//! surface interpolates the shared row and is as smooth across it as the geometry.
//! No point moves.

use glam::DVec4;

use super::{KnotVector, NurbsError, NurbsSurface, Side};

/// Largest distance between the shared rows of two joined patches, relative to the
/// size of their control nets.
const SAME_ROW: f64 = 1e-9;

impl NurbsSurface {
    /// `self` followed in v by each of `next`, as one surface, with the shift added
    /// to each patch's v to place it on the joined surface (0 for `self`): patch `k`
    /// at its `(u, v)` is the joined surface at `(u, v + shifts[k])`.
    ///
    /// # Errors
    ///
    /// [`NurbsError::InvalidGeometry`] where two neighbours differ in their u
    /// knots, or where one's v-end edge is not the next one's v-start edge.
    pub fn joined_v(&self, next: &[&NurbsSurface]) -> Result<(NurbsSurface, Vec<f64>), NurbsError> {
        let degree = next
            .iter()
            .map(|s| s.v_degree())
            .fold(self.v_degree(), usize::max);
        let raise = |s: &NurbsSurface| s.elevate_degree_v(degree - s.v_degree());
        let mut joined = raise(self)?;
        let mut shifts = vec![0.0];
        for &surface in next {
            let surface = raise(surface)?;
            let (shift, out) = append_v(&joined, &surface, degree)?;
            shifts.push(shift);
            joined = out;
        }
        Ok((joined, shifts))
    }
}

/// `b` appended to `a` in v (both of v-degree `degree`), with b's shift.
fn append_v(
    a: &NurbsSurface,
    b: &NurbsSurface,
    degree: usize,
) -> Result<(f64, NurbsSurface), NurbsError> {
    if a.u_knots() != b.u_knots() {
        return Err(NurbsError::InvalidGeometry {
            what: "u knot count of the next patch",
            value: b.u_knots().len() as f64,
            rule: "joined patches must share their u knots",
        });
    }
    let (nu, na, nb) = (a.u_count(), a.v_count(), b.v_count());
    let size = a
        .control_points()
        .iter()
        .chain(b.control_points().iter())
        .fold(1.0f64, |m, p| m.max(p.abs().max_element()));
    let end = a.boundary(Side::VMax).control_points();
    let start = b.boundary(Side::VMin).control_points();
    let gap = end
        .iter()
        .zip(&start)
        .fold(0.0f64, |m, (p, q)| m.max((*p - *q).length()));
    if gap > SAME_ROW * size {
        return Err(NurbsError::InvalidGeometry {
            what: "gap between the joined edges",
            value: gap,
            rule: "a patch's v-end edge must be the next patch's v-start edge",
        });
    }
    // Scale b's weights so the shared row has a's weights (same rational curve).
    let ratio = a.homogeneous_point_at(0, na - 1).w / b.homogeneous_point_at(0, 0).w;
    for i in 0..nu {
        let r = a.homogeneous_point_at(i, na - 1).w / b.homogeneous_point_at(i, 0).w;
        if (r - ratio).abs() > 1e-12 * ratio {
            return Err(NurbsError::InvalidGeometry {
                what: "weight ratio along the joined edges",
                value: r,
                rule: "the shared edge must have proportional weights in both patches",
            });
        }
    }
    let (a_knots, b_knots) = (a.v_knots().as_slice(), b.v_knots().as_slice());
    let (a_end, b_start) = (a.v_knots().domain().1, b.v_knots().domain().0);
    let shift = a_end - b_start;
    let mut knots: Vec<f64> = a_knots[..a_knots.len() - 1].to_vec();
    knots.extend(b_knots[degree + 1..].iter().map(|&k| k + shift));
    let v_knots = KnotVector::try_new(degree, knots)?;
    let nv = na + nb - 1;
    let mut points: Vec<DVec4> = Vec::with_capacity(nu * nv);
    for i in 0..nu {
        points.extend((0..na).map(|j| a.homogeneous_point_at(i, j)));
        points.extend((1..nb).map(|j| b.homogeneous_point_at(i, j) * ratio));
    }
    Ok((
        shift,
        NurbsSurface::try_new(a.u_knots().clone(), v_knots, points)?,
    ))
}
