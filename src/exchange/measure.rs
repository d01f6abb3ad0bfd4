//! Exact measures of trimmed faces: the area of a [`Face`] over its trimmed
//! domain and its share of the enclosed volume, the reference a receiver's
//! figures are checked against.
//!
//! A face is its surface over the region of (u, v) its loops bound, each loop a
//! chain of pcurves (straight lines and cubic B-splines in (u, v)), exactly as
//! written to the file. By Green's theorem an integral over that region is one over its
//! boundary: ∫∫_D f du dv = ∮_∂D F dv with F(u, v) = ∫_a^u f(s, v) ds, the
//! outer loop counter-clockwise, the holes clockwise; a side left out at a pole
//! runs along v = const and adds nothing, and each closed loop may take its own
//! `a` (a function of v alone integrates to zero round a closed loop). Both
//! integrals are Gauss–Legendre rules on pieces split at the pcurves' knots
//! and at the surface's knot lines, where the integrand is smooth (rational): [`ORDER`] points per piece
//! converge to round-off, which [`face_measures_with`] at two orders shows.

use glam::DVec2;

use super::brep::{Edge, Face};
use crate::nurbs::{FirstDerivatives, GaussLegendre, NurbsCurve, NurbsSurface};

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
pub fn face_measures(edges: &[Edge], face: &Face) -> FaceMeasures {
    face_measures_with(edges, face, ORDER)
}

/// The area and volume share of `face` (its uses referring to `edges`) over
/// its trimmed domain, with `order` Gauss–Legendre points per smooth piece of
/// each integral.
pub fn face_measures_with(edges: &[Edge], face: &Face, order: usize) -> FaceMeasures {
    let rule = GaussLegendre::new(order);
    let surface = &face.surface;
    let u_knots = surface.u_knots().distinct();
    let v_knots = surface.v_knots().distinct();
    let mut area = 0.0;
    let mut volume = 0.0;
    for lp in std::iter::once(&face.outer).chain(&face.holes) {
        let curves: Vec<NurbsCurve> = lp
            .iter()
            .filter_map(|e| {
                let c = edges[e.edge].curve.pcurve(&e.pcurve).ok()?;
                Some(if e.forward { c } else { c.reversed() })
            })
            .collect();
        let Some(first) = curves.first() else {
            continue;
        };
        let a = first.start().x;
        // The loop's pieces in order, and the straight segment closing each gap
        // (a pole side left out, along v = const, adds nothing).
        for c in &curves {
            for (t0, t1) in pieces(c, &u_knots, &v_knots) {
                for (t, wt) in rule.points_on(t0, t1) {
                    let d = c.derivatives(t);
                    let dv = d.first.y;
                    if dv == 0.0 {
                        continue;
                    }
                    let (fa, fv) = inner(surface, &rule, &u_knots, a, d.point.truncate());
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

/// The parameter intervals of a pcurve between its knots and its crossings of
/// the surface's knot lines, where the integrand is smooth.
fn pieces(c: &NurbsCurve, u_knots: &[f64], v_knots: &[f64]) -> Vec<(f64, f64)> {
    let spans = c.knots().distinct();
    let mut out = Vec::new();
    for w in spans.windows(2) {
        let (t0, t1) = (w[0], w[1]);
        let mut cuts = vec![t0, t1];
        // Sign changes of the coordinate minus each knot line it passes, on a
        // few steps of the span (a polynomial piece of low degree), each
        // bisected to round-off.
        const STEPS: usize = 8;
        let at = |t: f64| c.point(t).truncate();
        let steps: Vec<(f64, DVec2)> = (0..=STEPS)
            .map(|k| {
                let t = t0 + (t1 - t0) * k as f64 / STEPS as f64;
                (t, at(t))
            })
            .collect();
        for (axis, knots) in [(0usize, u_knots), (1, v_knots)] {
            for &kappa in knots {
                for s in steps.windows(2) {
                    let f = |p: DVec2| p[axis] - kappa;
                    let (fa, fb) = (f(s[0].1), f(s[1].1));
                    if fa == 0.0 {
                        cuts.push(s[0].0);
                    }
                    if fa == 0.0 || fb == 0.0 || (fa > 0.0) == (fb > 0.0) {
                        continue;
                    }
                    let (mut lo, mut hi) = (s[0].0, s[1].0);
                    let positive_at_lo = fa > 0.0;
                    for _ in 0..200 {
                        let mid = 0.5 * (lo + hi);
                        if mid <= lo || mid >= hi {
                            break;
                        }
                        if (f(at(mid)) > 0.0) == positive_at_lo {
                            lo = mid;
                        } else {
                            hi = mid;
                        }
                    }
                    cuts.push(0.5 * (lo + hi));
                }
            }
        }
        cuts.sort_by(f64::total_cmp);
        cuts.dedup();
        out.extend(cuts.windows(2).map(|w| (w[0], w[1])));
    }
    out
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
