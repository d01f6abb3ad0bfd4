//! Patch-edge discretization from the edge curve alone.
//!
//! Two patches that share an edge must put the same vertices on it, or the mesh
//! cracks. The patches may live in different part frames and run along the edge in
//! opposite directions, so nothing here looks at a surface or a parametrization: the
//! vertices are placed at equal steps of ARC LENGTH, and their number depends only on
//! the curve's length and its largest curvature. Any NURBS tracing the same point set
//! from the same start point (reversed, transformed, or built differently) therefore
//! yields the same 3D vertices, up to the accuracy of the arc-length inversion
//! (about 1e-14 of the length).
//!
//! Pipeline: the speed |C′| is fitted on every Bézier span by 16-term Legendre
//! series (pieces halved until the series' tail is negligible), which gives the arc
//! length and its inverse without further curve evaluations; the curvature is
//! sampled at the same nodes and at the span ends, its largest value refined by a
//! golden-section search. The segment count is `n = ⌈L / h(κ_max)⌉`, where `h(κ)` is
//! the arc length of the longest step allowed at curvature κ:
//!
//! - chordal tolerance δ: the arc of a circle of radius ρ = 1/κ whose sagitta is δ,
//!   `ρ·θ` with `θ = 2·arccos(1 − δ/ρ)` (θ = π once δ ≥ ρ, the chord `2ρ`);
//! - angle tolerance α: `α·ρ` (the tangent turns by at most α along a segment);
//! - maximum edge length: the arc itself, so the chord is shorter still.
//!
//! For a circle this is the closed form `n = ⌈2π / θ⌉` (R = 1000 mm, δ = 0.5 mm →
//! 100 segments). The count uses the LARGEST curvature rather than `∫ ds / h(κ)`:
//! with equal arc-length steps the steepest part of the curve (the equator of an
//! ellipsoidal head's meridian) must still meet the tolerance. For curves of constant
//! curvature (lines, circles, the knuckle and crown arcs of heads) both agree.
//!
//! Cost: about 35 curve evaluations per curved Bézier span (a full circle: ~140,
//! some 15 µs), plus a short Newton solve on a polynomial per vertex (~0.15 µs).
//! A full circle of four rational quarter arcs — most edges of a vessel — skips
//! all of it (`circles`): its length is 2πR, its curvature 1/R, and the
//! parameter of each angle is known in closed form.

use std::sync::OnceLock;

use super::circles::Circle;
use crate::MODEL_EPSILON;
use crate::mesh::TessellationOptions;
use crate::nurbs::{GaussLegendre, NurbsCurve};

/// Most segments an edge gets. Beyond it the tolerance is not met (an absurdly fine
/// tolerance on a large curve, or invalid options); `multiple_of` rounding may add
/// up to `multiple_of − 1` more.
pub const MAX_EDGE_SEGMENTS: usize = 1 << 16;

/// Terms of the Legendre series fitted to the speed on one piece (and nodes of the
/// Gauss–Legendre rule that fits them).
const TERMS: usize = 16;

/// A piece is accepted when its last two Legendre coefficients are below this
/// fraction of the mean speed (rounding leaves about 1e-15).
const TAIL_TOLERANCE: f64 = 1e-13;

/// Deepest halving of a Bézier span (a bound on the work near cusps, where |C′|
/// is not smooth).
const MAX_DEPTH: u32 = 12;

/// The raw count is reduced by this fraction before rounding up, so that a count
/// that is an integer in exact arithmetic (a line of 1000 mm with 100 mm edges) is
/// not pushed to the next one by rounding.
const COUNT_MARGIN: f64 = 1e-9;

/// Samples slower than this fraction of the mean speed are ignored for curvature
/// (near a stationary point the formula divides by |C′|³).
const SPEED_FLOOR: f64 = 1e-6;

/// Golden-section iterations refining the largest curvature (the bracket shrinks by
/// 0.618 per iteration).
const GOLDEN_ITERATIONS: usize = 50;

/// Parameters along `curve` (including both ends, increasing) at which to place mesh
/// vertices so that every chord deviates from the curve by at most
/// [`TessellationOptions::tolerance`] and respects the angle tolerance and maximum
/// edge length when set.
///
/// The vertices are spaced uniformly in arc length, and the segment count
/// ([`edge_segments`]) depends on the curve's shape only, rounded up to a multiple
/// of `multiple_of` (0 counts as 1). The same geometric curve traversed in either
/// direction, or represented by a different but equal NURBS starting at the same
/// point, therefore yields the same points. A degenerate curve (shorter than
/// [`MODEL_EPSILON`], e.g. a pole) or one whose length overflows yields just its two
/// end parameters. Options are expected to be valid
/// ([`TessellationOptions::validate`]); invalid ones give [`MAX_EDGE_SEGMENTS`].
pub fn edge_parameters(
    curve: &NurbsCurve,
    options: &TessellationOptions,
    multiple_of: usize,
) -> Vec<f64> {
    if one_straight_segment(curve, options, multiple_of) {
        let (a, b) = curve.domain();
        return vec![a, b];
    }
    measured_parameters(curve, options, multiple_of)
}

/// [`edge_parameters`] by the curve's closed form (a full circle) or its
/// measured profile.
fn measured_parameters(
    curve: &NurbsCurve,
    options: &TessellationOptions,
    multiple_of: usize,
) -> Vec<f64> {
    let (a, b) = curve.domain();
    if let Some(circle) = Circle::of(curve) {
        let n = segment_count(circle.length(), 1.0 / circle.radius, options, multiple_of);
        return circle.parameters(n);
    }
    let Some(profile) = Profile::of(curve) else {
        return vec![a, b];
    };
    let n = profile.segments(options, multiple_of);
    let mut params = Vec::with_capacity(n + 1);
    params.push(a);
    let mut index = 0;
    for k in 1..n {
        let target = profile.length * k as f64 / n as f64;
        while index + 1 < profile.pieces.len()
            && profile.pieces[index].offset + profile.pieces[index].length < target
        {
            index += 1;
        }
        let piece = &profile.pieces[index];
        let previous = params[params.len() - 1];
        params.push(piece.invert(target - piece.offset).clamp(previous, b));
    }
    params.push(b);
    params
}

/// Whether [`edge_parameters`] gives `curve` one segment without measuring it:
/// a straight segment (degree 1, two control points, equal weights: its
/// curvature is exactly zero) when no edge length limit or multiple asks for
/// more, and the tolerance is valid. A course's or a cone's meridian, which
/// every layout of a course or cone samples at its seam.
fn one_straight_segment(
    curve: &NurbsCurve,
    options: &TessellationOptions,
    multiple_of: usize,
) -> bool {
    let points = curve.homogeneous_points();
    curve.degree() == 1
        && points.len() == 2
        && points[0].w == points[1].w
        && options.max_edge_length.is_none()
        && multiple_of <= 1
        && options.tolerance > 0.0
}

/// Number of segments [`edge_parameters`] places on `curve` (one less than the
/// number of parameters it returns): 1 for a degenerate curve.
pub fn edge_segments(
    curve: &NurbsCurve,
    options: &TessellationOptions,
    multiple_of: usize,
) -> usize {
    if let Some(circle) = Circle::of(curve) {
        return segment_count(circle.length(), 1.0 / circle.radius, options, multiple_of);
    }
    Profile::of(curve).map_or(1, |p| p.segments(options, multiple_of))
}

/// Segments for a curve of `length` whose largest curvature is `max_curvature`,
/// rounded up to a multiple of `multiple_of`.
fn segment_count(
    length: f64,
    max_curvature: f64,
    options: &TessellationOptions,
    multiple_of: usize,
) -> usize {
    let raw = length * density(max_curvature, options);
    let n = if raw.is_finite() && raw < MAX_EDGE_SEGMENTS as f64 {
        ((raw * (1.0 - COUNT_MARGIN)).ceil() as usize).max(1)
    } else {
        MAX_EDGE_SEGMENTS
    };
    let m = multiple_of.clamp(1, MAX_EDGE_SEGMENTS);
    n.div_ceil(m) * m
}

/// Arc length per segment allowed at curvature `kappa` (1/mm), as its inverse:
/// segments per mm. Infinite for invalid options.
fn density(kappa: f64, options: &TessellationOptions) -> f64 {
    let delta = options.tolerance;
    if delta.is_nan() || delta <= 0.0 {
        return f64::INFINITY;
    }
    let mut d = 0.0f64;
    if kappa > 0.0 {
        // θ = 2·arccos(1 − x) = 4·asin(√(x/2)), stable for tiny x = δκ.
        let x = (delta * kappa).min(1.0);
        let theta = 4.0 * (0.5 * x).sqrt().asin();
        d = d.max(kappa / theta);
        if let Some(angle) = options.angle_tolerance {
            let angle = angle.to_radians();
            if angle.is_nan() || angle <= 0.0 {
                return f64::INFINITY;
            }
            d = d.max(kappa / angle);
        }
    }
    if let Some(length) = options.max_edge_length {
        if length.is_nan() || length <= 0.0 {
            return f64::INFINITY;
        }
        d = d.max(1.0 / length);
    }
    d
}

/// Gauss–Legendre nodes and weights with the Legendre polynomials at the nodes.
struct Table {
    nodes: [f64; TERMS],
    weights: [f64; TERMS],
    /// `legendre[j][i]` = P_j(node i).
    legendre: [[f64; TERMS]; TERMS],
}

/// The table shared by every edge, computed on first use.
fn table() -> &'static Table {
    static TABLE: OnceLock<Table> = OnceLock::new();
    TABLE.get_or_init(|| {
        let rule = GaussLegendre::new(TERMS);
        let mut nodes = [0.0; TERMS];
        let mut weights = [0.0; TERMS];
        nodes.copy_from_slice(rule.nodes());
        weights.copy_from_slice(rule.weights());
        let mut legendre = [[0.0; TERMS]; TERMS];
        for (i, &x) in nodes.iter().enumerate() {
            let p = legendre_values::<TERMS>(x);
            for (j, row) in legendre.iter_mut().enumerate() {
                row[i] = p[j];
            }
        }
        Table {
            nodes,
            weights,
            legendre,
        }
    })
}

/// Coefficients of the Legendre recurrence
/// `P_{k+1} = (2k+1)/(k+1) · x · P_k − k/(k+1) · P_{k−1}`, for k < [`TERMS`].
const RECURRENCE: [[f64; 2]; TERMS] = {
    let mut out = [[0.0; 2]; TERMS];
    let mut k = 0;
    while k < TERMS {
        out[k] = [
            (2 * k + 1) as f64 / (k + 1) as f64,
            k as f64 / (k + 1) as f64,
        ];
        k += 1;
    }
    out
};

/// P_0(x) … P_{N−1}(x) by the three-term recurrence.
#[inline]
fn legendre_values<const N: usize>(x: f64) -> [f64; N] {
    let mut p = [0.0; N];
    p[0] = 1.0;
    if N > 1 {
        p[1] = x;
    }
    for k in 1..N.saturating_sub(1) {
        let kf = k as f64;
        p[k + 1] = ((2.0 * kf + 1.0) * x * p[k] - kf * p[k - 1]) / (kf + 1.0);
    }
    p
}

/// One parameter interval `[mid − half, mid + half]` with the speed as a Legendre
/// series in `x = (u − mid) / half` and its integral from `x = −1`.
struct Piece {
    mid: f64,
    half: f64,
    /// Arc length from the curve's start to the piece's start, mm.
    offset: f64,
    /// Arc length of the piece, mm.
    length: f64,
    /// Legendre coefficients of |C′| (per unit parameter).
    speed: [f64; TERMS],
    /// Legendre coefficients of ∫₋₁ˣ |C′| dx (per unit x).
    integral: [f64; TERMS + 1],
}

impl Piece {
    /// The piece over `[a, b]` from the speeds at the mapped Gauss nodes.
    fn new(a: f64, b: f64, speeds: &[f64; TERMS]) -> Self {
        let t = table();
        let mut speed = [0.0; TERMS];
        for (j, c) in speed.iter_mut().enumerate() {
            let sum: f64 = (0..TERMS)
                .map(|i| t.weights[i] * speeds[i] * t.legendre[j][i])
                .sum();
            *c = (2 * j + 1) as f64 / 2.0 * sum;
        }
        // ∫₋₁ˣ P_0 = P_0 + P_1; ∫₋₁ˣ P_j = (P_{j+1} − P_{j−1}) / (2j + 1) for j ≥ 1.
        let mut integral = [0.0; TERMS + 1];
        integral[0] += speed[0];
        integral[1] += speed[0];
        for j in 1..TERMS {
            let c = speed[j] / (2 * j + 1) as f64;
            integral[j + 1] += c;
            integral[j - 1] -= c;
        }
        let half = 0.5 * (b - a);
        Self {
            mid: 0.5 * (a + b),
            half,
            offset: 0.0,
            length: 2.0 * speed[0] * half,
            speed,
            integral,
        }
    }

    /// True when the series has converged.
    fn converged(&self) -> bool {
        let tail = self.speed[TERMS - 2].abs() + self.speed[TERMS - 1].abs();
        tail <= TAIL_TOLERANCE * self.speed[0].abs()
    }

    /// Arc length from the piece's start to `x`, and d/dx of it: both series summed
    /// along the three-term recurrence of the Legendre polynomials.
    #[inline]
    fn length_at(&self, x: f64) -> (f64, f64) {
        let (mut previous, mut current) = (1.0, x);
        let mut s = self.integral[0] + self.integral[1] * x;
        let mut ds = self.speed[0] + self.speed[1] * x;
        for (k, &[a, b]) in RECURRENCE.iter().enumerate().skip(1) {
            let next = a * x * current - b * previous;
            previous = current;
            current = next;
            s += self.integral[k + 1] * current;
            if k + 1 < TERMS {
                ds += self.speed[k + 1] * current;
            }
        }
        (self.half * s, self.half * ds)
    }

    /// The parameter at arc length `r` from the piece's start: Newton's method on
    /// the series, safeguarded by bisection.
    fn invert(&self, r: f64) -> f64 {
        if self.length.is_nan() || self.length <= 0.0 {
            return self.mid - self.half;
        }
        let r = r.clamp(0.0, self.length);
        let (mut low, mut high) = (-1.0f64, 1.0f64);
        let mut x = -1.0 + 2.0 * r / self.length;
        for _ in 0..100 {
            let (s, ds) = self.length_at(x);
            let f = s - r;
            if f > 0.0 {
                high = x;
            } else {
                low = x;
            }
            let mut next = x - f / ds;
            if (next - x).abs() <= 1e-15 {
                x = next;
                break;
            }
            if !(next > low && next < high) {
                next = 0.5 * (low + high);
            }
            if high - low <= 1e-15 {
                x = next;
                break;
            }
            x = next;
        }
        self.mid + self.half * x.clamp(-1.0, 1.0)
    }
}

/// A curvature sample.
#[derive(Clone, Copy)]
struct Sample {
    u: f64,
    speed: f64,
    curvature: f64,
}

/// Arc length and curvature of one curve.
struct Profile {
    pieces: Vec<Piece>,
    length: f64,
    max_curvature: f64,
}

impl Profile {
    /// The profile of `curve`; `None` for a degenerate curve (shorter than
    /// [`MODEL_EPSILON`]) or one whose evaluation overflows.
    fn of(curve: &NurbsCurve) -> Option<Self> {
        let mut pieces = Vec::new();
        let mut samples = Vec::new();
        for (a, b) in curve.knots().spans() {
            samples.push(sample(curve, a));
            if curve.degree() == 1 {
                // Constant speed on a span: one piece is exact.
                fit(curve, a, b, 0, &mut pieces, &mut samples)?;
            } else {
                // Curved spans need about two pieces (a 90° arc does).
                let mid = 0.5 * (a + b);
                fit(curve, a, mid, 1, &mut pieces, &mut samples)?;
                fit(curve, mid, b, 1, &mut pieces, &mut samples)?;
            }
            samples.push(sample(curve, b.next_down().max(a)));
        }
        let mut length = 0.0;
        for piece in &mut pieces {
            piece.offset = length;
            length += piece.length;
        }
        if !length.is_finite() || length <= MODEL_EPSILON {
            return None;
        }
        let (u0, u1) = curve.domain();
        let floor = SPEED_FLOOR * length / (u1 - u0);
        samples.retain(|s| s.speed >= floor && s.curvature.is_finite());
        samples.sort_by(|p, q| p.u.total_cmp(&q.u));
        let max_curvature = max_curvature(curve, &samples, floor);
        Some(Self {
            pieces,
            length,
            max_curvature,
        })
    }

    /// Segment count for `options`, rounded up to a multiple of `multiple_of`.
    fn segments(&self, options: &TessellationOptions, multiple_of: usize) -> usize {
        segment_count(self.length, self.max_curvature, options, multiple_of)
    }
}

/// Speed and curvature at `u`.
fn sample(curve: &NurbsCurve, u: f64) -> Sample {
    let d = curve.derivatives(u);
    let speed = d.first.length();
    Sample {
        u,
        speed,
        curvature: d.first.cross(d.second).length() / (speed * speed * speed),
    }
}

/// Fits pieces on `[a, b]` (inside one Bézier span), halving until the speed's
/// series converges. `None` when the speed is not finite.
fn fit(
    curve: &NurbsCurve,
    a: f64,
    b: f64,
    depth: u32,
    pieces: &mut Vec<Piece>,
    samples: &mut Vec<Sample>,
) -> Option<()> {
    let t = table();
    let (mid, half) = (0.5 * (a + b), 0.5 * (b - a));
    let mut speeds = [0.0; TERMS];
    for (speed, &x) in speeds.iter_mut().zip(&t.nodes) {
        let s = sample(curve, mid + half * x);
        if !s.speed.is_finite() {
            return None;
        }
        *speed = s.speed;
        samples.push(s);
    }
    let piece = Piece::new(a, b, &speeds);
    if piece.converged() || depth >= MAX_DEPTH || !(mid > a && mid < b) {
        pieces.push(piece);
        return Some(());
    }
    fit(curve, a, mid, depth + 1, pieces, samples)?;
    fit(curve, mid, b, depth + 1, pieces, samples)
}

/// The largest curvature: the largest sample, refined by golden-section search
/// between its neighbours when the curvature varies.
fn max_curvature(curve: &NurbsCurve, samples: &[Sample], floor: f64) -> f64 {
    let Some((best, top)) = samples
        .iter()
        .enumerate()
        .max_by(|(_, p), (_, q)| p.curvature.total_cmp(&q.curvature))
    else {
        return 0.0;
    };
    let low = samples
        .iter()
        .map(|s| s.curvature)
        .fold(f64::INFINITY, f64::min);
    if top.curvature - low <= 1e-9 * top.curvature {
        return top.curvature;
    }
    let mut a = samples[best.saturating_sub(1)].u;
    let mut b = samples[(best + 1).min(samples.len() - 1)].u;
    let value = |u: f64| {
        let s = sample(curve, u);
        if s.speed >= floor && s.curvature.is_finite() {
            s.curvature
        } else {
            0.0
        }
    };
    let ratio = 0.5 * (5f64.sqrt() - 1.0);
    let mut c = b - ratio * (b - a);
    let mut d = a + ratio * (b - a);
    let (mut fc, mut fd) = (value(c), value(d));
    let mut found = top.curvature.max(fc).max(fd);
    for _ in 0..GOLDEN_ITERATIONS {
        if fc > fd {
            b = d;
            d = c;
            fd = fc;
            c = b - ratio * (b - a);
            fc = value(c);
            found = found.max(fc);
        } else {
            a = c;
            c = d;
            fc = fd;
            d = a + ratio * (b - a);
            fd = value(d);
            found = found.max(fd);
        }
    }
    found
}

#[cfg(test)]
mod tests {
    use std::f64::consts::TAU;

    use glam::DVec3;

    use super::*;
    use crate::nurbs::builders::circular_arc;

    /// A straight segment takes one segment without being measured, as the
    /// measure gives it: lines of any length and direction, domains and
    /// tolerances; not when an edge length limit or a multiple asks for more.
    #[test]
    fn a_straight_segment_is_one_segment_as_measured() {
        use crate::nurbs::builders::line;
        let ends = [
            (DVec3::ZERO, DVec3::new(0.0, 0.0, 2400.0)),
            (DVec3::new(900.0, 0.0, 0.0), DVec3::new(900.0, 0.0, 12345.6)),
            (DVec3::new(-3.0, 7.0, 1.0), DVec3::new(250.0, -40.0, 33.0)),
            (DVec3::ONE, DVec3::ONE),
        ];
        for (p, q) in ends {
            let curve = line(p, q).expect("a line");
            for curve in [
                curve.clone(),
                curve.reparametrized(-5.0, 17.5).expect("reparam"),
            ] {
                for tolerance in [0.01, 0.5, 1.0, 30.0] {
                    let options = TessellationOptions::chord(tolerance);
                    assert!(one_straight_segment(&curve, &options, 1));
                    assert_eq!(
                        edge_parameters(&curve, &options, 1),
                        measured_parameters(&curve, &options, 1)
                    );
                }
                let limited = TessellationOptions::chord(1.0).with_max_edge_length(Some(100.0));
                assert!(!one_straight_segment(&curve, &limited, 1));
                assert!(!one_straight_segment(
                    &curve,
                    &TessellationOptions::chord(1.0),
                    4
                ));
            }
        }
    }

    /// A full circle takes the closed form: the same segment count as the
    /// general sampler, its vertices uniform in angle on the circle, and the
    /// general sampler's parameters to within its own accuracy.
    #[test]
    fn a_full_circle_is_sampled_in_closed_form() {
        use crate::nurbs::builders::{line, revolve};
        // A circle as `circular_arc` builds it, and one as a course's end edge.
        let arc = circular_arc(DVec3::ZERO, DVec3::X, DVec3::Y, 1000.0, 0.0, TAU).unwrap();
        let generator = line(
            DVec3::new(1700.0, 0.0, 0.0),
            DVec3::new(1700.0, 0.0, 3000.0),
        )
        .unwrap();
        let course = revolve(&generator, DVec3::ZERO, DVec3::Z, TAU).unwrap();
        let end = course.boundary(crate::nurbs::Side::VMax);
        for (curve, radius, centre) in [
            (arc, 1000.0, DVec3::ZERO),
            (end, 1700.0, DVec3::new(0.0, 0.0, 3000.0)),
        ] {
            assert!(super::super::circles::Circle::of(&curve).is_some());
            for (tol, multiple) in [(1.0, 8), (0.1, 8), (0.5, 1)] {
                let options = TessellationOptions::chord(tol);
                let params = edge_parameters(&curve, &options, multiple);
                let profile = Profile::of(&curve).unwrap();
                let n = profile.segments(&options, multiple);
                assert_eq!(params.len(), n + 1, "segment count");
                let step = TAU / n as f64;
                let start = curve.point(0.0) - centre;
                for (k, &u) in params.iter().enumerate() {
                    let p = curve.point(u) - centre;
                    assert!((p.length() - radius).abs() < 1e-9 * radius);
                    let angle = start.angle_between(p);
                    let expected = (k as f64 * step).min(TAU - k as f64 * step);
                    assert!(
                        (angle - expected).abs() < 1e-9,
                        "vertex {k}: {angle} vs {expected}"
                    );
                    // The general sampler's parameter for the same arc length.
                    if k > 0 && k < n {
                        let target = profile.length * k as f64 / n as f64;
                        let piece = profile
                            .pieces
                            .iter()
                            .find(|p| p.offset + p.length >= target)
                            .unwrap();
                        let general = piece.invert(target - piece.offset);
                        assert!((general - u).abs() < 1e-9, "vertex {k}: {general} vs {u}");
                    }
                }
            }
        }
        // Not a circle: an ellipse-like quarter net is refused.
        let squashed = course
            .transformed(&glam::DAffine3::from_scale(DVec3::new(1.0, 0.5, 1.0)))
            .unwrap();
        let edge = squashed.boundary(crate::nurbs::Side::VMax);
        assert!(super::super::circles::Circle::of(&edge).is_none());
    }

    #[test]
    fn series_lengths_match_the_adaptive_arc_length() {
        let c = circular_arc(DVec3::ZERO, DVec3::X, DVec3::Y, 1000.0, 0.0, TAU).unwrap();
        let profile = Profile::of(&c).unwrap();
        assert!((profile.length - TAU * 1000.0).abs() < 1e-11 * profile.length);
        for piece in &profile.pieces {
            let (s, _) = piece.length_at(1.0);
            assert!((s - piece.length).abs() < 1e-12 * piece.length);
        }
    }
}
