//! The two surfaces of a neck–host intersection, with their parameter domains.
//!
//! The neck is evaluated with its straight generators extended linearly beyond the
//! ends of its v-domain, so that Newton iterates may step past the neck's ends
//! without the clamping of [`NurbsSurface::point`] hiding the true line. The host is
//! evaluated wrapped across a closed direction (the u seam of a revolved patch) and
//! clamped on an open one, so iterates keep unwrapped parameters and stay
//! continuous across the seam.

use glam::{DVec2, DVec3};

use crate::nurbs::{FirstDerivatives, KnotVector, NurbsError, NurbsSurface};

/// Relative distance (of the surfaces' size) below which two control points coincide:
/// for detecting closed directions.
const COINCIDENT_CONTROL_POINTS: f64 = 1e-12;

/// Newton's residual |neck − host| counts as zero below this fraction of the size of
/// the two control nets (or of their largest coordinate, where that is larger).
pub(super) const CONVERGED: f64 = 1e-12;

/// One parameter direction: its domain and whether the geometry closes across it.
#[derive(Clone, Copy, Debug)]
pub(super) struct Range {
    /// Start of the domain.
    pub start: f64,
    /// End of the domain.
    pub end: f64,
    /// Whether the surface closes across this direction (the two ends coincide).
    pub closed: bool,
}

impl Range {
    fn of(knots: &KnotVector, closed: bool) -> Self {
        let (start, end) = knots.domain();
        Self { start, end, closed }
    }

    /// Width of the domain: the period of a closed direction.
    pub fn width(self) -> f64 {
        self.end - self.start
    }

    /// `t` brought into the domain for evaluation: wrapped when closed, else clamped.
    pub fn wrap(self, t: f64) -> f64 {
        let t = if self.closed {
            self.start + (t - self.start).rem_euclid(self.width())
        } else {
            t
        };
        t.clamp(self.start, self.end)
    }

    /// `t` kept as an iterate: unchanged (unwrapped) when closed, clamped when open.
    pub fn hold(self, t: f64) -> f64 {
        if self.closed {
            t
        } else {
            t.clamp(self.start, self.end)
        }
    }

    /// `t` shifted by whole periods to lie nearest `reference` (unchanged when open).
    pub fn unwrap_near(self, t: f64, reference: f64) -> f64 {
        if self.closed {
            t + ((reference - t) / self.width()).round() * self.width()
        } else {
            t
        }
    }
}

/// Point and first derivatives of the (linearly extended) neck.
#[derive(Clone, Copy, Debug)]
pub(super) struct NeckPoint {
    /// N(u, s).
    pub point: DVec3,
    /// ∂N/∂u.
    pub du: DVec3,
    /// ∂N/∂s.
    pub dv: DVec3,
}

/// A neck-like surface and a host surface in one frame, ready to intersect.
#[derive(Clone, Copy, Debug)]
pub(super) struct Pair<'a> {
    /// The surface with straight v-generators.
    pub neck: &'a NurbsSurface,
    /// The surface the generators cross.
    pub host: &'a NurbsSurface,
    /// Neck u (around the neck).
    pub neck_u: Range,
    /// Neck v (along the generators).
    pub neck_v: Range,
    /// Host u and v.
    pub host_axes: [Range; 2],
    /// Diagonal of the bounding box of both control nets, mm.
    pub size: f64,
    /// Residual below which a point counts as on both surfaces, mm: [`CONVERGED`]
    /// relative.
    pub eps: f64,
}

impl<'a> Pair<'a> {
    /// The pair, with closed directions detected from the control nets.
    pub fn new(neck: &'a NurbsSurface, host: &'a NurbsSurface) -> Self {
        let neck_points = neck.control_points();
        let host_points = host.control_points();
        let size = net_size(neck_points.iter().chain(&host_points));
        // Rounding grows with the coordinates, not only with the size.
        let reach = neck_points
            .iter()
            .chain(&host_points)
            .map(|p| p.abs().max_element())
            .fold(0.0, f64::max);
        let tol = COINCIDENT_CONTROL_POINTS * size;
        let neck_closed = closed_in_u(neck, &neck_points, tol);
        let host_u = closed_in_u(host, &host_points, tol);
        let transposed = host.transposed();
        let host_v = closed_in_u(&transposed, &transposed.control_points(), tol);
        Self {
            neck,
            host,
            neck_u: Range::of(neck.u_knots(), neck_closed),
            neck_v: Range::of(neck.v_knots(), false),
            host_axes: [
                Range::of(host.u_knots(), host_u),
                Range::of(host.v_knots(), host_v),
            ],
            size,
            eps: CONVERGED * size.max(reach),
        }
    }

    /// Errors unless the neck closes in u (its u0 and u1 edges coincide).
    pub fn require_closed_neck(&self) -> Result<(), NurbsError> {
        if self.neck_u.closed {
            return Ok(());
        }
        let (u0, u1) = (self.neck_u.start, self.neck_u.end);
        let (v0, v1) = (self.neck_v.start, self.neck_v.end);
        let gap = [v0, 0.5 * (v0 + v1), v1]
            .into_iter()
            .map(|v| (self.neck.point(u0, v) - self.neck.point(u1, v)).length())
            .fold(0.0, f64::max);
        Err(NurbsError::InvalidGeometry {
            what: "neck seam gap",
            value: gap,
            rule: "the neck must close in u (its u0 and u1 edges must coincide)",
        })
    }

    /// The neck at (u, s), its generator extended linearly beyond the v-domain.
    pub fn neck_at(&self, u: f64, s: f64) -> NeckPoint {
        let inside = s.clamp(self.neck_v.start, self.neck_v.end);
        let beyond = s - inside;
        if beyond == 0.0 {
            // On the neck: first derivatives suffice (half the evaluation).
            let d = self.neck.first_derivatives(self.neck_u.wrap(u), inside);
            return NeckPoint {
                point: d.point,
                du: d.du,
                dv: d.dv,
            };
        }
        let d = self.neck.derivatives(self.neck_u.wrap(u), inside);
        NeckPoint {
            point: d.point + d.dv * beyond,
            du: d.du + d.duv * beyond,
            dv: d.dv,
        }
    }

    /// The host at unwrapped parameters `x`.
    pub fn host_at(&self, x: DVec2) -> FirstDerivatives {
        let [a, b] = self.host_axes;
        self.host.first_derivatives(a.wrap(x.x), b.wrap(x.y))
    }

    /// `x` kept as a host iterate (open directions clamped).
    pub fn hold_host(&self, x: DVec2) -> DVec2 {
        DVec2::new(self.host_axes[0].hold(x.x), self.host_axes[1].hold(x.y))
    }

    /// `x` shifted by whole periods in the closed host directions to lie nearest
    /// `reference`.
    pub fn unwrap_host_near(&self, x: DVec2, reference: DVec2) -> DVec2 {
        DVec2::new(
            self.host_axes[0].unwrap_near(x.x, reference.x),
            self.host_axes[1].unwrap_near(x.y, reference.y),
        )
    }
}

/// True when the first and last rows of control points (along u) coincide, weights
/// included.
fn closed_in_u(surface: &NurbsSurface, points: &[DVec3], tol: f64) -> bool {
    let (nu, nv) = (surface.u_count(), surface.v_count());
    (0..nv).all(|j| {
        let (first, last) = (j, (nu - 1) * nv + j);
        let (w0, w1) = (
            surface.homogeneous_point_at(0, j).w,
            surface.homogeneous_point_at(nu - 1, j).w,
        );
        (points[first] - points[last]).length() <= tol
            && (w0 - w1).abs() <= COINCIDENT_CONTROL_POINTS * w0
    })
}

/// Diagonal of the bounding box of `points`.
fn net_size<'p>(points: impl Iterator<Item = &'p DVec3>) -> f64 {
    let (lo, hi) = points.fold(
        (DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY)),
        |(lo, hi), &p| (lo.min(p), hi.max(p)),
    );
    (hi - lo).length()
}
