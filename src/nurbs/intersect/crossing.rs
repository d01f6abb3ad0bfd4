//! Where a neck–host intersection loop crosses a host isoline: the extra samples
//! an opening needs exactly on the host's seam angle (a loop round a head's pole)
//! or on the seam between two host patches joined in v.
//!
//! With one host parameter held, the unknowns are the neck parameters (u, s) and
//! the other host parameter; N(u, s) = H(a, b) is again a square 3×3 system, with
//! the Jacobian `[N_u, N_s, −H_free]`. It is solved by the same damped Newton's
//! method as a generator (`generator`), seeded on the chord between the two loop
//! samples the crossing lies between, so one solve replaces a bisection over
//! generators (each a coarse search of its own).

use glam::{DMat3, DVec2, DVec3};

use super::generator::newton_step;
use super::pair::Pair;
use crate::nurbs::{NurbsError, NurbsSurface};

/// Newton iterations per crossing.
const MAX_ITERATIONS: usize = 50;

/// Step halvings before a step counts as not reducing the residual.
const MAX_HALVINGS: usize = 30;

/// A host isoline: one host parameter held at a value (unwrapped, as the loop's
/// host parameters are).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum HostIsoline {
    /// Host u held: a meridian of a revolved host (its seam angle).
    U(f64),
    /// Host v held: a parallel (the seam between patches joined in v).
    V(f64),
}

impl HostIsoline {
    /// The held value.
    fn value(self) -> f64 {
        match self {
            Self::U(a) | Self::V(a) => a,
        }
    }

    /// The held coordinate of host parameters `x`.
    fn held(self, x: DVec2) -> f64 {
        match self {
            Self::U(_) => x.x,
            Self::V(_) => x.y,
        }
    }

    /// Host parameters with the held one set and the free one `free`.
    fn host(self, free: f64) -> DVec2 {
        match self {
            Self::U(a) => DVec2::new(a, free),
            Self::V(b) => DVec2::new(free, b),
        }
    }

    /// The free coordinate of host parameters `x`.
    fn free(self, x: DVec2) -> f64 {
        match self {
            Self::U(_) => x.y,
            Self::V(_) => x.x,
        }
    }
}

/// A sample of an intersection loop: its parameters on both surfaces.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LoopSample {
    /// (u, v) on the neck, u unwrapped.
    pub neck_uv: DVec2,
    /// (u, v) on the host, unwrapped.
    pub host_uv: DVec2,
}

/// Where the loop crosses a host isoline.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Crossing {
    /// (u, v) on the neck, u between the two samples' (unwrapped).
    pub neck_uv: DVec2,
    /// (u, v) on the host: the held parameter exactly the isoline's value, the
    /// other unwrapped near the samples'.
    pub host_uv: DVec2,
    /// The point, on both surfaces to the intersection's accuracy.
    pub point: DVec3,
}

/// The point where the intersection of `neck` and `host` (both in one frame, as for
/// [`neck_host_intersection`](super::neck_host_intersection)) crosses `isoline`
/// between two consecutive samples `from` and `to` of its loop, whose held host
/// parameters lie on either side of the isoline's value.
///
/// # Errors
///
/// [`NurbsError::IntersectionNotConverged`] where Newton's method does not converge
/// to a crossing strictly between the two samples' neck angles (the caller may fall
/// back to a bisection over generators).
pub fn loop_crossing(
    neck: &NurbsSurface,
    host: &NurbsSurface,
    isoline: HostIsoline,
    from: LoopSample,
    to: LoopSample,
) -> Result<Crossing, NurbsError> {
    let pair = Pair::new(neck, host);
    let target = isoline.value();
    let (held_from, held_to) = (isoline.held(from.host_uv), isoline.held(to.host_uv));
    let f = if held_to != held_from {
        ((target - held_from) / (held_to - held_from)).clamp(0.0, 1.0)
    } else {
        0.5
    };
    let neck_uv = from.neck_uv.lerp(to.neck_uv, f);
    let free = isoline.free(from.host_uv.lerp(to.host_uv, f));
    // Unknowns x = (neck u, neck s, free host parameter).
    let residual = |x: DVec3| {
        let neck_point = pair.neck_at(x.x, x.y);
        let host_uv = pair.hold_host(isoline.host(x.z));
        let h = pair.host_at(host_uv);
        let host_free = match isoline {
            HostIsoline::U(_) => h.dv,
            HostIsoline::V(_) => h.du,
        };
        let jacobian = DMat3::from_cols(neck_point.du, neck_point.dv, -host_free);
        (
            neck_point.point - h.point,
            jacobian,
            neck_point.point,
            h.point,
        )
    };
    let mut x = DVec3::new(neck_uv.x, neck_uv.y, free);
    let (mut r, mut j, mut n, mut h) = residual(x);
    let mut polished = false;
    for _ in 0..MAX_ITERATIONS {
        let size = r.length();
        if size <= pair.eps {
            if polished {
                break;
            }
            polished = true;
        }
        let step = newton_step(j, r);
        let mut t = 1.0;
        let mut accepted = false;
        for _ in 0..if polished { 1 } else { MAX_HALVINGS } {
            let trial = x + step * t;
            let next = residual(trial);
            if next.0.length() < size {
                (x, r, j, n, h) = (trial, next.0, next.1, next.2, next.3);
                accepted = true;
                break;
            }
            t *= 0.5;
        }
        if !accepted {
            break;
        }
    }
    let (lo, hi) = (
        from.neck_uv.x.min(to.neck_uv.x),
        from.neck_uv.x.max(to.neck_uv.x),
    );
    let (v0, v1) = (pair.neck_v.start, pair.neck_v.end);
    let inside = x.x > lo && x.x < hi && x.y >= v0 && x.y <= v1;
    if r.length() > pair.eps || !inside || !x.is_finite() {
        return Err(NurbsError::IntersectionNotConverged {
            u: x.x,
            residual: r.length(),
        });
    }
    Ok(Crossing {
        neck_uv: DVec2::new(x.x, x.y),
        host_uv: isoline.host(x.z),
        point: 0.5 * (n + h),
    })
}
