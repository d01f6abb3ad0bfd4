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
//!
//! The 3D curve and a pcurve's image are then up to the tolerance apart. A
//! receiver may replace a pcurve by the projection of the 3D curve
//! (OpenCASCADE's STEP reader does where they are further apart than twice
//! the file's uncertainty), which moves the face's boundary across the
//! curve; along a long edge of a thin face (a reinforcing pad's sliver
//! beside a seam) that moves a measurable share of its area. Where the move
//! would exceed [`AREA_SHARE`] of the face's area, the 3D curve is written
//! as the image of that face's pcurve instead ([`follow`]), within [`AGREE`]
//! of it, on the same spans cut into pieces.

use std::collections::HashMap;

use glam::{DVec2, DVec3};

use super::brep::{Edge, EdgeCurve, Face, OrientedEdge};
use crate::nurbs::{KnotVector, NurbsCurve, NurbsError, NurbsSurface};

/// Share of the exchange tolerance the fit may use at a sample; the rest is
/// the samples' own distance from the curve between them.
pub(super) const FIT_SHARE: f64 = 0.5;

/// Samples of a node's derivative stencil.
const STENCIL: usize = 5;

/// Largest number of pieces [`follow`] cuts a span into.
const MAX_PIECES: usize = 64;

/// Largest share of a face's area a receiver may move by replacing the
/// face's pcurve of a loop edge by the projection of the edge's 3D curve
/// (as OpenCASCADE's STEP reader does where the two are further apart than
/// twice the file's uncertainty): above it, the 3D curve follows that
/// pcurve ([`follow`]).
pub(super) const AREA_SHARE: f64 = 1e-7;

/// Distance, mm, within which [`follow`] puts the 3D curve from the
/// pcurve's image: half the uncertainty the STEP file states (1e-6 mm), so
/// that a receiver keeps the pcurve as it is.
pub(super) const AGREE: f64 = 0.5e-6;

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
    d3: Vec<DVec3>,
    d2: Vec<Vec<DVec2>>,
}

/// One pcurve's samples on its surface, with `|S_u|` and `|S_v|` there.
struct Plane<'a> {
    uv: &'a [DVec2],
    metric: Vec<DVec2>,
}

/// One span of a fitted loop: its parameter range and the cubic Hermite data
/// at its ends (value and derivative by the parameter at each) of the 3D
/// curve and of each use's pcurve.
#[derive(Clone, Debug)]
pub(super) struct Span {
    pub(super) t: (f64, f64),
    /// Whether the curve may turn at the span's end (a break, or the loop
    /// edge's end): a triple knot there, a double one (C¹) otherwise.
    pub(super) turns: bool,
    pub(super) d3: Hermite<DVec3>,
    pub(super) d2: Vec<Hermite<DVec2>>,
}

/// A cubic's values and derivatives at the two ends of its span.
#[derive(Clone, Copy, Debug)]
pub(super) struct Hermite<V> {
    pub(super) start: (V, V),
    pub(super) end: (V, V),
}

impl<V> Hermite<V>
where
    V: Copy + std::ops::Mul<f64, Output = V> + std::ops::Add<Output = V>,
{
    /// The cubic's value and derivative at `x` in the span `t`.
    fn at(&self, t: (f64, f64), x: f64) -> (V, V) {
        let h = t.1 - t.0;
        let s = (x - t.0) / h;
        let (s2, s3) = (s * s, s * s * s);
        let ((p0, d0), (p1, d1)) = (self.start, self.end);
        let value = p0 * (2.0 * s3 - 3.0 * s2 + 1.0)
            + d0 * (h * (s3 - 2.0 * s2 + s))
            + p1 * (3.0 * s2 - 2.0 * s3)
            + d1 * (h * (s3 - s2));
        let slope = p0 * ((6.0 * s2 - 6.0 * s) / h)
            + d0 * (3.0 * s2 - 4.0 * s + 1.0)
            + p1 * ((6.0 * s - 6.0 * s2) / h)
            + d1 * (3.0 * s2 - 2.0 * s);
        (value, slope)
    }
}

/// Fits the samples `points` at the increasing parameters `t`, with each use's
/// (u, v) of the same samples on its surface (`uses`), to `FIT_SHARE ×
/// tolerance`, every parameter in `breaks` that is a sample's being a node:
/// nodes chosen greedily, each span as long as the 3D curve and every
/// pcurve's image keep within the bound at the samples inside it. [`net`]
/// writes the spans as B-splines.
pub(super) fn fit_spans(
    t: &[f64],
    points: &[DVec3],
    uses: &[(&NurbsSurface, &[DVec2])],
    breaks: &[f64],
    tolerance: f64,
) -> Vec<Span> {
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
    // Each piece's slopes at every sample, in 3D and in each plane (a
    // break's sample has one on each side), computed once.
    let mut out: Vec<Span> = Vec::new();
    for w in cuts.windows(2) {
        let (lo, hi) = (w[0], w[1]);
        let stencils: Vec<Stencil> = (lo..=hi).map(|k| stencil(t, lo, hi, k)).collect();
        let piece = Slopes {
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
            let b = good;
            out.push(Span {
                t: (t[a], t[b]),
                turns: b == hi,
                d3: Hermite {
                    start: (points[a], piece.d3[a - lo]),
                    end: (points[b], piece.d3[b - lo]),
                },
                d2: planes
                    .iter()
                    .zip(&piece.d2)
                    .map(|(p, d)| Hermite {
                        start: (p.uv[a], d[a - lo]),
                        end: (p.uv[b], d[b - lo]),
                    })
                    .collect(),
            });
            a = good;
        }
    }
    out
}

/// The B-splines of fitted spans: the 3D curve and each pcurve on one knot
/// vector, a double knot between two spans of a piece (both take one slope:
/// C¹), a triple one where the curve turns.
///
/// # Errors
///
/// The kernel's error where the knot vector cannot be built.
pub(super) fn net(spans: &[Span]) -> Result<LoopFit, NurbsError> {
    let Some(first) = spans.first() else {
        return Err(NurbsError::InvalidGeometry {
            what: "fitted spans of a loop edge",
            value: 0.0,
            rule: "must be at least one (two samples)",
        });
    };
    let mut knots = vec![first.t.0; 4];
    let mut c3 = vec![first.d3.start.0];
    let mut c2: Vec<Vec<DVec2>> = first.d2.iter().map(|d| vec![d.start.0]).collect();
    for (j, span) in spans.iter().enumerate() {
        let h = span.t.1 - span.t.0;
        let (a, b) = (span.d3.start, span.d3.end);
        c3.push(a.0 + a.1 * (h / 3.0));
        c3.push(b.0 - b.1 * (h / 3.0));
        for (c, d) in c2.iter_mut().zip(&span.d2) {
            c.push(d.start.0 + d.start.1 * (h / 3.0));
            c.push(d.end.0 - d.end.1 * (h / 3.0));
        }
        let last = j + 1 == spans.len();
        if last || span.turns {
            knots.extend(std::iter::repeat_n(span.t.1, if last { 4 } else { 3 }));
            c3.push(b.0);
            for (c, d) in c2.iter_mut().zip(&span.d2) {
                c.push(d.end.0);
            }
        } else {
            knots.extend([span.t.1; 2]);
        }
    }
    let knots = KnotVector::try_new(3, knots)?;
    let curve = NurbsCurve::try_polynomial(knots, &c3)?;
    Ok(LoopFit { curve, pcurves: c2 })
}

/// How far a receiver moves a face's boundary (signed area, mm²) if it
/// replaces the pcurve `plane` of `spans` on `surface` by the projection of
/// the 3D curve: the 3D curve's offset from the pcurve's image across the
/// curve within the surface, integrated along it (midpoint rule, four points
/// a span).
pub(super) fn area_shift(spans: &[Span], plane: usize, surface: &NurbsSurface) -> f64 {
    let mut shift = 0.0;
    for span in spans {
        let h = span.t.1 - span.t.0;
        for q in 0..4 {
            let x = span.t.0 + h * (f64::from(q) + 0.5) / 4.0;
            let (c, dc) = span.d3.at(span.t, x);
            let (uv, _) = span.d2[plane].at(span.t, x);
            let s = surface.first_derivatives(uv.x, uv.y);
            let across = s.du.cross(s.dv).cross(dc).normalize_or_zero();
            shift += (c - s.point).dot(across) * dc.length() * h / 4.0;
        }
    }
    shift
}

/// `spans` with the 3D curve replaced by the image of the pcurve `plane` on
/// `surface` (the receiver's projection of the 3D curve then gives that
/// pcurve back): each span cut into equal pieces, as many as it takes for
/// the cubic Hermite interpolant of the image (its values and exact
/// derivatives, `S_u u' + S_v v'`, at the pieces' ends) to lie within
/// `agree` of the image at a quarter, half and three quarters of every
/// piece (its error, of the fourth order, peaks in the middle);
/// each pcurve is cut at the same parameters, exactly (the same cubics).
pub(super) fn follow(spans: &[Span], plane: usize, surface: &NurbsSurface, agree: f64) -> Vec<Span> {
    let image = |span: &Span, x: f64| -> (DVec3, DVec3) {
        let (uv, duv) = span.d2[plane].at(span.t, x);
        let s = surface.first_derivatives(uv.x, uv.y);
        (s.point, s.du * duv.x + s.dv * duv.y)
    };
    let mut out = Vec::with_capacity(spans.len() * 4);
    for span in spans {
        let (t0, t1) = span.t;
        let pieces = |m: usize| -> Vec<Span> {
            let at = |k: usize| t0 + (t1 - t0) * k as f64 / m as f64;
            (0..m)
                .map(|k| {
                    let t = (at(k), at(k + 1));
                    Span {
                        t,
                        turns: k + 1 == m && span.turns,
                        d3: Hermite {
                            start: image(span, t.0),
                            end: image(span, t.1),
                        },
                        d2: span
                            .d2
                            .iter()
                            .map(|d| Hermite {
                                start: d.at(span.t, t.0),
                                end: d.at(span.t, t.1),
                            })
                            .collect(),
                    }
                })
                .collect()
        };
        let error = |pieces: &[Span]| -> f64 {
            pieces
                .iter()
                .flat_map(|p| {
                    [0.25, 0.5, 0.75].map(|f| {
                        let x = p.t.0 + (p.t.1 - p.t.0) * f;
                        p.d3.at(p.t, x).0.distance(image(span, x).0)
                    })
                })
                .fold(0.0, f64::max)
        };
        let mut m = 1;
        let mut cut = pieces(m);
        loop {
            let e = error(&cut);
            if e <= agree || m >= MAX_PIECES {
                break;
            }
            // The error falls with the fourth power of the piece's length.
            let grow = ((e / agree).powf(0.25) * 1.2).ceil() as usize;
            m = (m * grow.max(2)).min(MAX_PIECES);
            cut = pieces(m);
        }
        out.extend(cut);
    }
    out
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

/// A face's area, roughly (for [`AREA_SHARE`]): its loops' area in (u, v),
/// through their pcurves' points, times the surface's area element at the
/// outer loop's centroid.
fn area_estimate(face: &Face) -> f64 {
    let mut twice = 0.0;
    let mut centroid = DVec2::ZERO;
    let mut count = 0.0;
    for (l, lp) in std::iter::once(&face.outer).chain(&face.holes).enumerate() {
        let points: Vec<DVec2> = lp
            .iter()
            .flat_map(|e| {
                let mut p = e.pcurve.clone();
                if !e.forward {
                    p.reverse();
                }
                p
            })
            .collect();
        for (k, p) in points.iter().enumerate() {
            twice += p.perp_dot(points[(k + 1) % points.len()]);
            if l == 0 {
                centroid += *p;
                count += 1.0;
            }
        }
    }
    if count == 0.0 {
        return 0.0;
    }
    let c = centroid / count;
    let d = face.surface.first_derivatives(c.x, c.y);
    0.5 * twice.abs() * d.du.cross(d.dv).length()
}

/// Fits every degree-1 loop edge of a vessel's B-rep (`breaks`: each with the
/// parameters it must keep as nodes) and each face's pcurve on it, in place.
/// Where a receiver's projection of the 3D curve would move a face's
/// boundary by more than [`AREA_SHARE`] of its area (a sliver along a long
/// edge), the 3D curve follows that face's pcurve ([`follow`]).
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
    let areas: Vec<f64> = faces.iter().map(area_estimate).collect();
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
        let mut spans = fit_spans(t, &points, &planes, edge_breaks, tolerance);
        // The use whose face's area a receiver's projection of the 3D curve
        // would move most, relative to the face's area.
        let worst = samples
            .iter()
            .enumerate()
            .map(|(i, (f, _))| {
                let shift = area_shift(&spans, i, &faces[*f].surface).abs();
                (i, shift / areas[*f].max(f64::MIN_POSITIVE))
            })
            .max_by(|a, b| a.1.total_cmp(&b.1));
        if let Some((i, share)) = worst
            && share > AREA_SHARE
        {
            spans = follow(&spans, i, &faces[samples[i].0].surface, AGREE);
        }
        let fit = net(&spans).map_err(|e| (*edge, e.to_string()))?;
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
        let fit = net(&fit_spans(
            &t,
            &points,
            &[(&host, &host_uv), (&neck, &neck_uv)],
            &[0.25, 0.5, 0.75],
            tolerance,
        ))
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

    /// The same saddle loop, its 3D curve made to follow the host's pcurve:
    /// at 20 001 parameters over the loop, the 3D curve lies within
    /// [`AGREE`] of the pcurve's image (the independent fits were more than
    /// 100 × that apart), both pcurves are the curves they were (1e-12),
    /// and the area a projection of the 3D curve would move on the host is
    /// within the image's own error times the loop's length.
    #[test]
    fn a_followed_curve_is_the_image_of_its_pcurve() {
        let host = revolve(
            &line(DVec3::new(0.0, -800.0, -400.0), DVec3::new(0.0, 800.0, -400.0))
                .expect("line"),
            DVec3::ZERO,
            DVec3::Y,
            TAU,
        )
        .expect("shell");
        let neck = revolve(
            &line(DVec3::new(150.0, 0.0, 0.0), DVec3::new(150.0, 0.0, 800.0)).expect("line"),
            DVec3::ZERO,
            DVec3::Z,
            TAU,
        )
        .expect("neck");
        let tolerance = 1e-3;
        let l = neck_host_intersection(&neck, &host, tolerance).expect("loop");
        let mut t: Vec<f64> = l.neck_uv.iter().map(|p| p.x).collect();
        t.push(t[0] + 1.0);
        let mut points = l.points.clone();
        points.push(points[0]);
        let mut host_uv = l.host_uv.clone();
        host_uv.push(host_uv[0]);
        let mut neck_uv = l.neck_uv.clone();
        neck_uv.push(neck_uv[0] + DVec2::X);
        let spans = fit_spans(
            &t,
            &points,
            &[(&host, &host_uv), (&neck, &neck_uv)],
            &[0.25, 0.5, 0.75],
            tolerance,
        );
        let followed = follow(&spans, 0, &host, AGREE);
        assert!(followed.len() > spans.len());
        let (before, after) = (net(&spans).expect("fit"), net(&followed).expect("fit"));
        let pcurve = |fit: &LoopFit, i: usize| {
            let p: Vec<DVec3> = fit.pcurves[i].iter().map(|q| q.extend(0.0)).collect();
            NurbsCurve::try_polynomial(fit.curve.knots().clone(), &p).expect("pcurve")
        };
        let (a, b) = before.curve.domain();
        let (mut gap_before, mut gap_after, mut moved) = (0.0f64, 0.0f64, 0.0f64);
        for k in 0..=20_000 {
            let x = a + (b - a) * f64::from(k) / 20_000.0;
            let (old, new) = (pcurve(&before, 0).point(x), pcurve(&after, 0).point(x));
            gap_before = gap_before.max(before.curve.point(x).distance(host.point(old.x, old.y)));
            gap_after = gap_after.max(after.curve.point(x).distance(host.point(new.x, new.y)));
            moved = moved
                .max(old.distance(new))
                .max(pcurve(&before, 1).point(x).distance(pcurve(&after, 1).point(x)));
        }
        assert!(gap_before > 100.0 * AGREE, "independent fits {gap_before} mm apart");
        assert!(gap_after <= AGREE, "followed: {gap_after} mm from the image");
        assert!(moved <= 1e-12, "a pcurve moved by {moved}");
        let length: f64 = points.windows(2).map(|w| w[0].distance(w[1])).sum();
        let shift = area_shift(&followed, 0, &host).abs();
        assert!(shift <= AGREE * length, "{shift} mm² moved");
    }
}
