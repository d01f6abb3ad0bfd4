//! Openings across the seam of a closed host patch: the loop gets exact samples
//! on the seam, so that the host face can be bounded by the loop's two arcs and
//! the pieces of its seam.
//!
//! A nozzle facing the angle where a course's (or head's) parameter closes cuts
//! a hole whose (u, v) loop leaves the patch's domain on one side. The mesher
//! moves its seam elsewhere; a face in an exchange file keeps its surface's
//! parametrization, so the loop is cut where it crosses u = u0 (mod the period):
//! [`loop_crossing`] solves each crossing on both surfaces (Newton, from the
//! chord between the two samples round it), and the crossings are inserted as
//! samples. Each arc between two crossings then lies within the domain, and the
//! face's outer loop runs up the seam, round the arc, and on.

use glam::DVec2;

use crate::nurbs::NurbsSurface;
use crate::nurbs::intersect::{HostIsoline, IntersectionLoop, LoopSample, loop_crossing};

/// Relative distance from the seam within which a sample counts as on it.
const ON_SEAM: f64 = 1e-12;

/// `curve` with a sample on every crossing of `host`'s u-seam, and the indices
/// of the samples on the seam, ascending. `neck` is the neck surface in the
/// host's frame. A loop that does not cross the seam comes back unchanged,
/// with no index.
///
/// # Errors
///
/// The kernel's message where a crossing does not converge.
pub fn with_seam_samples(
    curve: &IntersectionLoop,
    neck: &NurbsSurface,
    host: &NurbsSurface,
) -> Result<(IntersectionLoop, Vec<usize>), String> {
    let ((u0, u1), _) = host.domain();
    let period = u1 - u0;
    let turns = |u: f64| (u - u0) / period;
    let on_seam = |u: f64| (turns(u) - turns(u).round()).abs() < ON_SEAM;
    let n = curve.points.len();
    let mut out = IntersectionLoop::default();
    let mut seam = Vec::new();
    for k in 0..n {
        let here = curve.host_uv[k];
        if on_seam(here.x) {
            seam.push(out.points.len());
        }
        out.points.push(curve.points[k]);
        out.neck_uv.push(curve.neck_uv[k]);
        out.host_uv.push(here);
        let next = (k + 1) % n;
        // The host (u, v) are continuous round the loop, the closing chord too
        // (the loop does not go round the host); the neck's u goes one turn on.
        let there = curve.host_uv[next];
        let mut neck_there = curve.neck_uv[next];
        if next == 0 {
            let (nu0, nu1) = neck.domain().0;
            neck_there.x += nu1 - nu0;
        }
        let (a, b) = (turns(here.x), turns(there.x));
        if on_seam(here.x) || on_seam(there.x) || a.floor() == b.floor() {
            continue;
        }
        let line = u0 + a.floor().max(b.floor()) * period;
        let crossing = loop_crossing(
            neck,
            host,
            HostIsoline::U(line),
            LoopSample {
                neck_uv: curve.neck_uv[k],
                host_uv: here,
            },
            LoopSample {
                neck_uv: neck_there,
                host_uv: there,
            },
        )
        .map_err(|e| e.to_string())?;
        seam.push(out.points.len());
        out.points.push(crossing.point);
        out.neck_uv.push(crossing.neck_uv);
        out.host_uv.push(DVec2::new(line, crossing.host_uv.y));
    }
    if seam.len() < 2 {
        return Ok((curve.clone(), Vec::new()));
    }
    Ok((out, seam))
}
