//! Degree elevation of curves and surfaces (Piegl & Tiller A5.9).
//!
//! Elevation is the other half of making bases compatible: a ruled surface or loft
//! between a line (degree 1) and an arc (degree 2) needs both sections on one degree
//! before [`make_compatible`](super::make_compatible) merges their knots. The shape
//! and the parametrization do not change.
//!
//! The algorithm chosen is A5.9: each Bézier segment is extracted by knot insertion,
//! elevated, and the inserted knots are removed again on the fly. The result is the
//! elevated curve with *minimal* knot multiplicities: an interior knot of
//! multiplicity `m` comes out with `m + times`, the least that keeps the curve's
//! continuity `C^(p−m)` there. A5.9 assumes a continuous curve; a curve with an
//! interior knot of full multiplicity `p + 1` (a break) is split there, the pieces
//! elevated on their own and joined again with the knot at `p + times + 1`.

use glam::DVec4;

use super::refine::map_columns_u;
use super::{KnotVector, MAX_DEGREE, NurbsCurve, NurbsError, NurbsSurface};

impl NurbsCurve {
    /// The same curve (same shape, same parametrization) with the degree raised by
    /// `times`. Interior knot multiplicities rise by `times` as well (the minimum for
    /// the same continuity). Errors if the new degree would exceed
    /// [`MAX_DEGREE`]; `times = 0` returns a copy.
    pub fn elevate_degree(&self, times: usize) -> Result<NurbsCurve, NurbsError> {
        let p = self.degree();
        let degree = p.saturating_add(times);
        if degree > MAX_DEGREE {
            return Err(NurbsError::DegreeOutOfRange {
                degree,
                max: MAX_DEGREE,
            });
        }
        if times == 0 {
            return Ok(self.clone());
        }
        let (start, end) = self.domain();
        let break_knot = self
            .knots()
            .distinct()
            .into_iter()
            .find(|&k| k > start && k < end && self.knots().multiplicity(k) > p);
        if let Some(knot) = break_knot {
            let (left, right) = self.split_at(knot)?;
            return Ok(join_at_break(
                &left.elevate_degree(times)?,
                &right.elevate_degree(times)?,
            ));
        }
        let (knots, points) = elevate(self.knots(), self.homogeneous_points(), times);
        Ok(NurbsCurve::from_raw(
            KnotVector::from_raw(degree, knots),
            points,
        ))
    }
}

impl NurbsSurface {
    /// The same surface with the u-degree raised by `times`; see
    /// [`NurbsCurve::elevate_degree`].
    pub fn elevate_degree_u(&self, times: usize) -> Result<NurbsSurface, NurbsError> {
        map_columns_u(self, |c| c.elevate_degree(times))
    }

    /// The same surface with the v-degree raised by `times`; see
    /// [`NurbsCurve::elevate_degree`].
    pub fn elevate_degree_v(&self, times: usize) -> Result<NurbsSurface, NurbsError> {
        Ok(self.transposed().elevate_degree_u(times)?.transposed())
    }
}

/// Joins two clamped curves of one degree where `left` ends and `right` starts at
/// the same parameter: the joint knot keeps full multiplicity `degree + 1`.
fn join_at_break(left: &NurbsCurve, right: &NurbsCurve) -> NurbsCurve {
    let order = left.degree() + 1;
    let mut knots = left.knots().as_slice().to_vec();
    knots.extend_from_slice(&right.knots().as_slice()[order..]);
    let mut points = left.homogeneous_points().to_vec();
    points.extend_from_slice(right.homogeneous_points());
    NurbsCurve::from_raw(KnotVector::from_raw(left.degree(), knots), points)
}

/// `n choose k` as a float (small arguments only: n ≤ 2 · MAX_DEGREE).
fn binomial(n: usize, k: usize) -> f64 {
    (0..k).fold(1.0, |acc, i| acc * (n - i) as f64 / (i + 1) as f64)
}

/// Coefficients of Bézier degree elevation from `p` to `p + t`:
/// `Q_i = Σ_j alpha[i][j] P_j` with `alpha[i][j] = C(p, j) C(t, i − j) / C(p + t, i)`.
fn bezier_elevation_coefficients(p: usize, t: usize) -> Vec<Vec<f64>> {
    let ph = p + t;
    let mut alpha = vec![vec![0.0; p + 1]; ph + 1];
    for (i, row) in alpha.iter_mut().enumerate() {
        let inv = 1.0 / binomial(ph, i);
        for (j, value) in row.iter_mut().enumerate().take(p.min(i) + 1) {
            if i - j <= t {
                *value = inv * binomial(p, j) * binomial(t, i - j);
            }
        }
    }
    alpha
}

/// A5.9 on homogeneous points: the knots and points of the curve elevated `t > 0`
/// times. Interior multiplicities must be at most the degree.
fn elevate(knots: &KnotVector, points: &[DVec4], t: usize) -> (Vec<f64>, Vec<DVec4>) {
    let p = knots.degree();
    let u = knots.as_slice();
    let m = u.len() - 1;
    let ph = p + t;
    let bezalfs = bezier_elevation_coefficients(p, t);
    let segments = knots.distinct().len() - 1;
    let point_count = points.len() + t * segments;
    let mut qw = vec![DVec4::ZERO; point_count];
    let mut uh = vec![0.0; point_count + ph + 1];
    let mut bpts = vec![DVec4::ZERO; p + 1];
    let mut next_bpts = vec![DVec4::ZERO; p.saturating_sub(1)];
    let mut ebpts = vec![DVec4::ZERO; ph + 1];
    let mut alfs = vec![0.0; p.saturating_sub(1)];

    let mut kind = ph + 1;
    let mut r: isize = -1;
    let mut a = p;
    let mut b = p + 1;
    let mut cind = 1;
    let mut ua = u[0];
    qw[0] = points[0];
    uh[..=ph].fill(ua);
    bpts.copy_from_slice(&points[..=p]);
    while b < m {
        let i0 = b;
        while b < m && u[b] == u[b + 1] {
            b += 1;
        }
        let mul = b - i0 + 1;
        let ub = u[b];
        let oldr = r;
        r = p as isize - mul as isize;
        let lbz = if oldr > 0 { oldr as usize / 2 + 1 } else { 1 };
        let rbz = if r > 0 {
            ph - (r as usize).div_ceil(2)
        } else {
            ph
        };
        // Insert ub r times to isolate the Bézier segment [ua, ub].
        if r > 0 {
            let r = r as usize;
            let numer = ub - ua;
            for k in (mul + 1..=p).rev() {
                alfs[k - mul - 1] = numer / (u[a + k] - ua);
            }
            for j in 1..=r {
                let s = mul + j;
                for k in (s..=p).rev() {
                    let alpha = alfs[k - s];
                    bpts[k] = bpts[k] * alpha + bpts[k - 1] * (1.0 - alpha);
                }
                next_bpts[r - j] = bpts[p];
            }
        }
        // Elevate the segment; only points lbz..=ph are used below.
        for (i, row) in bezalfs.iter().enumerate().skip(lbz) {
            ebpts[i] = (i.saturating_sub(t)..=p.min(i))
                .map(|j| bpts[j] * row[j])
                .sum();
        }
        // Remove the knot ua, inserted oldr times for the previous segment.
        if oldr > 1 {
            let oldr = oldr as usize;
            let den = ub - ua;
            let bet = (ub - uh[kind - 1]) / den;
            for tr in 1..oldr as isize {
                // The removal window widens by one on each side per pass.
                let mut i = kind as isize - 1 - tr;
                let mut j = kind as isize - 1 + tr;
                let mut kj = tr;
                while j - i > tr {
                    if i < cind as isize {
                        let iu = i as usize;
                        let alf = (ub - uh[iu]) / (ua - uh[iu]);
                        qw[iu] = qw[iu] * alf + qw[iu - 1] * (1.0 - alf);
                    }
                    if j >= lbz as isize {
                        let k = kj as usize;
                        let gam = if j - tr <= (kind + oldr) as isize - ph as isize {
                            (ub - uh[(j - tr) as usize]) / den
                        } else {
                            bet
                        };
                        ebpts[k] = ebpts[k] * gam + ebpts[k + 1] * (1.0 - gam);
                    }
                    i += 1;
                    j -= 1;
                    kj -= 1;
                }
            }
        }
        if a != p {
            // oldr ≥ 0 here: the previous knot was interior.
            let copies = (ph as isize - oldr) as usize;
            uh[kind..kind + copies].fill(ua);
            kind += copies;
        }
        for point in &ebpts[lbz..=rbz] {
            qw[cind] = *point;
            cind += 1;
        }
        if b < m {
            let r = r as usize;
            bpts[..r].copy_from_slice(&next_bpts[..r]);
            bpts[r..].copy_from_slice(&points[b - p + r..=b]);
            a = b;
            b += 1;
            ua = ub;
        } else {
            uh[kind..=kind + ph].fill(ub);
        }
    }
    debug_assert_eq!(cind, point_count);
    (uh, qw)
}

#[cfg(test)]
mod tests {
    use glam::DVec3;

    use super::*;

    #[test]
    fn elevating_a_quadratic_bezier_matches_the_closed_form() {
        let knots = KnotVector::new(2, vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0]);
        let p = [
            DVec3::ZERO,
            DVec3::new(3.0, 3.0, 0.0),
            DVec3::new(6.0, 0.0, 3.0),
        ];
        let c = NurbsCurve::try_polynomial(knots, &p).unwrap();
        let e = c.elevate_degree(1).unwrap();
        assert_eq!(
            e.knots().as_slice(),
            &[0.0, 0.0, 0.0, 0.0, 1.0, 1.0, 1.0, 1.0]
        );
        let expected = [
            p[0],
            p[0] / 3.0 + p[1] * (2.0 / 3.0),
            p[1] * (2.0 / 3.0) + p[2] / 3.0,
            p[2],
        ];
        for (a, b) in e.control_points().iter().zip(expected) {
            assert!((*a - b).length() < 1e-12, "{a} vs {b}");
        }
    }
}
