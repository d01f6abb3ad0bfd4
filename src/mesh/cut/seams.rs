//! Openings across the seam between two host patches: a nozzle on a torispherical
//! head whose opening crosses the knuckle–crown seam, say.
//!
//! `opening::cut_opening` computes such a loop on the host patches joined into one
//! surface ([`NurbsSurface::joined_v`]). Here the loop gets a sample exactly on
//! every seam it crosses ([`insert_seam_samples`]) and is split there
//! ([`split_at_seams`]): each host patch gets the pieces of the loop inside it as
//! [`Notch`]es, paths from the seam side into the patch and back, in the patch's own
//! (u, v). The layout (`layout::host_region`) replaces the side samples between a
//! notch's ends with the notch; both patches at a seam cut the same interval out of
//! the same side samples and share the crossing points, and the neck's bottom (the
//! whole loop) passes through them too, so the seam stays watertight.

use std::sync::Arc;

use glam::DVec2;

use super::error::CutError;
use crate::mesh::surface::closed_in_u;
use crate::nurbs::intersect::{
    HostIsoline, IntersectionLoop, LoopSample, intersect_generator, loop_crossing,
};
use crate::nurbs::{NurbsSurface, Side};

/// Bisection steps placing a seam sample.
const SEAM_STEPS: usize = 80;

/// A sample this close to a seam (relative to the joined v-domain) is moved onto it
/// instead of adding another next to it.
const SNAP: f64 = 1e-12;

/// A piece of an opening's loop inside one host patch that enters and leaves through
/// the same v-side (the seam with a neighbour).
#[derive(Clone, Debug, PartialEq)]
pub struct Notch {
    /// The side it bites into: [`Side::VMin`] or [`Side::VMax`].
    pub side: Side,
    /// The loop inside the patch, in the patch's (u, v), from the crossing with the
    /// smaller u to the one with the larger (u unwrapped continuously); both ends lie
    /// exactly on the side's v.
    pub path: Vec<DVec2>,
}

/// How an opening trims one of its host patches.
#[derive(Clone, Debug, PartialEq)]
pub enum HostTrim {
    /// The whole loop (the pad's, if the nozzle has one) lies in the patch: a hole,
    /// or the patch's top when it goes round the pole.
    Hole,
    /// The loop crosses the patch's seams: its pieces inside the patch.
    Notches(Arc<[Notch]>),
}

/// One host patch of a run, placed on the joined surface.
#[derive(Clone, Copy, Debug)]
pub(super) struct Placed {
    /// The patch's own v-domain.
    pub v: (f64, f64),
    /// Added to the patch's v to give the joined surface's v.
    pub shift: f64,
}

impl Placed {
    fn joined(&self) -> (f64, f64) {
        (self.v.0 + self.shift, self.v.1 + self.shift)
    }
}

/// Inserts a sample of `curve` exactly at each seam's v (the v where one placed
/// patch ends and the next begins) between every two samples on either side of it.
/// `curve` was computed between `neck` and the joined `host`; `names` name the
/// joined patches in errors.
pub(super) fn insert_seam_samples(
    neck: &NurbsSurface,
    host: &NurbsSurface,
    curve: &mut IntersectionLoop,
    seams: &[f64],
    names: &[&'static str],
) -> Result<(), CutError> {
    let ((hu0, hu1), (hv0, hv1)) = host.domain();
    let (period, closed) = (hu1 - hu0, closed_in_u(host));
    let neck_period = neck.domain().0.1 - neck.domain().0.0;
    let snap = SNAP * (hv1 - hv0);
    for p in &mut curve.host_uv {
        if let Some(&c) = seams.iter().find(|&&c| (p.y - c).abs() <= snap) {
            p.y = c;
        }
    }
    let mut i = 0;
    while i < curve.host_uv.len() {
        let n = curve.host_uv.len();
        let j = (i + 1) % n;
        let (a, b) = (curve.host_uv[i], curve.host_uv[j]);
        let (na, nb) = (
            curve.neck_uv[i].x,
            curve.neck_uv[j].x + if j == 0 { neck_period } else { 0.0 },
        );
        let crossed = seams
            .iter()
            .copied()
            .filter(|&c| (a.y - c) * (b.y - c) < 0.0)
            .min_by(|x, y| (x - a.y).abs().total_cmp(&(y - a.y).abs()));
        let Some(c) = crossed else {
            i += 1;
            continue;
        };
        let from = LoopSample {
            neck_uv: curve.neck_uv[i],
            host_uv: a,
        };
        let to = LoopSample {
            neck_uv: DVec2::new(nb, curve.neck_uv[j].y),
            host_uv: b,
        };
        // One Newton solve on the seam; the bisection over generators below only
        // where it does not converge.
        if let Ok(x) = loop_crossing(neck, host, HostIsoline::V(c), from, to) {
            let mut hu = x.host_uv.x;
            if closed {
                let expected = a.x + (b.x - a.x) * (x.neck_uv.x - na) / (nb - na);
                hu += period * ((expected - hu) / period).round();
            }
            curve.points.insert(i + 1, x.point);
            curve.neck_uv.insert(i + 1, x.neck_uv);
            curve.host_uv.insert(i + 1, DVec2::new(hu, c));
            i += 1;
            continue;
        }
        let (mut x0, mut x1) = (na, nb);
        let mut hit = None;
        for _ in 0..SEAM_STEPS {
            let mid = 0.5 * (x0 + x1);
            let h = intersect_generator(neck, host, mid).map_err(|e| CutError::SeamCrossing {
                patches: names.to_vec(),
                v: c,
                source: Some(e),
            })?;
            if (h.host_uv.y < c) == (a.y < c) {
                x0 = mid;
            } else {
                x1 = mid;
            }
            let done = (h.host_uv.y - c).abs() <= 1e-13 * (hv1 - hv0);
            hit = Some((mid, h));
            if done {
                break;
            }
        }
        let Some((nu, h)) = hit else {
            return Err(CutError::SeamCrossing {
                patches: names.to_vec(),
                v: c,
                source: None,
            });
        };
        let mut hu = h.host_uv.x;
        if closed {
            let expected = a.x + (b.x - a.x) * (nu - na) / (nb - na);
            hu += period * ((expected - hu) / period).round();
        }
        curve.points.insert(i + 1, h.point);
        curve.neck_uv.insert(i + 1, DVec2::new(nu, h.neck_v));
        curve.host_uv.insert(i + 1, DVec2::new(hu, c));
        i += 1;
    }
    Ok(())
}

/// Splits `curve` (on the joined surface, with its seam samples) into each placed
/// patch's notches: one entry per patch, in order (empty where the loop does not
/// enter the patch). `names` name the patches in errors.
pub(super) fn split_at_seams(
    curve: &IntersectionLoop,
    placed: &[Placed],
    names: &[&'static str],
) -> Result<Vec<Vec<Notch>>, CutError> {
    // Seam k lies between patch k and patch k + 1.
    let seams: Vec<f64> = placed[..placed.len() - 1]
        .iter()
        .map(|p| p.joined().1)
        .collect();
    let uv = &curve.host_uv;
    let n = uv.len();
    let seam_of = |i: usize| seams.iter().position(|&c| uv[i].y == c);
    let on_seams: Vec<usize> = (0..n).filter(|&i| seam_of(i).is_some()).collect();
    if on_seams.len() < 2 {
        return Err(CutError::NotAcrossSeam {
            patches: names.to_vec(),
        });
    }
    let patch_at = |v: f64| {
        placed.iter().position(|p| {
            let (lo, hi) = p.joined();
            v > lo && v < hi
        })
    };
    let mut out: Vec<Vec<Notch>> = vec![Vec::new(); placed.len()];
    for (k, &start) in on_seams.iter().enumerate() {
        let end = on_seams[(k + 1) % on_seams.len()];
        let steps = (end + n - start) % n;
        let steps = if steps == 0 { n } else { steps };
        let piece: Vec<DVec2> = (0..=steps).map(|s| uv[(start + s) % n]).collect();
        let (sa, sb) = (
            seam_of(start).unwrap_or_default(),
            seam_of(end).unwrap_or_default(),
        );
        let patch = match piece.get(1..piece.len() - 1).and_then(|m| m.first()) {
            Some(p) => patch_at(p.y),
            None if sa != sb => Some(sa.max(sb)),
            None => None,
        };
        let Some(patch) = patch else {
            return Err(CutError::TouchesSeam {
                below: names[sa],
                above: names[sa + 1],
            });
        };
        if sa != sb {
            return Err(CutError::CrossesWholePatch {
                patch: names[patch],
                below: names[sa.min(sb)],
                above: names[sa.max(sb) + 1],
            });
        }
        // Seam `sa` is this patch's v-end side if the patch lies below it.
        let (side, edge) = if sa == patch {
            (Side::VMax, placed[patch].v.1)
        } else {
            (Side::VMin, placed[patch].v.0)
        };
        let shift = placed[patch].shift;
        let mut path: Vec<DVec2> = piece.iter().map(|p| DVec2::new(p.x, p.y - shift)).collect();
        if let Some(first) = path.first_mut() {
            first.y = edge;
        }
        if let Some(last) = path.last_mut() {
            last.y = edge;
        }
        if path.first().map(|p| p.x) > path.last().map(|p| p.x) {
            path.reverse();
        }
        out[patch].push(Notch { side, path });
    }
    Ok(out)
}
