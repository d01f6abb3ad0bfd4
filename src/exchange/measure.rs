//! Exact measures of trimmed faces: the area of a [`Face`] over its trimmed
//! domain and its share of the enclosed volume, the reference a receiver's
//! figures are checked against.
//!
//! A face is its surface over the region of (u, v) its loops bound, each loop a
//! chain of pcurves (straight segments in (u, v)), exactly as written to the
//! file. By Green's theorem an integral over that region is one over its
//! boundary: ∫∫_D f du dv = ∮_∂D F dv with F(u, v) = ∫_a^u f(s, v) ds, the
//! outer loop counter-clockwise, the holes clockwise; a side left out at a pole
//! runs along v = const and adds nothing, and each closed loop may take its own
//! `a` (a function of v alone integrates to zero round a closed loop). Both
//! integrals are Gauss–Legendre rules on pieces split at the surface's knot
//! lines, where the integrand is smooth (rational): [`ORDER`] points per piece
//! converge to round-off, which [`face_measures_with`] at two orders shows.

use glam::DVec2;

use super::brep::{Face, OrientedEdge};
use crate::nurbs::{FirstDerivatives, GaussLegendre, NurbsSurface};

/// Gauss–Legendre points per smooth piece.
pub const ORDER: usize = 12;

/// A face's measures over its trimmed domain.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FaceMeasures {
    /// Area, mm².
    pub area: f64,
    /// (1/3) ∫∫ S · (S_u × S_v) du dv over the trimmed domain, mm³: summed over a
    /// closed shell whose normals point out, the volume it encloses.
    pub volume: f64,
}

/// [`face_measures_with`] at [`ORDER`].
pub fn face_measures(face: &Face) -> FaceMeasures {
    face_measures_with(face, ORDER)
}

/// The area and volume share of `face` over its trimmed domain, with `order`
/// Gauss–Legendre points per smooth piece of each integral.
pub fn face_measures_with(face: &Face, order: usize) -> FaceMeasures {
    let rule = GaussLegendre::new(order);
    let surface = &face.surface;
    let u_knots = surface.u_knots().distinct();
    let v_knots = surface.v_knots().distinct();
    let mut area = 0.0;
    let mut volume = 0.0;
    for lp in std::iter::once(&face.outer).chain(&face.holes) {
        let points = loop_points(lp);
        let Some(&first) = points.first() else {
            continue;
        };
        let a = first.x;
        for w in points.windows(2) {
            let (p, q) = (w[0], w[1]);
            let dv = q.y - p.y;
            if dv == 0.0 {
                continue;
            }
            for (t0, t1) in pieces(p, q, &u_knots, &v_knots) {
                for (t, wt) in rule.points_on(t0, t1) {
                    let at = p.lerp(q, t);
                    let (fa, fv) = inner(surface, &rule, &u_knots, a, at);
                    area += fa * dv * wt;
                    volume += fv * dv * wt;
                }
            }
        }
    }
    FaceMeasures {
        area,
        volume: volume / 3.0,
    }
}

/// The (u, v) points of a loop in order, each use's pcurve taken the way the
/// loop runs, consecutive duplicates kept (a zero-length segment adds nothing).
fn loop_points(uses: &[OrientedEdge]) -> Vec<DVec2> {
    let mut points = Vec::new();
    for e in uses {
        if e.forward {
            points.extend(e.pcurve.iter().copied());
        } else {
            points.extend(e.pcurve.iter().rev().copied());
        }
    }
    if let Some(&first) = points.first() {
        points.push(first);
    }
    points
}

/// The sub-intervals of t ∈ [0, 1] on the segment p–q between its crossings
/// of the knot lines.
fn pieces(p: DVec2, q: DVec2, u_knots: &[f64], v_knots: &[f64]) -> Vec<(f64, f64)> {
    let mut cuts = vec![0.0, 1.0];
    for (knots, a, b) in [(u_knots, p.x, q.x), (v_knots, p.y, q.y)] {
        if a == b {
            continue;
        }
        for &k in knots {
            let t = (k - a) / (b - a);
            if t > 0.0 && t < 1.0 {
                cuts.push(t);
            }
        }
    }
    cuts.sort_by(f64::total_cmp);
    cuts.dedup();
    cuts.windows(2).map(|w| (w[0], w[1])).collect()
}

/// ∫_a^{at.x} of |S_u × S_v| and of S · (S_u × S_v) at v = at.y, split at the
/// u knots between.
fn inner(
    surface: &NurbsSurface,
    rule: &GaussLegendre,
    u_knots: &[f64],
    a: f64,
    at: DVec2,
) -> (f64, f64) {
    let (lo, hi, sign) = if at.x >= a {
        (a, at.x, 1.0)
    } else {
        (at.x, a, -1.0)
    };
    if hi == lo {
        return (0.0, 0.0);
    }
    let mut bounds = vec![lo];
    bounds.extend(u_knots.iter().copied().filter(|&k| k > lo && k < hi));
    bounds.push(hi);
    let (mut fa, mut fv) = (0.0, 0.0);
    for w in bounds.windows(2) {
        for (u, wu) in rule.points_on(w[0], w[1]) {
            let FirstDerivatives { point, du, dv } = surface.first_derivatives(u, at.y);
            let n = du.cross(dv);
            fa += n.length() * wu;
            fv += point.dot(n) * wu;
        }
    }
    (sign * fa, sign * fv)
}
