//! Shape-preserving knot operations: insertion, refinement, splitting and reversal.
//!
//! These sit between construction and every consumer that needs a finer or common
//! basis: [`make_compatible`](super::make_compatible) merges knot vectors with them,
//! degree elevation and exporters split at knots, the mesher may split patches.
//! None of them moves a point of the curve or surface: only the basis changes.
//!
//! Everything is written once for curves over homogeneous points (so rational
//! geometry needs no special case) and applied to surfaces column by column: a
//! u-operation acts on the curves `j ↦ points[i * v_count + j]` along u, a
//! v-operation on the transposed surface. Cost: one curve operation per column,
//! plus for v two transposes (copies of the control net).

use glam::DVec4;

use super::{KnotVector, NurbsCurve, NurbsError, NurbsSurface};

impl NurbsCurve {
    /// The same curve with the knot `u` inserted `times` times.
    ///
    /// Errors if `u` lies outside the domain (or is NaN) or if its multiplicity would
    /// exceed the degree (so the end knots can never be inserted). `times = 0`
    /// returns a copy. This is refinement (A5.4) with `times` copies of `u`, which
    /// gives the same points as Boehm insertion (A5.1) repeated `times` times.
    pub fn insert_knot(&self, u: f64, times: usize) -> Result<NurbsCurve, NurbsError> {
        check_in_domain(self.knots(), u)?;
        // Checked before allocating `times` copies: `times` may come from user data.
        let multiplicity = self.knots().multiplicity(u).saturating_add(times);
        if multiplicity > self.degree() {
            return Err(NurbsError::InsertionExceedsDegree {
                knot: u,
                multiplicity,
                degree: self.degree(),
            });
        }
        self.refine_knots(&vec![u; times])
    }

    /// The same curve with all of `new_knots` inserted (Piegl & Tiller A5.4).
    ///
    /// `new_knots` must be finite, non-decreasing (they are never sorted for the
    /// caller) and inside the domain, and no knot may end up with a multiplicity
    /// above the degree. An empty slice returns a copy.
    pub fn refine_knots(&self, new_knots: &[f64]) -> Result<NurbsCurve, NurbsError> {
        check_refinement(self.knots(), new_knots)?;
        if new_knots.is_empty() {
            return Ok(self.clone());
        }
        let (knots, points) = refine(self.knots(), self.homogeneous_points(), new_knots);
        Ok(NurbsCurve::from_raw(
            KnotVector::from_raw(self.degree(), knots),
            points,
        ))
    }

    /// The two pieces of the curve on `[start, u]` and `[u, end]`; `u` must lie
    /// strictly inside the domain. Each piece keeps its sub-domain (no
    /// reparametrization), so `left.point(t) == self.point(t)` for `t ≤ u`.
    pub fn split_at(&self, u: f64) -> Result<(NurbsCurve, NurbsCurve), NurbsError> {
        let (start, end) = self.domain();
        if !(u > start && u < end) {
            return Err(NurbsError::ParameterOutOfDomain {
                value: u,
                start,
                end,
            });
        }
        let p = self.degree();
        let existing = self.knots().multiplicity(u);
        let refined = self.refine_knots(&vec![u; p.saturating_sub(existing)])?;
        let knots = refined.knots().as_slice();
        let points = refined.homogeneous_points();
        // `u` now appears p (or p + 1) times at knots[first..=last].
        let first = knots.partition_point(|&k| k < u);
        let last = knots.partition_point(|&k| k <= u) - 1;
        let mut left_knots = knots[..first].to_vec();
        left_knots.extend(std::iter::repeat_n(u, p + 1));
        let mut right_knots = vec![u; p + 1];
        right_knots.extend_from_slice(&knots[last + 1..]);
        let right_count = knots.len() - 1 - last;
        let left = NurbsCurve::from_raw(
            KnotVector::from_raw(p, left_knots),
            points[..first].to_vec(),
        );
        let right = NurbsCurve::from_raw(
            KnotVector::from_raw(p, right_knots),
            points[points.len() - right_count..].to_vec(),
        );
        Ok((left, right))
    }
}

impl NurbsSurface {
    /// The same surface with the u-knot `u` inserted `times` times; see
    /// [`NurbsCurve::insert_knot`].
    pub fn insert_knot_u(&self, u: f64, times: usize) -> Result<NurbsSurface, NurbsError> {
        map_columns_u(self, |c| c.insert_knot(u, times))
    }

    /// The same surface with the v-knot `v` inserted `times` times; see
    /// [`NurbsCurve::insert_knot`].
    pub fn insert_knot_v(&self, v: f64, times: usize) -> Result<NurbsSurface, NurbsError> {
        Ok(self.transposed().insert_knot_u(v, times)?.transposed())
    }

    /// The same surface with all of `new_knots` inserted along u; see
    /// [`NurbsCurve::refine_knots`].
    pub fn refine_knots_u(&self, new_knots: &[f64]) -> Result<NurbsSurface, NurbsError> {
        map_columns_u(self, |c| c.refine_knots(new_knots))
    }

    /// The same surface with all of `new_knots` inserted along v; see
    /// [`NurbsCurve::refine_knots`].
    pub fn refine_knots_v(&self, new_knots: &[f64]) -> Result<NurbsSurface, NurbsError> {
        Ok(self.transposed().refine_knots_u(new_knots)?.transposed())
    }

    /// The pieces of the surface on `u ≤ u_split` and `u ≥ u_split`, each keeping its
    /// sub-domain; `u_split` must lie strictly inside the u-domain.
    pub fn split_u(&self, u_split: f64) -> Result<(NurbsSurface, NurbsSurface), NurbsError> {
        let (lower, upper): (Vec<_>, Vec<_>) = columns_u(self)
            .iter()
            .map(|c| c.split_at(u_split))
            .collect::<Result<Vec<_>, _>>()?
            .into_iter()
            .unzip();
        Ok((
            assemble_u(lower, self.v_knots(), self.u_knots()),
            assemble_u(upper, self.v_knots(), self.u_knots()),
        ))
    }

    /// The pieces of the surface on `v ≤ v_split` and `v ≥ v_split`, each keeping its
    /// sub-domain; `v_split` must lie strictly inside the v-domain.
    pub fn split_v(&self, v_split: f64) -> Result<(NurbsSurface, NurbsSurface), NurbsError> {
        let (lower, upper) = self.transposed().split_u(v_split)?;
        Ok((lower.transposed(), upper.transposed()))
    }

    /// The same point set with u running backwards over the same domain:
    /// `reversed_u().point(u0 + u1 − u, v) == point(u, v)`. The normal flips.
    pub fn reversed_u(&self) -> NurbsSurface {
        let nv = self.v_count();
        let points = self
            .homogeneous_points()
            .chunks_exact(nv)
            .rev()
            .flatten()
            .copied()
            .collect();
        NurbsSurface::from_raw(self.u_knots().reversed(), self.v_knots().clone(), points)
    }

    /// The same point set with v running backwards over the same domain:
    /// `reversed_v().point(u, v0 + v1 − v) == point(u, v)`. The normal flips.
    pub fn reversed_v(&self) -> NurbsSurface {
        let nv = self.v_count();
        let points = self
            .homogeneous_points()
            .chunks_exact(nv)
            .flat_map(|row| row.iter().rev())
            .copied()
            .collect();
        NurbsSurface::from_raw(self.u_knots().clone(), self.v_knots().reversed(), points)
    }
}

/// The curves along u of a surface, one per v-index `j`: `points[i * v_count + j]`.
pub(super) fn columns_u(surface: &NurbsSurface) -> Vec<NurbsCurve> {
    let nv = surface.v_count();
    let points = surface.homogeneous_points();
    (0..nv)
        .map(|j| {
            let column = points.iter().skip(j).step_by(nv).copied().collect();
            NurbsCurve::from_raw(surface.u_knots().clone(), column)
        })
        .collect()
}

/// The surface whose curves along u are `columns` (which share one knot vector, as
/// every column went through the same knot operation). `fallback_u` is used only
/// if `columns` is empty, which a valid surface never produces.
pub(super) fn assemble_u(
    columns: Vec<NurbsCurve>,
    v_knots: &KnotVector,
    fallback_u: &KnotVector,
) -> NurbsSurface {
    let u_knots = columns
        .first()
        .map_or_else(|| fallback_u.clone(), |c| c.knots().clone());
    let nu = u_knots.basis_count();
    let mut points = Vec::with_capacity(nu * columns.len());
    for i in 0..nu {
        points.extend(columns.iter().map(|c| c.homogeneous_points()[i]));
    }
    NurbsSurface::from_raw(u_knots, v_knots.clone(), points)
}

/// Applies the same curve operation to every column along u and reassembles.
pub(super) fn map_columns_u(
    surface: &NurbsSurface,
    operation: impl Fn(&NurbsCurve) -> Result<NurbsCurve, NurbsError>,
) -> Result<NurbsSurface, NurbsError> {
    let columns = columns_u(surface)
        .iter()
        .map(operation)
        .collect::<Result<Vec<_>, _>>()?;
    Ok(assemble_u(columns, surface.v_knots(), surface.u_knots()))
}

/// Errors unless `u` lies in the closed domain of `knots`.
fn check_in_domain(knots: &KnotVector, u: f64) -> Result<(), NurbsError> {
    let (start, end) = knots.domain();
    if u >= start && u <= end {
        Ok(())
    } else {
        Err(NurbsError::ParameterOutOfDomain {
            value: u,
            start,
            end,
        })
    }
}

/// Validates knots to insert: in the domain, non-decreasing, and no resulting
/// multiplicity above the degree.
fn check_refinement(knots: &KnotVector, new_knots: &[f64]) -> Result<(), NurbsError> {
    for (index, &x) in new_knots.iter().enumerate() {
        check_in_domain(knots, x)?;
        if index > 0 && x < new_knots[index - 1] {
            return Err(NurbsError::RefinementKnotsUnsorted {
                index,
                previous: new_knots[index - 1],
                next: x,
            });
        }
    }
    let degree = knots.degree();
    let mut start = 0;
    while start < new_knots.len() {
        let knot = new_knots[start];
        let run = new_knots[start..]
            .iter()
            .take_while(|&&k| k == knot)
            .count();
        let multiplicity = knots.multiplicity(knot) + run;
        if multiplicity > degree {
            return Err(NurbsError::InsertionExceedsDegree {
                knot,
                multiplicity,
                degree,
            });
        }
        start += run;
    }
    Ok(())
}

/// Knot refinement (Piegl & Tiller A5.4) on homogeneous points: inserts the sorted,
/// validated, non-empty `new_knots` and returns the new knots and points.
fn refine(knots: &KnotVector, points: &[DVec4], new_knots: &[f64]) -> (Vec<f64>, Vec<DVec4>) {
    let p = knots.degree();
    let u = knots.as_slice();
    let n = points.len() - 1;
    let m = n + p + 1;
    let r = new_knots.len() - 1;
    let a = knots.find_span(new_knots[0]);
    let b = knots.find_span(new_knots[r]) + 1;
    let mut q = vec![DVec4::ZERO; n + r + 2];
    let mut ubar = vec![0.0; m + r + 2];
    q[..=a - p].copy_from_slice(&points[..=a - p]);
    q[b + r..].copy_from_slice(&points[b - 1..]);
    ubar[..=a].copy_from_slice(&u[..=a]);
    ubar[b + p + r + 1..].copy_from_slice(&u[b + p..]);
    let mut i = b + p - 1;
    let mut k = b + p + r;
    for &x in new_knots.iter().rev() {
        while x <= u[i] && i > a {
            q[k - p - 1] = points[i - p - 1];
            ubar[k] = u[i];
            k -= 1;
            i -= 1;
        }
        q[k - p - 1] = q[k - p];
        for l in 1..=p {
            let ind = k - p + l;
            let alpha = ubar[k + l] - x;
            if alpha == 0.0 {
                q[ind - 1] = q[ind];
            } else {
                let alpha = alpha / (ubar[k + l] - u[i - p + l]);
                q[ind - 1] = q[ind - 1] * alpha + q[ind] * (1.0 - alpha);
            }
        }
        ubar[k] = x;
        k -= 1;
    }
    (ubar, q)
}

#[cfg(test)]
mod tests {
    use glam::DVec3;

    use super::*;

    #[test]
    fn refine_reproduces_the_textbook_insertion() {
        // Piegl & Tiller Ex. 5.1: p = 3, insert u = 5/2 into span 4 once.
        let knots = KnotVector::new(
            3,
            vec![0.0, 0.0, 0.0, 0.0, 1.0, 2.0, 3.0, 4.0, 5.0, 5.0, 5.0, 5.0],
        );
        let points: Vec<DVec3> = (0..8)
            .map(|i| DVec3::new(i as f64, (i * i) as f64, 0.0))
            .collect();
        let c = NurbsCurve::try_polynomial(knots, &points).unwrap();
        let r = c.insert_knot(2.5, 1).unwrap();
        assert_eq!(
            r.knots().as_slice(),
            &[
                0.0, 0.0, 0.0, 0.0, 1.0, 2.0, 2.5, 3.0, 4.0, 5.0, 5.0, 5.0, 5.0
            ]
        );
        let q = r.control_points();
        let expected = [
            points[0],
            points[1],
            points[2],
            points[3] * (5.0 / 6.0) + points[2] * (1.0 / 6.0),
            points[4] * 0.5 + points[3] * 0.5,
            points[5] * (1.0 / 6.0) + points[4] * (5.0 / 6.0),
            points[5],
            points[6],
            points[7],
        ];
        for (a, b) in q.iter().zip(expected) {
            assert!((*a - b).length() < 1e-12, "{a} vs {b}");
        }
    }

    #[test]
    fn splitting_a_bezier_gives_de_casteljau_polygons() {
        let knots = KnotVector::new(2, vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0]);
        let p = [
            DVec3::ZERO,
            DVec3::new(2.0, 2.0, 0.0),
            DVec3::new(4.0, 0.0, 0.0),
        ];
        let c = NurbsCurve::try_polynomial(knots, &p).unwrap();
        let (left, right) = c.split_at(0.5).unwrap();
        let mid = c.point(0.5);
        let l = left.control_points();
        let r = right.control_points();
        assert_eq!(l, vec![p[0], (p[0] + p[1]) / 2.0, mid]);
        assert_eq!(r, vec![mid, (p[1] + p[2]) / 2.0, p[2]]);
        assert_eq!(left.knots().as_slice(), &[0.0, 0.0, 0.0, 0.5, 0.5, 0.5]);
        assert_eq!(right.knots().as_slice(), &[0.5, 0.5, 0.5, 1.0, 1.0, 1.0]);
    }
}
