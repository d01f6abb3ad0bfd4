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
//!   parameter range; an opening's edge is its intersection loop as sampled to
//!   the exchange tolerance, a closed degree-1 curve through the samples, with
//!   each face's (u, v) of the same samples for its pcurve (the marcher bounds the
//!   chord's distance from both surfaces' images of the pcurve segment);
//! - shells: the faces joined through shared edges, closed when every edge of
//!   the shell is used twice.

use std::collections::HashMap;

use glam::{DAffine3, DVec2, DVec3};

use super::error::ExchangeError;
use super::seam::with_seam_samples;
use super::source::{NodeKind, VesselSource};
use crate::mesh::{HostTrim, closed_in_u};
use crate::nurbs::builders::{line, revolve};
use crate::nurbs::intersect::IntersectionLoop;
use crate::nurbs::{NurbsCurve, NurbsSurface};
use std::f64::consts::TAU;

/// An edge's curve, in the vessel frame.
#[derive(Clone, Debug, PartialEq)]
pub enum EdgeCurve {
    /// An exact isocurve of a patch, over its own parameter range.
    Nurbs(NurbsCurve),
    /// A sampled intersection loop: the points in order, the first repeated at
    /// the end; parameter k at point k.
    Polyline(Vec<DVec3>),
}

impl EdgeCurve {
    /// The parameter range.
    pub fn domain(&self) -> (f64, f64) {
        match self {
            EdgeCurve::Nurbs(c) => c.domain(),
            EdgeCurve::Polyline(p) => (0.0, (p.len() - 1) as f64),
        }
    }

    /// The point at parameter `t`.
    pub fn point(&self, t: f64) -> DVec3 {
        match self {
            EdgeCurve::Nurbs(c) => c.point(t),
            EdgeCurve::Polyline(p) => {
                let k = (t.floor() as usize).min(p.len() - 2);
                p[k].lerp(p[k + 1], t - k as f64)
            }
        }
    }
}

/// An edge between two vertices (equal for a closed edge).
#[derive(Clone, Debug, PartialEq)]
pub struct Edge {
    /// Index of the vertex at the curve's start.
    pub start: usize,
    /// Index of the vertex at the curve's end.
    pub end: usize,
    /// The curve.
    pub curve: EdgeCurve,
}

/// One use of an edge in a face's loop.
#[derive(Clone, Debug, PartialEq)]
pub struct OrientedEdge {
    /// Index of the edge.
    pub edge: usize,
    /// Whether the loop runs along the edge's curve direction.
    pub forward: bool,
    /// The pcurve in the face's (u, v), degree 1 over the edge's parameter:
    /// two points for an exact edge (its ends), one per sample for a loop.
    pub pcurve: Vec<DVec2>,
}

/// A face: one patch, trimmed.
#[derive(Clone, Debug, PartialEq)]
pub struct Face {
    /// Index of the part or nozzle in [`VesselBrep::nodes`].
    pub node: usize,
    /// Patch name (`"crown"`, `"leg 2"`).
    pub patch: String,
    /// The exact surface, vessel frame.
    pub surface: NurbsSurface,
    /// Outer loop, counter-clockwise in (u, v).
    pub outer: Vec<OrientedEdge>,
    /// Holes, clockwise in (u, v).
    pub holes: Vec<Vec<OrientedEdge>>,
}

/// Faces joined through shared edges.
#[derive(Clone, Debug, PartialEq)]
pub struct Shell {
    /// Indices of the faces.
    pub faces: Vec<usize>,
    /// Every edge of the shell is used twice.
    pub closed: bool,
}

/// A nozzle's connection point: where piping connects.
#[derive(Clone, Debug, PartialEq)]
pub struct Port {
    /// The nozzle's mark.
    pub mark: String,
    /// Flange gasket face centre, vessel frame, mm.
    pub origin: DVec3,
    /// Outward axis (unit).
    pub axis: DVec3,
    /// A unit direction across the axis (the nozzle frame's X).
    pub across: DVec3,
    /// Size, rating and facing, e.g. `"NPS 6 CL150 RF"`.
    pub description: String,
}

/// A vessel's B-rep, vessel frame.
#[derive(Clone, Debug, PartialEq)]
pub struct VesselBrep {
    /// Tag.
    pub tag: String,
    /// Vessel frame → plant frame.
    pub frame: DAffine3,
    /// Part ids and nozzle marks, design order.
    pub nodes: Vec<String>,
    /// Vertices.
    pub vertices: Vec<DVec3>,
    /// Edges.
    pub edges: Vec<Edge>,
    /// Faces.
    pub faces: Vec<Face>,
    /// Shells.
    pub shells: Vec<Shell>,
    /// Nozzle connection points.
    pub ports: Vec<Port>,
}

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
/// [`ExchangeError::Topology`] for a trim this builder does not handle yet (an
/// opening across a seam between two host patches, a hole that goes round a
/// pole or crosses a closed patch's seam), [`ExchangeError::Geometry`] where a
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
        edges: Vec::new(),
        by_ends: HashMap::new(),
    };
    let entity = |node: usize| format!("{}/{}", source.tag, source.nodes[node].id);

    // Opening loops: one closed edge each, or two where the loop goes round
    // its host's pole (split at the sample on the host's seam).
    let mut holes: HashMap<(usize, usize), Vec<Hole>> = HashMap::new();
    let mut rounds: HashMap<(usize, usize), (LoopEdges, &IntersectionLoop, usize)> = HashMap::new();
    let mut pad_faces = Vec::new();
    // Loops with samples added on a host's seam, by cut.
    let mut seam_loops: Vec<Option<IntersectionLoop>> = vec![None; source.cuts.len()];
    let mut seam_holes: HashMap<(usize, usize), Vec<SeamHole>> = HashMap::new();
    let mut pairs = Vec::new();
    for (c, cut) in source.cuts.iter().enumerate() {
        let host_frame = source.nodes[cut.host].frame;
        let fail = |k: usize, rule: &str| ExchangeError::Topology {
            entity: entity(cut.neck),
            patch: source.nodes[cut.host].patches[k].name.to_string(),
            rule: rule.to_string(),
        };
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
                HostTrim::Hole => {}
                HostTrim::Notches(_) => {
                    return Err(fail(
                        *k,
                        "an opening across the seam between two host patches is not written yet",
                    ));
                }
            }
        }
        // A plain hole across its closed host's seam: samples on the seam.
        let mut splits: Vec<usize> = match (pad_round, round) {
            (Some((_, neck_split)), _) => vec![neck_split],
            (None, Some((_, split))) => vec![split],
            (None, None) => Vec::new(),
        };
        let mut seam_host = None;
        if round.is_none()
            && cut.cut.pad.is_none()
            && let [(k, HostTrim::Hole)] = cut.cut.hosts.as_slice()
        {
            {
                let host = &source.nodes[cut.host].patches[*k].surface;
                if closed_in_u(host) {
                    let neck_frame = host_frame.inverse() * source.nodes[cut.neck].frame;
                    let neck = source.nodes[cut.neck].patches[0]
                        .surface
                        .transformed(&neck_frame)
                        .map_err(|source| ExchangeError::Geometry {
                            entity: entity(cut.neck),
                            source,
                        })?;
                    let (with_seam, seam) = with_seam_samples(&cut.cut.neck, &neck, host)
                        .map_err(|rule| fail(*k, &rule))?;
                    if !seam.is_empty() {
                        seam_loops[c] = Some(with_seam);
                        splits = seam.clone();
                        seam_host = Some((*k, seam));
                    }
                }
            }
        }
        let neck_loop: &IntersectionLoop = seam_loops[c].as_ref().unwrap_or(&cut.cut.neck);
        let neck_edges = builder.loop_edges(neck_loop, &host_frame, &splits);
        let hole_edges = match &cut.cut.pad {
            Some(pad_loop) => {
                let pad_splits: Vec<usize> = pad_round.map(|r| vec![r.0]).unwrap_or_default();
                builder.loop_edges(pad_loop, &host_frame, &pad_splits)
            }
            None => neck_edges.clone(),
        };
        let hole_loop = cut.cut.pad.as_ref().unwrap_or(&cut.cut.neck);
        if let Some((k, seam)) = seam_host {
            seam_holes.entry((cut.host, k)).or_default().push((
                neck_edges.clone(),
                neck_loop.host_uv.clone(),
                seam,
            ));
            pairs.push((c, neck_edges));
            continue;
        }
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
            let face = builder
                .patch_face(&surface, bottom, rounds.get(&(n, k)), &face_holes, &across)
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
            let (outer, holes) =
                builder
                    .patch_face(&cap, None, None, &[], &[])
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
    for (cut, pad, neck_edge, hole_edge, round) in pad_faces {
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
        let (outer, holes) = if round {
            builder
                .pad_round_pole(&surface, (&hole_edge, &pad.outer), (&neck_edge, &pad.inner))
                .map_err(fail)?
        } else {
            let outer = builder
                .hole_use(&surface, &hole_edge, &pad.outer.host_uv, true)
                .map_err(fail)?;
            let inner = builder
                .hole_use(&surface, &neck_edge, &pad.inner.host_uv, false)
                .map_err(fail)?;
            (outer, vec![inner])
        };
        faces.push(Face {
            node: cut.neck,
            patch: crate::export::patch_name(&pad.patch),
            surface,
            outer,
            holes,
        });
    }

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
    })
}

/// The index of the sample of `uv` on `surface`'s u-seam.
fn seam_index(uv: &[DVec2], surface: &NurbsSurface) -> Option<usize> {
    let ((u0, u1), _) = surface.domain();
    let period = u1 - u0;
    uv.iter().position(|p| {
        let r = (p.x - u0) / period;
        (r - r.round()).abs() < 1e-9
    })
}

/// Faces joined by shared edges (union–find), in order of their first face.
fn shells(faces: &[Face], edge_count: usize) -> Vec<Shell> {
    let mut parent: Vec<usize> = (0..faces.len()).collect();
    fn root(parent: &mut [usize], mut i: usize) -> usize {
        while parent[i] != i {
            parent[i] = parent[parent[i]];
            i = parent[i];
        }
        i
    }
    let mut first_face: Vec<Option<usize>> = vec![None; edge_count];
    let mut uses = vec![0usize; edge_count];
    for (f, face) in faces.iter().enumerate() {
        for e in face.outer.iter().chain(face.holes.iter().flatten()) {
            uses[e.edge] += 1;
            match first_face[e.edge] {
                None => first_face[e.edge] = Some(f),
                Some(g) => {
                    let (a, b) = (root(&mut parent, f), root(&mut parent, g));
                    parent[a.max(b)] = a.min(b);
                }
            }
        }
    }
    let mut shells: Vec<Shell> = Vec::new();
    let mut index: HashMap<usize, usize> = HashMap::new();
    for f in 0..faces.len() {
        let r = root(&mut parent, f);
        let s = *index.entry(r).or_insert_with(|| {
            shells.push(Shell {
                faces: Vec::new(),
                closed: true,
            });
            shells.len() - 1
        });
        shells[s].faces.push(f);
    }
    for shell in &mut shells {
        shell.closed = shell.faces.iter().all(|&f| {
            let face = &faces[f];
            face.outer
                .iter()
                .chain(face.holes.iter().flatten())
                .all(|e| uses[e.edge] == 2)
        });
    }
    shells
}

/// Vertices and edges being gathered for one vessel.
struct Builder {
    /// Match distance, mm.
    tolerance: f64,
    vertices: Vec<DVec3>,
    edges: Vec<Edge>,
    /// Exact edges by their (smaller, larger) vertex pair.
    by_ends: HashMap<(usize, usize), Vec<usize>>,
}

/// The edges of one opening loop: `(edge, first sample, last sample)` in loop
/// order, the last sample of the last part being the first sample again.
#[derive(Clone, Debug)]
struct LoopEdges {
    parts: Vec<(usize, usize, usize)>,
}

/// A hole: its loop's edges and (u, v) on the face.
type Hole = (LoopEdges, Vec<DVec2>);

/// A hole across the seam: its loop's edges, (u, v) on the face and the
/// indices of its samples on the seam.
type SeamHole = (LoopEdges, Vec<DVec2>, Vec<usize>);

/// A face's outer loop and holes.
type Loops = (Vec<OrientedEdge>, Vec<Vec<OrientedEdge>>);

impl Builder {
    /// The vertex at `p`, added if no vertex lies within the match distance.
    fn vertex(&mut self, p: DVec3) -> usize {
        if let Some(i) = self
            .vertices
            .iter()
            .position(|q| q.distance(p) <= self.tolerance)
        {
            return i;
        }
        self.vertices.push(p);
        self.vertices.len() - 1
    }

    /// The edges through a loop's samples, mapped from the host part's frame
    /// into the vessel's: one closed edge, or two split at sample `split` (the
    /// sample on the seam of a host the loop goes round).
    fn loop_edges(
        &mut self,
        curve: &IntersectionLoop,
        host_frame: &DAffine3,
        splits: &[usize],
    ) -> LoopEdges {
        let mut points: Vec<DVec3> = curve
            .points
            .iter()
            .map(|p| host_frame.transform_point3(*p))
            .collect();
        points.push(points[0]);
        let n = curve.points.len();
        let mut bounds: Vec<usize> = vec![0];
        bounds.extend(splits.iter().copied().filter(|&k| k > 0 && k < n));
        bounds.push(n);
        let parts = bounds
            .windows(2)
            .map(|w| {
                let (from, to) = (w[0], w[1]);
                let start = self.vertex(points[from]);
                let end = self.vertex(points[to]);
                self.edges.push(Edge {
                    start,
                    end,
                    curve: EdgeCurve::Polyline(points[from..=to].to_vec()),
                });
                (self.edges.len() - 1, from, to)
            })
            .collect();
        LoopEdges { parts }
    }

    /// The uses of a loop's edges along the loop's order, each with its slice
    /// of `pcurve` (one point per sample, the first repeated at the end).
    fn along(edges: &LoopEdges, pcurve: &[DVec2]) -> Vec<OrientedEdge> {
        edges
            .parts
            .iter()
            .map(|&(edge, from, to)| OrientedEdge {
                edge,
                forward: true,
                pcurve: pcurve[from..=to].to_vec(),
            })
            .collect()
    }

    /// The same uses the other way round.
    fn against(mut uses: Vec<OrientedEdge>) -> Vec<OrientedEdge> {
        uses.reverse();
        uses.iter_mut().for_each(|e| e.forward = !e.forward);
        uses
    }

    /// The use of the exact edge along `curve` (from `uv_start` at the start of
    /// its range to `uv_end`), the edge shared with an earlier side whose curve
    /// coincides. `along` tells whether the loop runs along the curve.
    fn side_use(
        &mut self,
        curve: NurbsCurve,
        uv_start: DVec2,
        uv_end: DVec2,
        along: bool,
    ) -> OrientedEdge {
        let s = self.vertex(curve.start());
        let e = self.vertex(curve.end());
        let key = (s.min(e), s.max(e));
        let fractions = [0.25, 0.5, 0.75];
        let at = |c: &EdgeCurve, f: f64| {
            let (a, b) = c.domain();
            c.point(a + (b - a) * f)
        };
        let own = EdgeCurve::Nurbs(curve);
        for &i in self.by_ends.get(&key).map(Vec::as_slice).unwrap_or(&[]) {
            let edge = &self.edges[i];
            if edge.start == s
                && edge.end == e
                && fractions
                    .iter()
                    .all(|&f| at(&edge.curve, f).distance(at(&own, f)) <= self.tolerance)
            {
                return OrientedEdge {
                    edge: i,
                    forward: along,
                    pcurve: vec![uv_start, uv_end],
                };
            }
            if edge.start == e
                && edge.end == s
                && fractions
                    .iter()
                    .all(|&f| at(&edge.curve, 1.0 - f).distance(at(&own, f)) <= self.tolerance)
            {
                return OrientedEdge {
                    edge: i,
                    forward: !along,
                    pcurve: vec![uv_end, uv_start],
                };
            }
        }
        self.edges.push(Edge {
            start: s,
            end: e,
            curve: own,
        });
        let i = self.edges.len() - 1;
        self.by_ends.entry(key).or_default().push(i);
        OrientedEdge {
            edge: i,
            forward: along,
            pcurve: vec![uv_start, uv_end],
        }
    }

    /// The use of a loop edge as a face's hole (`outer` false: clockwise in
    /// (u, v)) or outer loop (counter-clockwise), with the loop's (u, v) on
    /// `surface` shifted by whole periods into its domain.
    fn hole_use(
        &mut self,
        surface: &NurbsSurface,
        edges: &LoopEdges,
        uv: &[DVec2],
        outer: bool,
    ) -> Result<Vec<OrientedEdge>, String> {
        let ((u0, u1), _) = surface.domain();
        let period = u1 - u0;
        let (lo, hi) = uv
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), p| {
                (lo.min(p.x), hi.max(p.x))
            });
        let shift = if lo < u0 || hi > u1 {
            let k = ((u0 - lo) / period).ceil();
            k * period
        } else {
            0.0
        };
        if lo + shift < u0 - 1e-12 || hi + shift > u1 + 1e-12 {
            return Err(format!(
                "an opening loop spans u from {lo} to {hi}, across the seam of a patch \
                 closed in u over [{u0}, {u1}]: not written yet"
            ));
        }
        let mut pcurve: Vec<DVec2> = uv.iter().map(|p| DVec2::new(p.x + shift, p.y)).collect();
        pcurve.push(pcurve[0]);
        let area: f64 = pcurve.windows(2).map(|w| w[0].perp_dot(w[1])).sum();
        let uses = Self::along(edges, &pcurve);
        Ok(if (area > 0.0) == outer {
            uses
        } else {
            Self::against(uses)
        })
    }

    /// The uses of a loop that goes round the host's pole, replacing the pole
    /// side (`pole_at_start`: the side v = v0), from the seam sample `split`
    /// round to it again, in the direction the face's outer loop runs there.
    fn round_pole(
        surface: &NurbsSurface,
        edges: &LoopEdges,
        curve: &IntersectionLoop,
        split: usize,
        pole_at_start: bool,
    ) -> Vec<OrientedEdge> {
        let ((u0, u1), _) = surface.domain();
        let period = u1 - u0;
        let turns = f64::from(curve.host_turns(surface));
        let n = curve.host_uv.len();
        let u = |k: usize| {
            if k == n {
                curve.host_uv[0].x + turns * period
            } else {
                curve.host_uv[k].x
            }
        };
        let v = |k: usize| curve.host_uv[k % n].y;
        let start = if turns > 0.0 { u0 } else { u1 };
        let end = if turns > 0.0 { u1 } else { u0 };
        let shift = start - u(split);
        let mut uses: Vec<OrientedEdge> = edges
            .parts
            .iter()
            .map(|&(edge, from, to)| {
                // Samples from the seam sample on keep their place; those before
                // it come one turn later.
                let wrap = if from < split { turns * period } else { 0.0 };
                let mut pcurve: Vec<DVec2> = (from..=to)
                    .map(|k| DVec2::new(u(k) + shift + wrap, v(k)))
                    .collect();
                if from == split {
                    pcurve[0].x = start;
                }
                if to == split || (split == 0 && to == n) {
                    pcurve.last_mut().expect("a sample").x = end;
                }
                OrientedEdge {
                    edge,
                    forward: true,
                    pcurve,
                }
            })
            .collect();
        // In loop order from the seam sample.
        uses.sort_by_key(|e| usize::from(e.pcurve[0].x != start));
        let increasing = turns > 0.0;
        if increasing == pole_at_start {
            uses
        } else {
            Self::against(uses)
        }
    }

    /// The arcs of a hole across the seam, between consecutive seam samples:
    /// `(near u1, v where the outer loop meets it, v where it leaves, uses)`,
    /// the uses running the way the face's outer loop does (up the u1 side,
    /// down the u0 side).
    #[expect(clippy::type_complexity, reason = "a private tuple read right away")]
    fn seam_arcs(
        surface: &NurbsSurface,
        edges: &LoopEdges,
        uv: &[DVec2],
        seam: &[usize],
    ) -> Result<Vec<(bool, f64, f64, Vec<OrientedEdge>)>, String> {
        let ((u0, u1), _) = surface.domain();
        let period = u1 - u0;
        let n = uv.len();
        let at = |k: usize| uv[k % n];
        let mut arcs = Vec::new();
        for (i, &from) in seam.iter().enumerate() {
            let to = if i + 1 < seam.len() {
                seam[i + 1]
            } else {
                seam[0] + n
            };
            // The arc's samples from..=to (indices past n wrap round).
            let inner: Vec<f64> = (from + 1..to).map(|k| at(k).x).collect();
            let Some(&middle) = inner.get(inner.len() / 2) else {
                return Err("an arc of the opening between two seam samples has no sample".into());
            };
            let shift = ((u0 + 0.5 * period - middle) / period).round() * period;
            let near_u1 =
                (inner.iter().sum::<f64>() / inner.len() as f64 + shift) > u0 + 0.5 * period;
            let edge_u = if near_u1 { u1 } else { u0 };
            let mut uses = Vec::new();
            for &(edge, a, b) in &edges.parts {
                // Parts within from..=to, by their place in the unrolled order.
                let (a2, b2) = if a < from { (a + n, b + n) } else { (a, b) };
                if a2 >= from && b2 <= to {
                    let mut pcurve: Vec<DVec2> = (a2..=b2)
                        .map(|k| {
                            let p = at(k);
                            DVec2::new(p.x + shift, p.y)
                        })
                        .collect();
                    if a2 == from {
                        pcurve[0].x = edge_u;
                    }
                    if b2 == to {
                        pcurve.last_mut().expect("a sample").x = edge_u;
                    }
                    uses.push((
                        a2,
                        OrientedEdge {
                            edge,
                            forward: true,
                            pcurve,
                        },
                    ));
                }
            }
            uses.sort_by_key(|u| u.0);
            let uses: Vec<OrientedEdge> = uses.into_iter().map(|u| u.1).collect();
            if uses
                .iter()
                .any(|e| e.pcurve.iter().any(|p| p.x < u0 - 1e-9 || p.x > u1 + 1e-9))
            {
                return Err("an arc of the opening leaves the patch's domain".into());
            }
            let (v_from, v_to) = (at(from).y, at(to).y);
            // Up the u1 side: from the lower end; down the u0 side: from the upper.
            let along = if near_u1 {
                v_from < v_to
            } else {
                v_from > v_to
            };
            let uses = if along { uses } else { Self::against(uses) };
            let (enter, leave) = if along {
                (v_from, v_to)
            } else {
                (v_to, v_from)
            };
            arcs.push((near_u1, enter, leave, uses));
        }
        Ok(arcs)
    }

    /// A pad round its host's pole: the band between its outer loop and the
    /// neck's, both going round the pole, joined by the seam between their
    /// seam samples: one outer loop, no hole.
    fn pad_round_pole(
        &mut self,
        surface: &NurbsSurface,
        pad: (&LoopEdges, &IntersectionLoop),
        neck: (&LoopEdges, &IntersectionLoop),
    ) -> Result<Loops, String> {
        let ((u0, u1), (v0, _)) = surface.domain();
        let pole_at_start = self.degenerate(&surface.isocurve_v(v0));
        // The loop nearer the pole is the neck's.
        let (bottom, top) = if pole_at_start {
            (neck, pad)
        } else {
            (pad, neck)
        };
        let split = |curve: &IntersectionLoop| {
            seam_index(&curve.host_uv, surface)
                .ok_or_else(|| "a loop round the pole has no sample on the seam".to_string())
        };
        let (bottom_split, top_split) = (split(bottom.1)?, split(top.1)?);
        let v_bottom = bottom.1.host_uv[bottom_split].y;
        let v_top = top.1.host_uv[top_split].y;
        let mut outer = Self::round_pole(surface, bottom.0, bottom.1, bottom_split, true);
        let piece = |c: NurbsCurve| -> Result<NurbsCurve, String> {
            let (low, high) = (v_bottom.min(v_top), v_bottom.max(v_top));
            let (_, upper) = c.split_at(low).map_err(|e| e.to_string())?;
            let (lower, _) = upper.split_at(high).map_err(|e| e.to_string())?;
            Ok(lower)
        };
        let right = piece(surface.isocurve_u(u1))?;
        outer.push(self.side_use(right, DVec2::new(u1, v_bottom), DVec2::new(u1, v_top), true));
        outer.extend(Self::round_pole(surface, top.0, top.1, top_split, false));
        let left = piece(surface.isocurve_u(u0))?;
        outer.push(self.side_use(left, DVec2::new(u0, v_bottom), DVec2::new(u0, v_top), false));
        Ok((outer, Vec::new()))
    }

    /// A patch's loops: its rectangle's sides (poles left out), the bottom
    /// replaced by the neck–host loop on a neck, and its holes.
    fn patch_face(
        &mut self,
        surface: &NurbsSurface,
        bottom: Option<&(LoopEdges, &IntersectionLoop)>,
        round: Option<&(LoopEdges, &IntersectionLoop, usize)>,
        holes: &[Hole],
        across: &[SeamHole],
    ) -> Result<Loops, String> {
        let ((u0, u1), (v0, v1)) = surface.domain();
        let mut outer = Vec::with_capacity(4);
        // The v-range of the two u-sides: cut by a trimmed bottom or a loop
        // round a pole.
        let (mut v_low, mut v_high) = (v0, v1);
        let mut top_uses = None;
        if let Some((edges, curve, split)) = round {
            let pole_at_start = self.degenerate(&surface.isocurve_v(v0));
            if !pole_at_start && !self.degenerate(&surface.isocurve_v(v1)) {
                return Err("an opening goes round the patch's axis, which has no pole".into());
            }
            let v_seam = curve.host_uv[*split % curve.host_uv.len()].y;
            let uses = Self::round_pole(surface, edges, curve, *split, pole_at_start);
            if pole_at_start {
                v_low = v_seam;
                outer.extend(uses);
            } else {
                v_high = v_seam;
                top_uses = Some(uses);
            }
        }
        match bottom {
            Some((edges, curve)) => {
                let first = curve.neck_uv[0];
                if (first.x - u0).abs() > 1e-12 * (u1 - u0).max(1.0) {
                    return Err(format!(
                        "the neck loop starts at u = {}, not at the neck's seam u = {u0}",
                        first.x
                    ));
                }
                v_low = first.y;
                let mut pcurve = curve.neck_uv.clone();
                pcurve[0].x = u0;
                pcurve.push(DVec2::new(u1, first.y));
                outer.extend(Self::along(edges, &pcurve));
            }
            None if round.is_some() && v_low > v0 => {}
            None => {
                let c = surface.isocurve_v(v0);
                if !self.degenerate(&c) {
                    outer.push(self.side_use(c, DVec2::new(u0, v0), DVec2::new(u1, v0), true));
                }
            }
        }
        // Arcs of holes across the seam, each with its v-range on the seam:
        // those just inside u1 interrupt the right side, those just inside u0
        // the left one.
        let mut right_arcs: Vec<(f64, f64, Vec<OrientedEdge>)> = Vec::new();
        let mut left_arcs: Vec<(f64, f64, Vec<OrientedEdge>)> = Vec::new();
        for (edges, uv, seam) in across {
            for arc in Self::seam_arcs(surface, edges, uv, seam)? {
                if arc.0 {
                    right_arcs.push((arc.1, arc.2, arc.3));
                } else {
                    left_arcs.push((arc.1, arc.2, arc.3));
                }
            }
        }
        right_arcs.sort_by(|a, b| a.0.total_cmp(&b.0));
        left_arcs.sort_by(|a, b| b.0.total_cmp(&a.0));
        let piece = |c: &NurbsCurve, low: f64, high: f64| -> Result<NurbsCurve, String> {
            let mut c = c.clone();
            if low > v0 {
                c = c
                    .split_at(low)
                    .map(|(_, upper)| upper)
                    .map_err(|e| e.to_string())?;
            }
            if high < v1 {
                c = c
                    .split_at(high)
                    .map(|(lower, _)| lower)
                    .map_err(|e| e.to_string())?;
            }
            Ok(c)
        };
        // Up the right side, round its arcs.
        let right_curve = surface.isocurve_u(u1);
        let mut v = v_low;
        for (low, high, uses) in right_arcs {
            let c = piece(&right_curve, v, low)?;
            if !self.degenerate(&c) {
                outer.push(self.side_use(c, DVec2::new(u1, v), DVec2::new(u1, low), true));
            }
            outer.extend(uses);
            v = high;
        }
        let right = piece(&right_curve, v, v_high)?;
        if !self.degenerate(&right) {
            outer.push(self.side_use(right, DVec2::new(u1, v), DVec2::new(u1, v_high), true));
        }
        match top_uses {
            Some(uses) => outer.extend(uses),
            None => {
                let top = surface.isocurve_v(v1);
                if !self.degenerate(&top) {
                    outer.push(self.side_use(top, DVec2::new(u0, v1), DVec2::new(u1, v1), false));
                }
            }
        }
        // Down the left side, round its arcs.
        let left_curve = surface.isocurve_u(u0);
        let mut v = v_high;
        for (high, low, uses) in left_arcs {
            let c = piece(&left_curve, high, v)?;
            if !self.degenerate(&c) {
                outer.push(self.side_use(c, DVec2::new(u0, high), DVec2::new(u0, v), false));
            }
            outer.extend(uses);
            v = low;
        }
        let left = piece(&left_curve, v_low, v)?;
        if !self.degenerate(&left) {
            outer.push(self.side_use(left, DVec2::new(u0, v_low), DVec2::new(u0, v), false));
        }
        let mut inner = Vec::with_capacity(holes.len());
        for (edges, uv) in holes {
            inner.push(self.hole_use(surface, edges, uv, false)?);
        }
        Ok((outer, inner))
    }

    /// Whether a side collapses to a point (a pole).
    fn degenerate(&self, curve: &NurbsCurve) -> bool {
        let points = curve.control_points();
        points
            .iter()
            .all(|p| p.distance(points[0]) <= self.tolerance)
    }
}
