//! Opening loops as cubic B-splines: the exact intersection curve, marched to
//! the exchange tolerance, fitted in model space and in each face's parameter
//! plane over one parameter, the neck angle the march follows.
//!
//! The march gives exact samples of the curve (each a converged point on both
//! surfaces) at neck parameters `t`. The fit is the piecewise cubic Hermite
//! interpolant through a subset of them (the nodes), with the derivative at
//! each node taken from the Lagrange polynomial through the five samples
//! nearest to it (one-sided at the ends and at breaks, so of fourth order in
//! the samples' spacing): a cubic B-spline with double interior knots (C¹),
//! two control points per node. The same nodes and parameters give the 3D
//! curve and every pcurve, so a receiver finds them on one parameter.
//!
//! Nodes are chosen greedily, each span as long as it may be: a span is kept
//! when at every sample inside it the 3D curve lies within [`FIT_SHARE`] of the
//! tolerance of the sample, and so does each pcurve's image (bounded to first
//! order by `|S_u|·|Δu| + |S_v|·|Δv|`). The samples are at most the tolerance
//! apart from the curve between them, hence the stated bound: the written curve
//! and its pcurves' images lie within the exchange tolerance of the exact
//! curve. Breaks (the neck's knots, where its parametrization is only C¹) are
//! always nodes. The error of a cubic falls with the fourth power of the span,
//! so a loop written as ~1 200 samples at 0.001 mm needs some 30–60 spans.

use std::collections::HashMap;

use glam::{DVec2, DVec3};

use super::brep::{Edge, EdgeCurve, Face, OrientedEdge};
use crate::nurbs::{KnotVector, NurbsCurve, NurbsError, NurbsSurface};

/// Share of the exchange tolerance the fit may use at a sample; the rest is
/// the samples' own distance from the curve between them.
pub(super) const FIT_SHARE: f64 = 0.5;

/// Samples of a node's derivative stencil.
const STENCIL: usize = 5;

/// A loop edge fitted: the 3D curve and each use's pcurve control points (on
/// the curve's knots and degree).
#[derive(Clone, Debug)]
pub(super) struct LoopFit {
    pub(super) curve: NurbsCurve,
    pub(super) pcurves: Vec<Vec<DVec2>>,
}

/// One piece's slopes (between two breaks, from sample `lo`): in 3D and in
/// each plane, at each of its samples.
struct Slopes {
    lo: usize,
    d3: Vec<DVec3>,
    d2: Vec<Vec<DVec2>>,
}

/// One pcurve's samples on its surface, with `|S_u|` and `|S_v|` there.
struct Plane<'a> {
    uv: &'a [DVec2],
    metric: Vec<DVec2>,
}

/// Fits the samples `points` at the increasing parameters `t`, with each use's
/// (u, v) of the same samples on its surface, to `FIT_SHARE × tolerance`,
/// every parameter in `breaks` that is a sample's being a node.
///
/// # Errors
///
/// The kernel's error where the knot vector cannot be built (fewer than two
/// samples, parameters not increasing).
pub(super) fn fit_loop(
    t: &[f64],
    points: &[DVec3],
    uses: &[(&NurbsSurface, &[DVec2])],
    breaks: &[f64],
    tolerance: f64,
) -> Result<LoopFit, NurbsError> {
    let n = t.len();
    let bound = FIT_SHARE * tolerance;
    let planes: Vec<Plane> = uses
        .iter()
        .map(|(surface, uv)| Plane {
            uv,
            metric: uv
                .iter()
                .map(|p| {
                    let d = surface.first_derivatives(p.x, p.y);
                    DVec2::new(d.du.length(), d.dv.length())
                })
                .collect(),
        })
        .collect();
    // Pieces between breaks: the first and last samples and those at a break.
    let span = (t[n - 1] - t[0]).abs().max(1e-300);
    let mut cuts = vec![0];
    for (k, &tk) in t.iter().enumerate().take(n - 1).skip(1) {
        if breaks.iter().any(|&b| (tk - b).abs() <= 1e-12 * span) {
            cuts.push(k);
        }
    }
    cuts.push(n - 1);
    // Spans (a, b) with the piece their slopes are taken on; each piece's
    // slopes at every sample, in 3D and in each plane (a break's sample has
    // one on each side), computed once.
    let mut spans: Vec<(usize, usize, usize)> = Vec::new();
    let mut slopes: Vec<Slopes> = Vec::with_capacity(cuts.len() - 1);
    for w in cuts.windows(2) {
        let (lo, hi) = (w[0], w[1]);
        let stencils: Vec<Stencil> = (lo..=hi).map(|k| stencil(t, lo, hi, k)).collect();
        let piece = Slopes {
            lo,
            d3: stencils.iter().map(|s| s.apply(points)).collect(),
            d2: planes
                .iter()
                .map(|p| stencils.iter().map(|s| s.apply(p.uv)).collect())
                .collect(),
        };
        let fits = |a: usize, b: usize| -> bool {
            let (da, db) = (piece.d3[a - lo], piece.d3[b - lo]);
            if (a + 1..b)
                .any(|k| hermite(t, points, a, b, da, db, t[k]).distance(points[k]) > bound)
            {
                return false;
            }
            planes.iter().zip(&piece.d2).all(|(p, d)| {
                let (da, db) = (d[a - lo], d[b - lo]);
                (a + 1..b).all(|k| {
                    let e = (hermite(t, p.uv, a, b, da, db, t[k]) - p.uv[k]).abs();
                    e.dot(p.metric[k]) <= bound
                })
            })
        };
        let mut a = lo;
        let mut step = 8usize;
        while a < hi {
            // The longest span from `a`: grow while it fits, then bisect.
            let mut good = a + 1;
            let mut bad = None;
            loop {
                let b = (a + step).min(hi);
                if fits(a, b) {
                    good = b;
                    if b == hi {
                        break;
                    }
                    step *= 2;
                } else {
                    bad = Some(b);
                    break;
                }
            }
            if let Some(mut bad) = bad {
                while bad - good > 1 {
                    let mid = (good + bad) / 2;
                    if fits(a, mid) {
                        good = mid;
                    } else {
                        bad = mid;
                    }
                }
            }
            step = (good - a).max(2);
            spans.push((a, good, slopes.len()));
            a = good;
        }
        slopes.push(piece);
    }
    // The Bézier net: a double knot at a node inside a piece (both spans take
    // its one slope: C¹), a triple one at a break (each side its own slope).
    let mut knots = vec![t[0]; 4];
    let mut c3 = vec![points[0]];
    let mut c2: Vec<Vec<DVec2>> = planes.iter().map(|p| vec![p.uv[0]]).collect();
    for (j, &(a, b, piece)) in spans.iter().enumerate() {
        let h = t[b] - t[a];
        let piece = &slopes[piece];
        let (da, db) = (piece.d3[a - piece.lo], piece.d3[b - piece.lo]);
        c3.push(points[a] + da * (h / 3.0));
        c3.push(points[b] - db * (h / 3.0));
        for ((c, p), d) in c2.iter_mut().zip(&planes).zip(&piece.d2) {
            let (da, db) = (d[a - piece.lo], d[b - piece.lo]);
            c.push(p.uv[a] + da * (h / 3.0));
            c.push(p.uv[b] - db * (h / 3.0));
        }
        let hi = piece.lo + piece.d3.len() - 1;
        let last = j + 1 == spans.len();
        if last || b == hi {
            knots.extend(std::iter::repeat_n(t[b], if last { 4 } else { 3 }));
            c3.push(points[b]);
            for (c, p) in c2.iter_mut().zip(&planes) {
                c.push(p.uv[b]);
            }
        } else {
            knots.extend([t[b]; 2]);
        }
    }
    let knots = KnotVector::try_new(3, knots)?;
    let curve = NurbsCurve::try_polynomial(knots, &c3)?;
    Ok(LoopFit { curve, pcurves: c2 })
}

/// The derivative at a sample of the Lagrange polynomial through the
/// [`STENCIL`] samples nearest to it within a piece, as weights of those
/// samples' values: the same for the 3D points and every pcurve's (u, v).
struct Stencil {
    first: usize,
    count: usize,
    weights: [f64; STENCIL],
}

impl Stencil {
    /// The derivative of `values` at the stencil's sample.
    fn apply<V>(&self, values: &[V]) -> V
    where
        V: Copy + std::ops::Mul<f64, Output = V> + std::ops::Add<Output = V> + Default,
    {
        let mut out = V::default();
        for (i, &w) in self.weights[..self.count].iter().enumerate() {
            out = out + values[self.first + i] * w;
        }
        out
    }
}

/// The stencil of sample `k` within `lo..=hi`.
fn stencil(t: &[f64], lo: usize, hi: usize, k: usize) -> Stencil {
    let count = STENCIL.min(hi - lo + 1);
    let first = k.saturating_sub(count / 2).max(lo).min(hi + 1 - count);
    let xs = &t[first..first + count];
    let at = k - first;
    let x = xs[at];
    // L_i'(x) = Σ_{j≠i} 1/(xi − xj) · Π_{l≠i,j} (x − xl)/(xi − xl), at the
    // node x = x_at: for i ≠ at only the term j = at is not zero; for i = at
    // every product is 1.
    let mut weights = [0.0; STENCIL];
    for (i, &xi) in xs.iter().enumerate() {
        weights[i] = if i == at {
            xs.iter()
                .enumerate()
                .filter(|&(j, _)| j != at)
                .map(|(_, &xj)| 1.0 / (xi - xj))
                .sum()
        } else {
            let mut term = 1.0 / (xi - x);
            for (l, &xl) in xs.iter().enumerate() {
                if l != i && l != at {
                    term *= (x - xl) / (xi - xl);
                }
            }
            term
        };
    }
    Stencil {
        first,
        count,
        weights,
    }
}

/// The cubic Hermite interpolant between samples `a` and `b` (slopes `da`,
/// `db`) at parameter `x`.
fn hermite<V>(t: &[f64], values: &[V], a: usize, b: usize, da: V, db: V, x: f64) -> V
where
    V: Copy + std::ops::Mul<f64, Output = V> + std::ops::Add<Output = V>,
{
    let h = t[b] - t[a];
    let s = (x - t[a]) / h;
    let (s2, s3) = (s * s, s * s * s);
    values[a] * (2.0 * s3 - 3.0 * s2 + 1.0)
        + da * (h * (s3 - 2.0 * s2 + s))
        + values[b] * (3.0 * s2 - 2.0 * s3)
        + db * (h * (s3 - s2))
}

/// Fits every degree-1 loop edge of a vessel's B-rep (`breaks`: each with the
/// parameters it must keep as nodes) and each face's pcurve on it, in place.
///
/// # Errors
///
/// The edge's index and a message where a use's pcurve does not have one
/// point per sample or the fit cannot be built.
pub(super) fn fit_loops(
    edges: &mut [Edge],
    faces: &mut [Face],
    breaks: &[(usize, Vec<f64>)],
    tolerance: f64,
) -> Result<(), (usize, String)> {
    // Each edge's uses: (face, loop: 0 outer, 1 + hole, use).
    let mut uses: HashMap<usize, Vec<(usize, usize, usize)>> = HashMap::new();
    for (f, face) in faces.iter().enumerate() {
        for (l, lp) in std::iter::once(&face.outer).chain(&face.holes).enumerate() {
            for (k, e) in lp.iter().enumerate() {
                uses.entry(e.edge).or_default().push((f, l, k));
            }
        }
    }
    let use_of = |faces: &[Face], (f, l, k): (usize, usize, usize)| -> OrientedEdge {
        let face = &faces[f];
        if l == 0 {
            face.outer[k].clone()
        } else {
            face.holes[l - 1][k].clone()
        }
    };
    for (edge, edge_breaks) in breaks {
        let EdgeCurve::Loop(line) = &edges[*edge].curve else {
            continue;
        };
        if line.degree() != 1 {
            continue;
        }
        let points = line.control_points();
        let knots = line.knots().as_slice();
        let t = &knots[1..knots.len() - 1];
        let its_uses = uses.get(edge).cloned().unwrap_or_default();
        let samples: Vec<(usize, Vec<DVec2>)> = its_uses
            .iter()
            .map(|&u| (u.0, use_of(faces, u).pcurve))
            .collect();
        if let Some((_, bad)) = samples.iter().find(|(_, uv)| uv.len() != points.len()) {
            return Err((
                *edge,
                format!(
                    "a pcurve has {} points for the loop's {} samples",
                    bad.len(),
                    points.len()
                ),
            ));
        }
        let planes: Vec<(&NurbsSurface, &[DVec2])> = samples
            .iter()
            .map(|(f, uv)| (&faces[*f].surface, uv.as_slice()))
            .collect();
        let fit = fit_loop(t, &points, &planes, edge_breaks, tolerance)
            .map_err(|e| (*edge, e.to_string()))?;
        edges[*edge].curve = EdgeCurve::Loop(fit.curve);
        for (&(f, l, k), pcurve) in its_uses.iter().zip(fit.pcurves) {
            let face = &mut faces[f];
            let e = if l == 0 {
                &mut face.outer[k]
            } else {
                &mut face.holes[l - 1][k]
            };
            e.pcurve = pcurve;
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use std::f64::consts::TAU;

    use glam::{DVec2, DVec3};

    use super::*;
    use crate::nurbs::builders::{line, revolve};
    use crate::nurbs::intersect::neck_host_intersection;

    /// A nozzle of radius 150 on a shell of radius 400 (a saddle-shaped loop):
    /// the loop marched at 0.001 mm, fitted, lies within 0.001 mm of the exact
    /// curve at every sample of a march at 0.00001 mm, in 3D and through both
    /// pcurves, at the same parameter; with a few dozen spans for ~1 000
    /// samples.
    #[test]
    fn a_fitted_loop_keeps_within_the_tolerance_of_the_exact_curve() {
        let (radius, host_radius) = (150.0, 400.0);
        // The shell's seam at its bottom, away from the nozzle on top (a loop
        // across a seam is split before it is fitted).
        let host = revolve(
            &line(
                DVec3::new(0.0, -800.0, -host_radius),
                DVec3::new(0.0, 800.0, -host_radius),
            )
            .expect("line"),
            DVec3::ZERO,
            DVec3::Y,
            TAU,
        )
        .expect("shell");
        let neck = revolve(
            &line(
                DVec3::new(radius, 0.0, 0.0),
                DVec3::new(radius, 0.0, 2.0 * host_radius),
            )
            .expect("line"),
            DVec3::ZERO,
            DVec3::Z,
            TAU,
        )
        .expect("neck");
        let tolerance = 1e-3;
        let coarse = neck_host_intersection(&neck, &host, tolerance).expect("loop");
        let exact = neck_host_intersection(&neck, &host, 1e-5).expect("loop");
        // Closed: the first sample again, one neck period on.
        let closed = |l: &crate::nurbs::intersect::IntersectionLoop| {
            let mut t: Vec<f64> = l.neck_uv.iter().map(|p| p.x).collect();
            t.push(t[0] + 1.0);
            let mut points = l.points.clone();
            points.push(points[0]);
            let mut host_uv = l.host_uv.clone();
            host_uv.push(host_uv[0]);
            let mut neck_uv = l.neck_uv.clone();
            neck_uv.push(neck_uv[0] + DVec2::X);
            (t, points, host_uv, neck_uv)
        };
        let (t, points, host_uv, neck_uv) = closed(&coarse);
        let fit = fit_loop(
            &t,
            &points,
            &[(&host, &host_uv), (&neck, &neck_uv)],
            &[0.25, 0.5, 0.75],
            tolerance,
        )
        .expect("fit");
        let spans = fit.curve.knots().distinct().len() - 1;
        assert!(
            spans * 10 < t.len(),
            "{spans} spans for {} samples",
            t.len()
        );
        let knots = fit.curve.knots().clone();
        let pcurve = |uv: &[DVec2]| {
            let p: Vec<DVec3> = uv.iter().map(|q| q.extend(0.0)).collect();
            NurbsCurve::try_polynomial(knots.clone(), &p).expect("pcurve")
        };
        let (on_host, on_neck) = (pcurve(&fit.pcurves[0]), pcurve(&fit.pcurves[1]));
        // The exact loop may start elsewhere round the neck: its samples are
        // taken into the fit's one period.
        let (start, end) = (t[0], t[t.len() - 1]);
        let (exact_t, points, _, _) = closed(&exact);
        let mut worst: f64 = 0.0;
        for (&t, &p) in exact_t.iter().zip(&points) {
            let t = start + (t - start).rem_euclid(end - start);
            let h = on_host.point(t);
            let n = on_neck.point(t);
            for q in [
                fit.curve.point(t),
                host.point(h.x, h.y),
                neck.point(n.x, n.y),
            ] {
                worst = worst.max(q.distance(p));
            }
        }
        assert!(worst <= tolerance, "worst {worst} mm");
    }
}
