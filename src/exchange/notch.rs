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

use glam::{DAffine3, DVec2};

use super::brep::OrientedEdge;
use super::loops::{Builder, LoopEdges, NotchUse};
use crate::mesh::{Cut, HostTrim, Notch};
use crate::nurbs::Side;
use crate::parts::Patch;

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
