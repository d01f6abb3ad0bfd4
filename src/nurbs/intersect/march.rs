//! The closed intersection curve of a neck-like surface with its host, marched
//! around the neck angle and sampled to a chordal tolerance.
//!
//! The first point comes from the coarse search of one generator; every later one
//! is continued from its neighbour with the curve's tangent as predictor, halving
//! the step where Newton's method fails. A first pass walks once around the neck in
//! a few equal steps and checks that the curve closes. Then an interval is split
//! while the true curve point at its midpoint parameter lies farther than the
//! tolerance from the chord, or from the image of the straight segment between
//! the two samples' parameters on either surface (so the loop also trims both
//! surfaces accurately in their parameter planes), or while the tangent turns by
//! more than [`MAX_TURNING_ANGLE`] across it. It is split into equal parts, as many
//! as the deviation predicts (it falls with the square of the step), and each part
//! is checked again. The turning limit keeps strongly curved loops (a large nozzle
//! on a small shell, whose opening is a saddle) from being judged by a midpoint
//! that happens to lie near its chord.

use glam::{DVec2, DVec3};

use super::generator::Solution;
use super::pair::Pair;
use crate::nurbs::{NurbsError, NurbsSurface};

/// Largest angle, radians (20°), between the curve's tangents at the two ends of
/// one chord of an [`IntersectionLoop`].
pub const MAX_TURNING_ANGLE: f64 = 20.0 * std::f64::consts::PI / 180.0;

/// Fewest equal steps of the first pass around the neck.
const MIN_FIRST_STEPS: usize = 16;

/// Steps of the first pass per Bézier span of the neck in u.
const STEPS_PER_SPAN: usize = 4;

/// Times a continuation step is halved before falling back to a coarse search.
const MAX_STEP_HALVINGS: usize = 12;

/// Deepest subdivision of one first-pass interval.
const MAX_DEPTH: usize = 40;

/// Most parts one interval is split into at once.
const MAX_SPLIT: usize = 4096;

/// Margin on the predicted number of parts of a split interval, so that the parts
/// rarely need splitting again.
const SPLIT_MARGIN: f64 = 1.1;

/// Most samples of one loop.
const MAX_SAMPLES: usize = 1 << 20;

/// Largest gap, relative to the size of the two surfaces, between the first point
/// and the point reached after one turn.
const CLOSURE: f64 = 1e-9;

/// The closed curve where a nozzle neck meets its host surface, sampled to a
/// chordal tolerance.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct IntersectionLoop {
    /// 3D points, in the frame both surfaces are given in; closed (the last joins
    /// the first, which is not repeated).
    pub points: Vec<DVec3>,
    /// (u, v) of each point on the neck surface; u increasing continuously
    /// (unwrapped) over one full turn, from the start of the neck's u-domain.
    pub neck_uv: Vec<DVec2>,
    /// (u, v) of each point on the host surface; unwrapped continuously (it may
    /// leave the host's u-domain by up to one period when the host is closed in u
    /// and the loop crosses its seam or winds around its axis). Where the loop passes
    /// exactly through a pole of the host, u jumps there.
    pub host_uv: Vec<DVec2>,
}

impl IntersectionLoop {
    /// How many times the loop winds around the u direction of `host` (the surface
    /// it was computed on): 0 for an opening beside the host's axis, ±1 for one
    /// that encircles a pole of the host (a nozzle centred on a head), whose host u
    /// then runs over a whole period and which, in the host's parameter plane,
    /// bounds the opening together with the pole's edge.
    pub fn host_turns(&self, host: &NurbsSurface) -> i32 {
        let (u0, u1) = host.domain().0;
        let period = u1 - u0;
        let (Some(first), Some(last)) = (self.host_uv.first(), self.host_uv.last()) else {
            return 0;
        };
        // The closing chord, last → first, moves by less than half a period.
        let closing = (first.x - last.x) - ((first.x - last.x) / period).round() * period;
        ((last.x + closing - first.x) / period).round() as i32
    }
}

/// The closed curve where the straight v-generators of `neck` cross `host`, both
/// surfaces in one frame (transform the neck into the host's frame with
/// [`NurbsSurface::transformed`]), sampled so that the true curve at the middle
/// parameter of every chord lies within `tolerance` mm of the chord and of the
/// chord's images in both parameter planes (chords longer than `tolerance`), and
/// the tangent turns by at most [`MAX_TURNING_ANGLE`] across a chord.
///
/// `neck` must close in u (a full turn, as every revolved patch does) and have
/// straight v-isolines, each meeting the host once within the neck's v-domain: a
/// nozzle neck, or the coaxial cylinder of a reinforcing pad's outside diameter for
/// the pad's outer curve.
///
/// # Errors
///
/// [`NurbsError::InvalidGeometry`] for a tolerance that is not finite and > 0 or a
/// neck that does not close in u; [`NurbsError::GeneratorMissesHost`] where a
/// generator passes beside the host patch (the nozzle does not touch its host, or
/// its opening runs off the patch); [`NurbsError::IntersectionOutsideNeck`] where a
/// generator meets the host only beyond the neck's ends;
/// [`NurbsError::IntersectionNotConverged`], [`NurbsError::IntersectionNotClosed`]
/// and [`NurbsError::IntersectionTooManySamples`] where the curve cannot be
/// followed.
pub fn neck_host_intersection(
    neck: &NurbsSurface,
    host: &NurbsSurface,
    tolerance: f64,
) -> Result<IntersectionLoop, NurbsError> {
    if !(tolerance.is_finite() && tolerance > 0.0) {
        return Err(NurbsError::InvalidGeometry {
            what: "intersection tolerance",
            value: tolerance,
            rule: "must be finite and > 0",
        });
    }
    let pair = Pair::new(neck, host);
    pair.require_closed_neck()?;
    let (u0, u1) = (pair.neck_u.start, pair.neck_u.end);
    let steps = MIN_FIRST_STEPS.max(STEPS_PER_SPAN * neck.u_knots().spans().len());

    let found = pair.search(u0)?;
    let [a, b] = pair.host_axes;
    let first = Solution {
        host: DVec2::new(a.wrap(found.host.x), b.wrap(found.host.y)),
        ..found
    };
    let mut coarse = Vec::with_capacity(steps + 1);
    coarse.push(first);
    for k in 1..=steps {
        let u = if k == steps {
            u1
        } else {
            u0 + (u1 - u0) * k as f64 / steps as f64
        };
        let next = advance(&pair, &coarse[k - 1], u, 0)?;
        coarse.push(next);
    }
    let gap = coarse
        .last()
        .map_or(0.0, |last| (last.point - first.point).length());
    if gap > CLOSURE * pair.size {
        return Err(NurbsError::IntersectionNotClosed { gap });
    }

    let mut sampler = Sampler {
        pair: &pair,
        tolerance,
        samples: Vec::new(),
    };
    for w in coarse.windows(2) {
        sampler.samples.push(w[0]);
        sampler.refine(&w[0], &w[1], 0)?;
    }
    let samples = sampler.samples;
    Ok(IntersectionLoop {
        points: samples.iter().map(|s| s.point).collect(),
        neck_uv: samples.iter().map(|s| DVec2::new(s.u, s.s)).collect(),
        host_uv: samples.iter().map(|s| s.host).collect(),
    })
}

/// The solution at `u` continued from `from`, halving the step where Newton fails
/// and searching afresh after [`MAX_STEP_HALVINGS`] halvings.
fn advance(pair: &Pair, from: &Solution, u: f64, depth: usize) -> Result<Solution, NurbsError> {
    if let Some(found) = pair.continue_from(from, u) {
        return Ok(found);
    }
    if depth < MAX_STEP_HALVINGS {
        let middle = advance(pair, from, 0.5 * (from.u + u), depth + 1)?;
        return advance(pair, &middle, u, depth + 1);
    }
    let found = pair.search(u)?;
    Ok(Solution {
        host: pair.unwrap_host_near(found.host, from.host),
        ..found
    })
}

/// The solution at `u` between the solutions `a` and `b` (`a.u < u < b.u`): Newton
/// from the cubic Hermite interpolant of both ends' parameters and rates (its error
/// falls with the fourth power of the step, the tangent predictor's with the
/// second), else continued from `a` as [`advance`] does.
fn advance_between(
    pair: &Pair,
    a: &Solution,
    b: &Solution,
    u: f64,
) -> Result<Solution, NurbsError> {
    let h = b.u - a.u;
    let t = (u - a.u) / h;
    let (p0, p1) = (
        DVec3::new(a.s, a.host.x, a.host.y),
        DVec3::new(b.s, b.host.x, b.host.y),
    );
    let (t2, t3) = (t * t, t * t * t);
    let seed = p0 * (2.0 * t3 - 3.0 * t2 + 1.0)
        + a.rates * (h * (t3 - 2.0 * t2 + t))
        + p1 * (3.0 * t2 - 2.0 * t3)
        + b.rates * (h * (t3 - t2));
    if let Some(found) = pair.converge_near(a, u, seed) {
        return Ok(found);
    }
    advance(pair, a, u, 0)
}

/// Distance from `p` to the segment from `a` to `b`.
fn segment_distance(p: DVec3, a: DVec3, b: DVec3) -> f64 {
    let d = b - a;
    let length2 = d.length_squared();
    let t = if length2 > 0.0 {
        ((p - a).dot(d) / length2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    (p - (a + d * t)).length()
}

/// Angle between two tangents, 0 where either vanishes.
fn turning(a: DVec3, b: DVec3) -> f64 {
    if a == DVec3::ZERO || b == DVec3::ZERO {
        0.0
    } else {
        a.angle_between(b)
    }
}

/// Adaptive subdivision of the first pass's intervals, collecting samples in order.
struct Sampler<'p, 'a> {
    pair: &'p Pair<'a>,
    tolerance: f64,
    samples: Vec<Solution>,
}

impl Sampler<'_, '_> {
    /// Pushes the samples strictly between `a` and `b` that the tolerance and the
    /// turning limit need, in order of u.
    fn refine(&mut self, a: &Solution, b: &Solution, depth: usize) -> Result<(), NurbsError> {
        let middle = advance_between(self.pair, a, b, 0.5 * (a.u + b.u))?;
        let chord = segment_distance(middle.point, a.point, b.point);
        // The chord in each parameter plane, mapped onto its surface: checked
        // while the 3D chord is longer than the tolerance (not across a pole, where
        // the host's u jumps).
        let neck_middle = self.pair.neck_at(middle.u, 0.5 * (a.s + b.s)).point;
        let host_middle = self.pair.host_at(0.5 * (a.host + b.host)).point;
        let in_planes = if (b.point - a.point).length() > self.tolerance {
            (neck_middle - middle.point)
                .length()
                .max((host_middle - middle.point).length())
        } else {
            0.0
        };
        let deviation = chord.max(in_planes);
        if deviation <= self.tolerance && turning(a.tangent, b.tangent) <= MAX_TURNING_ANGLE {
            return Ok(());
        }
        if self.samples.len() >= MAX_SAMPLES || depth >= MAX_DEPTH {
            return Err(NurbsError::IntersectionTooManySamples {
                tolerance: self.tolerance,
                limit: MAX_SAMPLES,
            });
        }
        // The chord error of a smooth curve falls with the square of the step: split
        // into as many equal parts as that predicts (at least two).
        let parts = (deviation / self.tolerance)
            .sqrt()
            .max(turning(a.tangent, b.tangent) / MAX_TURNING_ANGLE)
            * SPLIT_MARGIN;
        let parts = (parts.ceil() as usize).clamp(2, MAX_SPLIT);
        if parts == 2 {
            self.refine(a, &middle, depth + 1)?;
            self.samples.push(middle);
            return self.refine(&middle, b, depth + 1);
        }
        let mut left = *a;
        for k in 1..parts {
            let u = a.u + (b.u - a.u) * k as f64 / parts as f64;
            let next = advance_between(self.pair, &left, b, u)?;
            self.refine(&left, &next, depth + 1)?;
            self.samples.push(next);
            left = next;
        }
        self.refine(&left, b, depth + 1)
    }
}
