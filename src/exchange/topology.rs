//! The B-rep of a vessel: faces on the exact patches, bounded by loops of edges
//! that neighbouring faces share, grouped into shells.
//!
//! Input: a [`VesselSource`] (patches in part frames, openings cut into their
//! hosts). Output: a [`VesselBrep`] in the vessel's frame (a receiver places it in
//! the plant with the vessel frame), with
//!
//! - one [`Face`] per patch, on its exact rational surface, whose outer loop runs
//!   counter-clockwise in (u, v) (the face's normal `S_u × S_v` is outward): the
//!   four sides of the parameter rectangle, a side collapsed to a pole left out
//!   (receivers add their degenerate edge there); a nozzle's neck has the
//!   neck–host loop for its bottom side, and a host has that loop (or its pad's)
//!   as a hole, clockwise;
//! - one [`Edge`] per distinct boundary curve: a side is the exact isocurve of its
//!   surface, and two sides of neighbouring faces (or the two sides of a closed
//!   patch's seam) are one edge when their curves coincide point for point (ends
//!   within the vessel's match distance, and three interior points at the same
//!   fractions of their parameter ranges, taken either way round); each face's
//!   use of an edge carries its pcurve, a straight line in (u, v) over the edge's
//!   parameter range; an opening's edge is its intersection loop, marched to
//!   the exchange tolerance and fitted (`fit`) as a cubic B-spline over the
//!   neck's parameter, with each face's pcurve fitted on the same knots, all
//!   within the tolerance of the exact curve;
//! - a reinforcing pad across the seam between two host patches (a head's
//!   knuckle and the crown, cone or plate beyond): a face on each host patch,
//!   bounded by the pad loop's notch in it and the seam's isocurve between
//!   the notch's ends (an edge the two pieces share), the neck's loop a hole
//!   in the piece holding it, or, where it crosses the seam too, split at its
//!   crossings solved on the seam and notching each piece's seam side (the
//!   seam's isocurve between the pad's and the neck's notches shared by the
//!   two pieces);
//! - shells: the faces joined through shared edges, closed when every edge of
//!   the shell is used twice.

//!
//! The data types live in `brep`, the loops each face is bounded by (sides,
//! opening loops, arcs round a seam or a pole, pcurves) in `loops`.

use std::collections::HashMap;

use glam::DVec3;

use super::brep::{Face, Port, VesselBrep, shells};
use super::error::ExchangeError;
use super::fit::fit_loops;
use super::loops::{Builder, Hole, LoopEdges, Loops, NotchUse, SeamHole, seam_index};
use super::notch::{neck_across, notched_loop};
use super::seam::{on_pad_cylinder, uv_with_inserted, with_seam_samples};
use super::source::{CutSource, NodeKind, VesselSource};
use crate::mesh::{Cut, HostTrim, PadCut, closed_in_u};
use crate::nurbs::builders::{line, revolve};
use crate::nurbs::intersect::IntersectionLoop;
use crate::nurbs::{NurbsSurface, Side};
use crate::parts::Patch;
use glam::DVec2;
use std::f64::consts::TAU;

/// The nozzle patch whose inner edge is the bore.
const GASKET_FACE: &str = "gasket face";

/// The name of the disk closing a bore.
pub const BORE_CAP: &str = "bore cap";

/// Distance, relative to the vessel's size, within which two points are one
/// vertex and two curves one edge.
const MATCH_RELATIVE: f64 = 1e-9;

/// Smallest match distance, mm.
const MATCH_MIN: f64 = 1e-7;

/// Builds the B-rep of one vessel.
///
/// # Errors
///
/// [`ExchangeError::Topology`] for a trim this builder does not handle yet (a
/// notch across a closed patch's seam in u), [`ExchangeError::Geometry`] where a
/// surface or curve cannot be mapped or split.
pub fn vessel_brep(source: &VesselSource) -> Result<VesselBrep, ExchangeError> {
    vessel_brep_with(source, false)
}

/// [`vessel_brep`], with each nozzle's bore closed by a disk in its gasket
/// plane (`"bore cap"`, continuing the gasket face's parametrization to the
/// axis) when `close_bores` is set: the envelope is then a closed shell, the
/// vessel's displacement solid.
///
/// # Errors
///
/// As [`vessel_brep`].
pub fn vessel_brep_with(
    source: &VesselSource,
    close_bores: bool,
) -> Result<VesselBrep, ExchangeError> {
    let mut size = 0.0f64;
    for node in &source.nodes {
        for patch in &node.patches {
            for p in patch.surface.control_points() {
                size = size.max(node.frame.transform_point3(p).abs().max_element());
            }
        }
    }
    let mut builder = Builder {
        tolerance: (size * MATCH_RELATIVE).max(MATCH_MIN),
        vertices: Vec::new(),
        vertex_cells: Default::default(),
        group: 0,
        edges: Vec::new(),
        by_ends: Default::default(),
        loop_breaks: Vec::new(),
    };
    let entity = |node: usize| format!("{}/{}", source.tag, source.nodes[node].id);

    // Opening loops: one closed edge each, or two where the loop goes round
    // its host's pole (split at the sample on the host's seam).
    let mut holes: HashMap<(usize, usize), Vec<Hole>> = HashMap::new();
    let mut rounds: HashMap<(usize, usize), (LoopEdges, &IntersectionLoop, usize)> = HashMap::new();
    let mut pad_faces = Vec::new();
    // Loops with samples added on a host's seam, by cut.
    let mut seam_loops: Vec<Option<IntersectionLoop>> = vec![None; source.cuts.len()];
    // Pad loops with samples added on their host's seam, by cut.
    let mut pad_seam_loops: Vec<Option<IntersectionLoop>> = vec![None; source.cuts.len()];
    let mut seam_holes: HashMap<(usize, usize), Vec<SeamHole>> = HashMap::new();
    let mut notches: HashMap<(usize, usize), Vec<NotchUse>> = HashMap::new();
    let mut pairs = Vec::new();
    let mut pad_pieces = Vec::new();
    for (c, cut) in source.cuts.iter().enumerate() {
        let host_frame = source.nodes[cut.host].frame;
        let fail = |k: usize, rule: &str| ExchangeError::Topology {
            entity: entity(cut.neck),
            patch: source.nodes[cut.host].patches[k].name.to_string(),
            rule: rule.to_string(),
        };
        // The neck's u knots: the loops' parameter and its breaks (a pad's
        // outside cylinder is revolved as the neck is).
        let neck_knots = source.nodes[cut.neck]
            .patches
            .first()
            .map(|p| p.surface.u_knots().distinct())
            .unwrap_or_default();
        let no_neck = || fail(0, "the opening's neck has no patch");
        if neck_knots.len() < 2 {
            return Err(no_neck());
        }
        // Across the seam between two host patches: notches in their sides.
        if let Some((k, _)) = cut
            .cut
            .hosts
            .iter()
            .find(|(_, t)| matches!(t, HostTrim::Notches(_)))
        {
            let (edges, uses) = notched_loop(
                &mut builder,
                &cut.cut,
                &source.nodes[cut.host].patches,
                &host_frame,
                &neck_knots,
            )
            .map_err(|(k, rule)| fail(k, &rule))?;
            let pieces = uses.clone();
            for (k, notch) in uses {
                notches.entry((cut.host, k)).or_default().push(notch);
            }
            // A pad across the seam: a face on each host patch, from its
            // notch to the seam, with the neck's loop as a hole where it lies
            // in one patch; where the neck's loop crosses the seam too, split
            // at the seam, notching each piece as the pad's loop notches the
            // host faces.
            if cut.pad.is_none() {
                pairs.push((c, edges));
                continue;
            }
            let hosts = &source.nodes[cut.host].patches;
            let (neck_edges, neck_at) = match neck_in_one_patch(&cut.cut, hosts) {
                Some((inside, uv)) => {
                    let neck_edges = builder
                        .loop_edges(&cut.cut.neck, &host_frame, &[], &neck_knots)
                        .map_err(|rule| fail(*k, &rule))?;
                    (neck_edges, NeckAt::Inside(inside, uv))
                }
                None => {
                    let neck = neck_in_host(source, cut, &entity(cut.neck))?;
                    let (with_seam, (neck_edges, neck_notches)) = neck_across(
                        &mut builder,
                        &cut.cut,
                        &neck,
                        hosts,
                        &host_frame,
                        &neck_knots,
                    )
                    .map_err(|(k, rule)| fail(k, &rule))?;
                    seam_loops[c] = Some(with_seam);
                    (neck_edges, NeckAt::Across(neck_notches))
                }
            };
            pad_pieces.push((c, pieces, neck_at, neck_edges.clone()));
            pairs.push((c, neck_edges));
            continue;
        }
        // The host patch a hole lies in, and the seam sample of a loop round its pole.
        let mut round: Option<(usize, usize)> = None;
        // For a padded opening round the pole: the pad loop's and the neck
        // loop's seam samples.
        let mut pad_round: Option<(usize, usize)> = None;
        for (k, trim) in &cut.cut.hosts {
            let host = &source.nodes[cut.host].patches[*k].surface;
            let hole_loop = cut.cut.pad.as_ref().unwrap_or(&cut.cut.neck);
            match trim {
                HostTrim::Hole if hole_loop.host_turns(host) != 0 => {
                    let no_sample = || {
                        fail(
                            *k,
                            "the loop round the pole has no sample on the host's seam",
                        )
                    };
                    let split = seam_index(&hole_loop.host_uv, host).ok_or_else(no_sample)?;
                    if cut.cut.pad.is_some() {
                        let neck_split =
                            seam_index(&cut.cut.neck.host_uv, host).ok_or_else(no_sample)?;
                        pad_round = Some((split, neck_split));
                    }
                    round = Some((*k, split));
                }
                // Notches were written above.
                HostTrim::Hole | HostTrim::Notches(_) => {}
            }
        }
        // A hole across its closed host's seam (the neck's loop, or the pad's
        // round it): samples on the seam.
        let mut splits: Vec<usize> = match (pad_round, round) {
            (Some((_, neck_split)), _) => vec![neck_split],
            (None, Some((_, split))) => vec![split],
            (None, None) => Vec::new(),
        };
        let mut pad_splits: Vec<usize> = pad_round.map(|r| vec![r.0]).unwrap_or_default();
        let mut seam_host = None;
        if round.is_none()
            && let [(k, HostTrim::Hole)] = cut.cut.hosts.as_slice()
            && closed_in_u(&source.nodes[cut.host].patches[*k].surface)
        {
            let host = &source.nodes[cut.host].patches[*k].surface;
            let nozzle_in_host = host_frame.inverse() * source.nodes[cut.neck].frame;
            let (with_seam, seam) = match (&cut.cut.pad, cut.pad_od) {
                (None, _) => {
                    let neck = neck_in_host(source, cut, &entity(cut.neck))?;
                    with_seam_samples(&cut.cut.neck, &neck, host)
                }
                (Some(pad_loop), Some(od)) => on_pad_cylinder(pad_loop, 0.5 * od, &nozzle_in_host)
                    .and_then(|(cylinder, on_cylinder)| {
                        with_seam_samples(&on_cylinder, &cylinder, host)
                    }),
                (Some(_), None) => Err("a pad loop without the pad's diameter".to_string()),
            }
            .map_err(|rule| fail(*k, &rule))?;
            if !seam.is_empty() {
                seam_host = Some((*k, seam.clone(), with_seam.host_uv.clone()));
                if cut.cut.pad.is_some() {
                    pad_seam_loops[c] = Some(with_seam);
                    pad_splits = seam;
                } else {
                    seam_loops[c] = Some(with_seam);
                    splits = seam;
                }
            }
        }
        let neck_edges = {
            let neck_loop = seam_loops[c].as_ref().unwrap_or(&cut.cut.neck);
            builder
                .loop_edges(neck_loop, &host_frame, &splits, &neck_knots)
                .map_err(|rule| fail(0, &rule))?
        };
        let hole_edges = match (&pad_seam_loops[c], &cut.cut.pad) {
            (Some(pad_loop), _) | (None, Some(pad_loop)) => builder
                .loop_edges(pad_loop, &host_frame, &pad_splits, &neck_knots)
                .map_err(|rule| fail(0, &rule))?,
            (None, None) => neck_edges.clone(),
        };
        if let Some((k, seam, uv)) = seam_host {
            seam_holes
                .entry((cut.host, k))
                .or_default()
                .push((hole_edges.clone(), uv, seam));
            if let Some(pad) = &cut.pad {
                pad_faces.push((cut, pad, neck_edges.clone(), hole_edges, false, Some(c)));
            }
            pairs.push((c, neck_edges));
            continue;
        }
        let hole_loop = cut.cut.pad.as_ref().unwrap_or(&cut.cut.neck);
        for (k, _) in &cut.cut.hosts {
            match round {
                Some((r, split)) if r == *k => {
                    rounds.insert((cut.host, *k), (hole_edges.clone(), hole_loop, split));
                }
                _ => holes
                    .entry((cut.host, *k))
                    .or_default()
                    .push((hole_edges.clone(), hole_loop.host_uv.clone())),
            }
        }
        if let Some(pad) = &cut.pad {
            pad_faces.push((
                cut,
                pad,
                neck_edges.clone(),
                hole_edges,
                pad_round.is_some(),
                None,
            ));
        }
        pairs.push((c, neck_edges));
    }
    // Each neck's bottom: its loop (with any seam samples) and its edges.
    let mut bottoms: HashMap<usize, (LoopEdges, &IntersectionLoop)> = HashMap::new();
    for (c, edges) in pairs {
        let cut = &source.cuts[c];
        let curve = seam_loops[c].as_ref().unwrap_or(&cut.cut.neck);
        bottoms.insert(cut.neck, (edges, curve));
    }

    let mut faces = Vec::new();
    for (n, node) in source.nodes.iter().enumerate() {
        builder.group = if node.kind == NodeKind::Support {
            n + 1
        } else {
            0
        };
        for (k, patch) in node.patches.iter().enumerate() {
            let surface = patch.surface.transformed(&node.frame).map_err(|source| {
                ExchangeError::Geometry {
                    entity: entity(n),
                    source,
                }
            })?;
            let bottom = if k == 0 { bottoms.get(&n) } else { None };
            let face_holes = holes.remove(&(n, k)).unwrap_or_default();
            let across = seam_holes.remove(&(n, k)).unwrap_or_default();
            let face_notches = notches.remove(&(n, k)).unwrap_or_default();
            let face = builder
                .patch_face(
                    &surface,
                    bottom,
                    rounds.get(&(n, k)),
                    &face_holes,
                    &across,
                    &face_notches,
                )
                .map_err(|rule| ExchangeError::Topology {
                    entity: entity(n),
                    patch: crate::export::patch_name(patch),
                    rule,
                })?;
            faces.push(Face {
                node: n,
                patch: crate::export::patch_name(patch),
                surface,
                outer: face.0,
                holes: face.1,
            });
        }
    }
    builder.group = 0;
    if close_bores {
        for (n, node) in source.nodes.iter().enumerate() {
            if node.kind != NodeKind::Nozzle {
                continue;
            }
            let Some(gasket) = node.patches.iter().find(|p| p.name == GASKET_FACE) else {
                continue;
            };
            let ((u0, u1), (v0, v1)) = gasket.surface.domain();
            let bore = gasket.surface.point(u0, v1);
            let centre = DVec3::new(0.0, 0.0, bore.z);
            if bore.distance(centre) <= builder.tolerance {
                continue; // a blind: closed already
            }
            let geometry = |source| ExchangeError::Geometry {
                entity: entity(n),
                source,
            };
            let profile = line(bore, centre).map_err(geometry)?;
            let cap = revolve(&profile, DVec3::ZERO, DVec3::Z, TAU)
                .and_then(|s| s.transformed(&node.frame))
                .map_err(geometry)?;
            let _ = (u1, v0);
            let (outer, holes) = builder
                .patch_face(&cap, None, None, &[], &[], &[])
                .map_err(|rule| ExchangeError::Topology {
                    entity: entity(n),
                    patch: BORE_CAP.to_string(),
                    rule,
                })?;
            faces.push(Face {
                node: n,
                patch: BORE_CAP.to_string(),
                surface: cap,
                outer,
                holes,
            });
        }
    }
    for (cut, pad, neck_edge, hole_edge, round, seam_cut) in pad_faces {
        let frame = source.nodes[cut.neck].frame;
        let surface =
            pad.patch
                .surface
                .transformed(&frame)
                .map_err(|source| ExchangeError::Geometry {
                    entity: entity(cut.neck),
                    source,
                })?;
        let fail = |rule: String| ExchangeError::Topology {
            entity: entity(cut.neck),
            patch: pad.patch.name.to_string(),
            rule,
        };
        let (surface, outer, holes) = if round {
            let (outer, holes) = builder
                .pad_round_pole(&surface, (&hole_edge, &pad.outer), (&neck_edge, &pad.inner))
                .map_err(fail)?;
            (surface, outer, holes)
        } else {
            // The pad's loop with the samples added on its host's seam, (u, v)
            // on the pad's surface.
            let outer_uv = match seam_cut.and_then(|c| pad_seam_loops[c].as_ref()) {
                Some(with_seam) => {
                    pad_outer_uv(cut, pad, with_seam, &surface, &source.nodes[cut.host].frame)
                        .map_err(fail)?
                }
                None => pad.outer.host_uv.clone(),
            };
            let (surface, (outer, holes)) = builder
                .annulus(
                    &surface,
                    (&hole_edge, &outer_uv),
                    (&neck_edge, &pad.inner.host_uv),
                )
                .map_err(fail)?;
            (surface, outer, holes)
        };
        faces.push(Face {
            node: cut.neck,
            patch: crate::export::patch_name(&pad.patch),
            surface,
            outer,
            holes,
        });
    }

    for (c, pieces, neck_at, neck_edges) in pad_pieces {
        let cut = &source.cuts[c];
        let host_frame = source.nodes[cut.host].frame;
        for (k, notch) in pieces {
            let patch = &source.nodes[cut.host].patches[k];
            let surface = patch.surface.transformed(&host_frame).map_err(|source| {
                ExchangeError::Geometry {
                    entity: entity(cut.neck),
                    source,
                }
            })?;
            let neck = match &neck_at {
                NeckAt::Inside(inside, uv) if *inside == k => {
                    NeckIn::Hole(&neck_edges, uv.as_slice())
                }
                NeckAt::Inside(..) => NeckIn::Notches(Vec::new()),
                NeckAt::Across(notches) => NeckIn::Notches(
                    notches
                        .iter()
                        .filter(|(patch, _)| *patch == k)
                        .map(|(_, n)| n)
                        .collect(),
                ),
            };
            let (outer, holes) =
                pad_piece(&mut builder, &surface, &notch, neck).map_err(|rule| {
                    ExchangeError::Topology {
                        entity: entity(cut.neck),
                        patch: crate::mesh::PAD_PATCH.to_string(),
                        rule,
                    }
                })?;
            faces.push(Face {
                node: cut.neck,
                patch: crate::mesh::PAD_PATCH.to_string(),
                surface,
                outer,
                holes,
            });
        }
    }
    fit_loops(
        &mut builder.edges,
        &mut faces,
        &builder.loop_breaks,
        source.tolerance,
    )
    .map_err(|(edge, rule)| ExchangeError::Topology {
        entity: source.tag.clone(),
        patch: format!("opening loop edge {edge}"),
        rule,
    })?;
    let shells = shells(&faces, builder.edges.len());
    let ports = source
        .nodes
        .iter()
        .filter(|n| n.kind == NodeKind::Nozzle)
        .filter_map(|n| {
            let nozzle = n.nozzle.as_ref()?;
            Some(Port {
                mark: n.id.clone(),
                origin: n
                    .frame
                    .transform_point3(DVec3::new(0.0, 0.0, nozzle.projection)),
                axis: n.frame.transform_vector3(DVec3::Z).normalize(),
                across: n.frame.transform_vector3(DVec3::X).normalize(),
                description: format!(
                    "{:?} {:?} {:?} {:?}",
                    nozzle.nps, nozzle.class, nozzle.flange, nozzle.facing
                ),
            })
        })
        .collect();
    Ok(VesselBrep {
        tag: source.tag.clone(),
        frame: source.frame,
        nodes: source.nodes.iter().map(|n| n.id.clone()).collect(),
        vertices: builder.vertices,
        edges: builder.edges,
        faces,
        shells,
        ports,
        tolerance: source.tolerance,
    })
}

/// The (u, v) on the pad's `surface` (vessel frame; `to_surface` maps the
/// host's frame there) of each sample of `with_seam`: the pad's loop in its
/// host's frame (`cut.cut.pad`) with samples added on the host's seam. The
/// loop's own samples keep their (u, v) on the pad's patch (`pad.outer`, one
/// per sample, in the same order: a straight course's pad loop is the
/// canonical loop `cut.cut.pad` was placed from); only the added samples are
/// projected. Matching `with_seam` against `pad.outer` itself, whose points
/// are the canonical loop's, matched no sample in a straight course and
/// projected every one (a global closest-point search each).
fn pad_outer_uv(
    cut: &CutSource,
    pad: &PadCut,
    with_seam: &IntersectionLoop,
    surface: &NurbsSurface,
    to_surface: &glam::DAffine3,
) -> Result<Vec<DVec2>, String> {
    let original = match &cut.cut.pad {
        Some(placed) if placed.points.len() == pad.outer.host_uv.len() => placed,
        _ => &pad.outer,
    };
    uv_with_inserted(original, &pad.outer.host_uv, with_seam, surface, to_surface)
}

/// Where the neck's loop of an opening across the seam between two host
/// patches lies, when it lies in one of them: that patch's index and the
/// loop's (u, v) on it (the cut gives them on the patches joined in v).
/// The neck's surface of `cut` in its host's frame; `entity` names the neck
/// in the error.
fn neck_in_host(
    source: &VesselSource,
    cut: &CutSource,
    entity: &str,
) -> Result<NurbsSurface, ExchangeError> {
    let nozzle_in_host = source.nodes[cut.host].frame.inverse() * source.nodes[cut.neck].frame;
    source.nodes[cut.neck].patches[0]
        .surface
        .transformed(&nozzle_in_host)
        .map_err(|source| ExchangeError::Geometry {
            entity: entity.to_string(),
            source,
        })
}

fn neck_in_one_patch(cut: &Cut, hosts: &[Patch]) -> Option<(usize, Vec<DVec2>)> {
    let [(a, _), (b, _)] = cut.hosts.as_slice() else {
        return None;
    };
    let (first, second) = (&hosts[*a].surface, &hosts[*b].surface);
    let seam = first.domain().1.1;
    let shift = seam - second.domain().1.0;
    let uv = &cut.neck.host_uv;
    if uv.iter().all(|p| p.y < seam) {
        Some((*a, uv.clone()))
    } else if uv.iter().all(|p| p.y > seam) {
        Some((
            *b,
            uv.iter().map(|p| DVec2::new(p.x, p.y - shift)).collect(),
        ))
    } else {
        None
    }
}

/// Where a padded opening's neck loop lies, its pad's loop crossing the seam
/// between two host patches.
enum NeckAt {
    /// In one patch (its index), with the loop's (u, v) on it.
    Inside(usize, Vec<DVec2>),
    /// Across the seam too: its notch uses in each patch, by patch index.
    Across(Vec<(usize, NotchUse)>),
}

/// The neck's loop in one piece of a pad across a seam.
enum NeckIn<'a> {
    /// A hole: the loop's edges and (u, v) on the piece's patch.
    Hole(&'a LoopEdges, &'a [DVec2]),
    /// Notches into the piece's seam side (none where the neck lies in the
    /// other piece).
    Notches(Vec<&'a NotchUse>),
}

/// The face of a reinforcing pad's piece on one host patch (`surface`, vessel
/// frame): the pad's loop along `notch` the other way round from the host's
/// face, then the side's isocurve between the notch's ends (the edge the
/// piece on the neighbouring patch shares), cut where the neck's loop
/// notches it, and the neck's loop as a hole where it lies in this patch.
fn pad_piece(
    builder: &mut Builder,
    surface: &NurbsSurface,
    notch: &NotchUse,
    neck: NeckIn,
) -> Result<Loops, String> {
    let ((u0, u1), (v0, v1)) = surface.domain();
    let (v, bottom) = match notch.side {
        Side::VMin => (v0, true),
        _ => (v1, false),
    };
    let (low, high) = notch.u;
    let mut side = surface.isocurve_v(v);
    if low > u0 {
        side = side.split_at(low).map_err(|e| e.to_string())?.1;
    }
    if high < u1 {
        side = side.split_at(high).map_err(|e| e.to_string())?.0;
    }
    let mut outer = Builder::against(notch.uses.clone());
    match neck {
        NeckIn::Hole(edges, uv) => {
            outer.push(builder.side_use(side, DVec2::new(low, v), DVec2::new(high, v), bottom));
            Ok((outer, vec![builder.hole_use(surface, edges, uv, false)?]))
        }
        NeckIn::Notches(notches) => {
            builder.notched_side(&mut outer, &side, v, notches, bottom)?;
            Ok((outer, Vec::new()))
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::exchange::vessel_sources;
    use crate::plant::generate_plant;

    /// Every pad loop of a generated plant across its course's seam keeps
    /// the pad cut's own (u, v) bit for bit at each of its samples; only the
    /// samples added on the seam are projected onto the pad.
    #[test]
    fn a_pad_across_a_seam_projects_only_its_seam_samples() {
        let design = generate_plant(5, 1).expect("plant");
        let (mut pads, mut kept) = (0, 0);
        for source in vessel_sources(&design, &[], 1e-3).expect("sources") {
            for cut in &source.cuts {
                let (Some(pad), Some(pad_loop), Some(od)) = (&cut.pad, &cut.cut.pad, cut.pad_od)
                else {
                    continue;
                };
                let [(k, HostTrim::Hole)] = cut.cut.hosts.as_slice() else {
                    continue;
                };
                let host_frame = source.nodes[cut.host].frame;
                let host = &source.nodes[cut.host].patches[*k].surface;
                if !closed_in_u(host) {
                    continue;
                }
                let nozzle_in_host = host_frame.inverse() * source.nodes[cut.neck].frame;
                let (with_seam, seam) = on_pad_cylinder(pad_loop, 0.5 * od, &nozzle_in_host)
                    .and_then(|(cylinder, on)| with_seam_samples(&on, &cylinder, host))
                    .expect("seam samples");
                if seam.is_empty() {
                    continue;
                }
                let surface = pad
                    .patch
                    .surface
                    .transformed(&source.nodes[cut.neck].frame)
                    .expect("pad surface");
                let uv = pad_outer_uv(cut, pad, &with_seam, &surface, &host_frame).expect("uv");
                assert_eq!(uv.len(), with_seam.points.len());
                let mut j = 0;
                for (i, p) in with_seam.points.iter().enumerate() {
                    if j < pad_loop.points.len() && pad_loop.points[j] == *p {
                        assert_eq!(
                            uv[i], pad.outer.host_uv[j],
                            "{}: sample {j}",
                            source.nodes[cut.neck].id
                        );
                        j += 1;
                    }
                }
                assert_eq!(j, pad_loop.points.len(), "{}", source.nodes[cut.neck].id);
                pads += 1;
                kept += j;
            }
        }
        assert!(pads > 0 && kept > 0, "no pad across a seam in the plant");
    }
}
