//! What curve and surface inversion share: the tolerances, the parameter domain
//! (clamped or wrapped), sampling for seeds and the backtracking line search.

use glam::DVec3;

use crate::nurbs::{KnotVector, NurbsError};

/// Point coincidence (P&T ε₁), relative to the diagonal of the control net's bounding
/// box: a query point this close counts as on the curve or surface, and a Newton step
/// that moves the point less than this ends the iteration.
pub(super) const POINT_COINCIDENCE: f64 = 1e-13;

/// Zero cosine (P&T ε₂): the iteration ends when |cos| of the angle between the
/// offset S − P and every free tangent S_u, S_v is at most this.
pub(super) const ZERO_COSINE: f64 = 1e-12;

/// Relative distance (of the control net's size) below which two control points
/// coincide: for detecting closed directions and degenerate edges.
pub(super) const COINCIDENT_CONTROL_POINTS: f64 = 1e-12;

/// Newton iterations per seed.
pub(super) const MAX_ITERATIONS: usize = 64;

/// Step halvings tried before a Newton step is given up as not reducing the distance.
pub(super) const MAX_HALVINGS: usize = 40;

/// Local minima of the sampled distance that Newton is started from.
pub(super) const MAX_SEEDS: usize = 4;

/// Relative change of a squared distance that floating point cannot resolve: near the
/// minimum, where ½|S − P|² is flat, steps are told apart by their residual instead.
const ROUNDING: f64 = 16.0 * f64::EPSILON;

/// One parameter direction: its domain and whether the geometry closes across it.
#[derive(Clone, Copy)]
pub(super) struct Axis {
    start: f64,
    end: f64,
    closed: bool,
}

impl Axis {
    pub(super) fn new(knots: &KnotVector, closed: bool) -> Self {
        let (start, end) = knots.domain();
        Self { start, end, closed }
    }

    /// `t` brought into the domain: wrapped on a closed axis, clamped otherwise.
    pub(super) fn place(self, t: f64) -> f64 {
        let t = if self.closed {
            self.start + (t - self.start).rem_euclid(self.end - self.start)
        } else {
            t
        };
        t.clamp(self.start, self.end)
    }

    /// False when `t` is held at a bound: the descent direction −`gradient` leaves
    /// the domain there.
    pub(super) fn is_free(self, t: f64, gradient: f64) -> bool {
        self.closed || !((t <= self.start && gradient > 0.0) || (t >= self.end && gradient < 0.0))
    }

    /// A step limited to the width of the domain.
    pub(super) fn limit(self, step: f64) -> f64 {
        let width = self.end - self.start;
        step.clamp(-width, width)
    }
}

/// Sample parameters: `2 (degree + 1)` intervals per Bézier span, both ends included.
pub(super) fn sample_parameters(knots: &KnotVector) -> Vec<f64> {
    let per_span = 2 * (knots.degree() + 1);
    let mut out = Vec::new();
    for (a, b) in knots.spans() {
        out.extend((0..per_span).map(|k| a + (b - a) * k as f64 / per_span as f64));
    }
    out.push(knots.domain().1);
    out
}

/// Diagonal of the bounding box of `points`.
pub(super) fn net_size(points: &[DVec3]) -> f64 {
    let (lo, hi) = points.iter().fold(
        (DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY)),
        |(lo, hi), &p| (lo.min(p), hi.max(p)),
    );
    (hi - lo).length()
}

/// True when all points lie within `tol` of the first.
pub(super) fn all_coincide(mut points: impl Iterator<Item = DVec3>, tol: f64) -> bool {
    match points.next() {
        Some(first) => points.all(|p| (p - first).length() <= tol),
        None => true,
    }
}

/// The query point, or the error for a non-finite one.
pub(super) fn check_query(p: DVec3) -> Result<DVec3, NurbsError> {
    if p.is_finite() {
        Ok(p)
    } else {
        Err(NurbsError::QueryPointNotFinite {
            x: p.x,
            y: p.y,
            z: p.z,
        })
    }
}

/// A trial point of a line search: squared distance, stationarity residual (the
/// largest |(S − P) · S_k| / |S_k| over the free directions k) and the state.
pub(super) struct Trial<T> {
    pub(super) value: f64,
    pub(super) residual: f64,
    pub(super) state: T,
}

/// Backtracking on the projected path: the first `t` in 1, ½, ¼, … whose trial
/// reduces the squared distance, or (where the change is below rounding) keeps it and
/// reduces the residual; with whether it was `t = 1`. So the distance never increases
/// beyond rounding.
pub(super) fn backtrack<T>(
    value: f64,
    residual: f64,
    mut trial: impl FnMut(f64) -> Trial<T>,
) -> Option<(Trial<T>, bool)> {
    let mut t = 1.0;
    for _ in 0..MAX_HALVINGS {
        let next = trial(t);
        if next.value < value
            || (next.value <= value * (1.0 + ROUNDING) && next.residual < residual)
        {
            return Some((next, t == 1.0));
        }
        t *= 0.5;
    }
    None
}
