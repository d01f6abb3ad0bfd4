//! Openings across the seam between two host patches (a nozzle on a
//! torispherical head whose opening crosses the knuckle–crown seam).
//!
//! The cut gives such a loop on the host patches joined in v, with a sample
//! exactly on every seam it crosses, and each host patch's pieces of it as
//! [`Notch`]es: paths from the seam side into the patch and back, in the
//! patch's own (u, v), made of the loop's samples. Here the loop is split into
//! edges at its seam samples, and each notch becomes the uses of its edges in
//! its face's outer loop, in the direction that loop runs along the side it
//! bites into; `loops::Builder::patch_face` cuts the side's exact isocurve at
//! the notches' ends, so both faces at the seam share the side's pieces
//! between notches as they share any side, and the neck's bottom runs through
//! the same crossing vertices.
//!
//! Where such an opening has a reinforcing pad, the pad's loop notches the
//! host patches and the pad is a face on each; where the neck's loop crosses
//! the seam too, [`neck_across`] solves its crossings of the seam exactly and
//! splits it there, so that it notches each piece of the pad as the pad's
//! loop notches each host face.

use std::sync::Arc;

use glam::{DAffine3, DVec2};

use super::brep::OrientedEdge;
use super::loops::{Builder, LoopEdges, NotchUse};
use crate::mesh::{Cut, HostTrim, Notch, closed_in_u};
use crate::nurbs::intersect::{HostIsoline, IntersectionLoop, LoopSample, loop_crossing};
use crate::nurbs::{NurbsSurface, Side};
use crate::parts::Patch;

/// Distance from the seam, relative to the joined v-range, within which a
/// neck loop sample is taken as on it.
const ON_SEAM: f64 = 1e-12;

/// A loop's edges and each host patch's notch uses, by patch index.
pub(super) type Notched = (LoopEdges, Vec<(usize, NotchUse)>);

/// A notch with the indices of the loop samples its ends are.
struct Placed<'a> {
    patch: usize,
    notch: &'a Notch,
    ends: (usize, usize),
}

/// The edges of an opening loop that crosses the seams between the host
/// patches `hosts` (host part frame, mapped into the vessel's by `host_frame`),
/// split at its seam samples, and each host patch's notch uses: the neck's
/// loop, or the reinforcing pad's where the nozzle has one (its face, on the
/// patches joined, runs from that loop to the neck's). `neck_knots`
/// as for [`Builder::loop_edges`].
///
/// # Errors
///
/// `(host patch, rule)` where the cut trims a patch otherwise than by notches,
/// a notch end is not a sample of the loop, or a notch crosses its patch's
/// seam in u.
pub(super) fn notched_loop(
    builder: &mut Builder,
    cut: &Cut,
    hosts: &[Patch],
    host_frame: &DAffine3,
    neck_knots: &[f64],
) -> Result<Notched, (usize, String)> {
    // The loop the hosts are notched by: the pad's, if the nozzle has one.
    let curve = cut.pad.as_ref().unwrap_or(&cut.neck);
    let n = curve.points.len();
    let mut placed = Vec::new();
    for (k, trim) in &cut.hosts {
        let HostTrim::Notches(notches) = trim else {
            return Err((
                *k,
                "an opening both across a seam and whole in one host patch".into(),
            ));
        };
        let surface = &hosts[*k].surface;
        let ((u0, u1), _) = surface.domain();
        for notch in notches.iter() {
            let (Some(&first), Some(&last)) = (notch.path.first(), notch.path.last()) else {
                return Err((*k, "a notch with no sample".into()));
            };
            if notch
                .path
                .iter()
                .any(|p| p.x < u0 - 1e-12 || p.x > u1 + 1e-12)
            {
                return Err((
                    *k,
                    format!(
                        "a notch spans u from {} to {}, across the patch's seam in u \
                         ([{u0}, {u1}]): not written yet",
                        first.x, last.x
                    ),
                ));
            }
            // The loop's sample at a notch's end: the same u, the same point.
            let sample = |end: DVec2| -> Result<usize, (usize, String)> {
                let at = surface.point(end.x, end.y);
                (0..n)
                    .filter(|&i| curve.host_uv[i].x == end.x)
                    .min_by(|&a, &b| {
                        curve.points[a]
                            .distance(at)
                            .total_cmp(&curve.points[b].distance(at))
                    })
                    .ok_or_else(|| {
                        (
                            *k,
                            format!("a notch's end at u = {} is no loop sample", end.x),
                        )
                    })
            };
            placed.push(Placed {
                patch: *k,
                notch,
                ends: (sample(first)?, sample(last)?),
            });
        }
    }
    let mut splits: Vec<usize> = placed.iter().flat_map(|p| [p.ends.0, p.ends.1]).collect();
    splits.sort_unstable();
    splits.dedup();
    let edges = builder
        .loop_edges(curve, host_frame, &splits, neck_knots)
        .map_err(|rule| (placed.first().map_or(0, |p| p.patch), rule))?;
    let mut uses = Vec::with_capacity(placed.len());
    for p in placed {
        let path = &p.notch.path;
        let steps = path.len() - 1;
        // The path in the loop's direction, from the loop sample `start`.
        let along_loop = (p.ends.0 + steps) % n == p.ends.1;
        let (start, in_loop_order): (usize, Vec<DVec2>) = if along_loop {
            (p.ends.0, path.clone())
        } else if (p.ends.1 + steps) % n == p.ends.0 {
            (p.ends.1, path.iter().rev().copied().collect())
        } else {
            return Err((
                p.patch,
                "a notch's samples are not the loop's between its ends".into(),
            ));
        };
        // The loop's edges from `start` for `steps` samples.
        let mut notch_uses = Vec::new();
        let mut offset = 0;
        while offset < steps {
            let at = (start + offset) % n;
            let Some(&(edge, from, to)) = edges.parts.iter().find(|part| part.1 == at) else {
                return Err((p.patch, "a notch does not start at a loop edge".into()));
            };
            let len = to - from;
            if offset + len > steps {
                return Err((p.patch, "a loop edge runs past its notch's end".into()));
            }
            notch_uses.push(OrientedEdge {
                edge,
                forward: true,
                pcurve: in_loop_order[offset..=offset + len].to_vec(),
            });
            offset += len;
        }
        // The path runs from the smaller u to the larger: the outer loop's way
        // on the v-min side, against it on the v-max side.
        let increasing = p.notch.side == Side::VMin;
        let notch_uses = if along_loop == increasing {
            notch_uses
        } else {
            Builder::against(notch_uses)
        };
        uses.push((
            p.patch,
            NotchUse {
                side: p.notch.side,
                u: (path[0].x, path[steps].x),
                uses: notch_uses,
            },
        ));
    }
    Ok((edges, uses))
}

/// The neck's loop of a padded opening across the seam between the host
/// patches `a` and `a + 1` of `hosts` (the pad's notches are in `cut.hosts`)
/// when the neck's loop crosses the seam too: the loop (`cut.neck`, host
/// (u, v) on the two patches joined in v) with a sample solved exactly on
/// the seam at each crossing ([`loop_crossing`] between the neck `neck`, in
/// the host part's frame, and the joined surface), its edges split there,
/// and each patch's notch uses, as [`notched_loop`] gives them for a loop
/// without a pad. Returns the loop with its seam samples too: the neck's
/// bottom runs through them.
///
/// # Errors
///
/// `(host patch, rule)` where the patches cannot be joined, a crossing does
/// not converge, or the loop touches the seam without crossing it.
pub(super) fn neck_across(
    builder: &mut Builder,
    cut: &Cut,
    neck: &NurbsSurface,
    hosts: &[Patch],
    host_frame: &DAffine3,
    neck_knots: &[f64],
) -> Result<(IntersectionLoop, Notched), (usize, String)> {
    let (a, b) = match cut.hosts.as_slice() {
        [(a, _), (b, _)] if *b == *a + 1 => (*a, *b),
        _ => {
            return Err((
                cut.hosts.first().map_or(0, |h| h.0),
                "a pad across more than one seam between host patches".into(),
            ));
        }
    };
    let (below, above) = (&hosts[a].surface, &hosts[b].surface);
    let (joined, shifts) = below
        .joined_v(&[above])
        .map_err(|e| (a, format!("the host patches do not join: {e}")))?;
    let seam = below.domain().1.1 + shifts[0];
    let (jv0, jv1) = joined.domain().1;
    let snap = ON_SEAM * (jv1 - jv0);
    let (nu0, nu1) = neck.domain().0;
    let neck_period = nu1 - nu0;
    let ((u0, u1), _) = joined.domain();
    let (period, closed) = (u1 - u0, closed_in_u(&joined));

    let source = &cut.neck;
    let n = source.points.len();
    let mut curve = IntersectionLoop::default();
    let mut on_seam = Vec::new();
    for k in 0..n {
        let mut here = source.host_uv[k];
        if (here.y - seam).abs() <= snap {
            here.y = seam;
            on_seam.push(curve.points.len());
        }
        curve.points.push(source.points[k]);
        curve.neck_uv.push(source.neck_uv[k]);
        curve.host_uv.push(here);
        let next = (k + 1) % n;
        let there = source.host_uv[next];
        if (here.y - seam) * (there.y - seam) >= 0.0 || (there.y - seam).abs() <= snap {
            continue;
        }
        let mut neck_there = source.neck_uv[next];
        if next == 0 {
            neck_there.x += neck_period;
        }
        let crossing = loop_crossing(
            neck,
            &joined,
            HostIsoline::V(seam),
            LoopSample {
                neck_uv: source.neck_uv[k],
                host_uv: here,
            },
            LoopSample {
                neck_uv: neck_there,
                host_uv: there,
            },
        )
        .map_err(|e| (a, format!("the neck's loop's crossing of the seam: {e}")))?;
        // The host u continuous with the samples round it on a closed host.
        let mut u = crossing.host_uv.x;
        if closed {
            let f =
                (crossing.neck_uv.x - source.neck_uv[k].x) / (neck_there.x - source.neck_uv[k].x);
            let expected = here.x + (there.x - here.x) * f;
            u += period * ((expected - u) / period).round();
        }
        on_seam.push(curve.points.len());
        curve.points.push(crossing.point);
        curve.neck_uv.push(crossing.neck_uv);
        curve.host_uv.push(DVec2::new(u, seam));
    }
    let n = curve.points.len();
    if on_seam.len() < 2 {
        return Err((a, "the neck's loop does not cross the seam".into()));
    }
    // Each piece between two seam samples, in the patch its samples lie in.
    let (mut notches_below, mut notches_above) = (Vec::new(), Vec::new());
    for (i, &start) in on_seam.iter().enumerate() {
        let end = on_seam[(i + 1) % on_seam.len()];
        let steps = (end + n - start) % n;
        let Some(middle) = (steps > 1).then(|| curve.host_uv[(start + steps / 2) % n]) else {
            return Err((
                a,
                "the neck's loop touches the seam without crossing it".into(),
            ));
        };
        let (side, edge, shift, list) = if middle.y < seam {
            (
                Side::VMax,
                below.domain().1.1,
                shifts[0],
                &mut notches_below,
            )
        } else {
            (
                Side::VMin,
                above.domain().1.0,
                shifts[1],
                &mut notches_above,
            )
        };
        let mut path: Vec<DVec2> = (0..=steps)
            .map(|s| {
                let p = curve.host_uv[(start + s) % n];
                DVec2::new(p.x, p.y - shift)
            })
            .collect();
        path[0].y = edge;
        path[steps].y = edge;
        if path[0].x > path[steps].x {
            path.reverse();
        }
        list.push(Notch { side, path });
    }
    let neck_cut = Cut {
        hosts: [(a, notches_below), (b, notches_above)]
            .into_iter()
            .filter(|(_, n)| !n.is_empty())
            .map(|(k, n)| (k, HostTrim::Notches(Arc::from(n))))
            .collect(),
        neck: curve,
        pad: None,
    };
    let notched = notched_loop(builder, &neck_cut, hosts, host_frame, neck_knots)?;
    Ok((neck_cut.neck, notched))
}
