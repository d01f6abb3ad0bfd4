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
//!
//! A reinforcing pad round such an opening puts its outer loop across the seam
//! instead: the crossings are solved on the pad's outside cylinder
//! ([`on_pad_cylinder`]), and the pad's own face, on a copy of the host
//! surface, is written on that surface with its seam moved half a turn
//! ([`seam_moved`]), its inserted samples' (u, v) found by projection
//! ([`uv_with_inserted`]).

use std::f64::consts::TAU;

use glam::{DAffine3, DVec2, DVec3};

use crate::nurbs::NurbsSurface;
use crate::nurbs::builders::{line, revolve};
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

/// A reinforcing pad's outer loop (host frame) with its neck (u, v) put on the
/// pad's outside cylinder: radius `radius` about the nozzle's axis, the nozzle
/// frame being `nozzle_in_host` in the host's frame, spanning the loop's height
/// along the axis. Returns the cylinder (host frame) and the loop, ready for
/// [`with_seam_samples`]. Each sample's neck u is the loop's own where it maps
/// onto the sample, the point's projection on the cylinder otherwise.
///
/// # Errors
///
/// The kernel's message where the cylinder cannot be built or a sample not
/// projected.
pub fn on_pad_cylinder(
    curve: &IntersectionLoop,
    radius: f64,
    nozzle_in_host: &DAffine3,
) -> Result<(NurbsSurface, IntersectionLoop), String> {
    let to_nozzle = nozzle_in_host.inverse();
    let local: Vec<DVec3> = curve
        .points
        .iter()
        .map(|p| to_nozzle.transform_point3(*p))
        .collect();
    let (lo, hi) = local
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), p| {
            (lo.min(p.z), hi.max(p.z))
        });
    let margin = (hi - lo).max(radius) * 0.5;
    let (z0, z1) = (lo - margin, hi + margin);
    let generator = line(DVec3::new(radius, 0.0, z0), DVec3::new(radius, 0.0, z1))
        .map_err(|e| e.to_string())?;
    let cylinder = revolve(&generator, DVec3::ZERO, DVec3::Z, TAU)
        .and_then(|c| c.transformed(nozzle_in_host))
        .map_err(|e| e.to_string())?;
    let size = radius.max(1.0);
    let mut out = curve.clone();
    for (k, p) in local.iter().enumerate() {
        let v = (p.z - z0) / (z1 - z0);
        let u = curve.neck_uv[k].x;
        let u = if cylinder.point(u, v).distance(curve.points[k]) <= 1e-9 * size {
            u
        } else {
            cylinder
                .closest_point(curve.points[k])
                .map_err(|e| e.to_string())?
                .u
        };
        out.neck_uv[k] = DVec2::new(u, v);
    }
    Ok((cylinder, out))
}

/// `surface` (closed in u over [u0, u1]) with its seam moved half a turn: the
/// same points over u in [m, u1 + (m − u0)], m the middle of the domain, equal
/// to `surface` at u in [m, u1] and to `surface` at u − (u1 − u0) beyond. A
/// face whose loops cross the seam is written on it with its (u, v) shifted by
/// whole periods, so that they run within the domain.
///
/// # Errors
///
/// The kernel's message where the surface cannot be split or joined.
pub fn seam_moved(surface: &NurbsSurface) -> Result<NurbsSurface, String> {
    let ((u0, u1), _) = surface.domain();
    let (lower, upper) = surface
        .split_u(0.5 * (u0 + u1))
        .map_err(|e| e.to_string())?;
    let (joined, _) = upper
        .transposed()
        .joined_v(&[&lower.transposed()])
        .map_err(|e| e.to_string())?;
    Ok(joined.transposed())
}

/// The (u, v) on `surface` (in the frame of `to_surface`'s target) of each
/// sample of `augmented`, a copy of `original` with samples inserted: the
/// original samples keep `uv` (theirs on `surface`), each inserted one is
/// projected and unwrapped by whole periods next to the sample before it.
///
/// # Errors
///
/// The kernel's message where a sample cannot be projected.
pub fn uv_with_inserted(
    original: &IntersectionLoop,
    uv: &[DVec2],
    augmented: &IntersectionLoop,
    surface: &NurbsSurface,
    to_surface: &DAffine3,
) -> Result<Vec<DVec2>, String> {
    let ((u0, u1), _) = surface.domain();
    let period = u1 - u0;
    let mut out: Vec<DVec2> = Vec::with_capacity(augmented.points.len());
    let mut j = 0;
    for p in &augmented.points {
        if j < original.points.len() && original.points[j] == *p {
            out.push(uv[j]);
            j += 1;
            continue;
        }
        let q = surface
            .closest_point(to_surface.transform_point3(*p))
            .map_err(|e| e.to_string())?;
        let mut u = q.u;
        if let Some(before) = out.last().or(uv.get(j)) {
            u += ((before.x - u) / period).round() * period;
        }
        out.push(DVec2::new(u, q.v));
    }
    Ok(out)
}
