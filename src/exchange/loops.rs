//! The loops bounding each face, gathered for one vessel: vertices matched
//! within the vessel's match distance (per group: the envelope, each support),
//! exact sides shared between neighbouring faces, opening loops as sampled
//! edges (fitted once every face is bounded, in `fit`), and the uses of those edges with their pcurves: a hole, an arc of a
//! hole across a closed patch's seam, a loop round a pole, a pad's annulus
//! (on its surface with the seam moved half a turn where its loops cross it).

use rustc_hash::FxHashMap;

use glam::{DAffine3, DVec2, DVec3};

use super::brep::{Edge, EdgeCurve, OrientedEdge};
use super::seam::seam_moved;
use crate::mesh::closed_in_u;
use crate::nurbs::intersect::IntersectionLoop;
use crate::nurbs::{KnotVector, NurbsCurve, NurbsSurface, Side};

/// The index of the sample of `uv` on `surface`'s u-seam.
pub(super) fn seam_index(uv: &[DVec2], surface: &NurbsSurface) -> Option<usize> {
    let ((u0, u1), _) = surface.domain();
    let period = u1 - u0;
    uv.iter().position(|p| {
        let r = (p.x - u0) / period;
        (r - r.round()).abs() < 1e-9
    })
}

/// Vertices and edges being gathered for one vessel.
pub(super) struct Builder {
    /// Match distance, mm.
    pub(super) tolerance: f64,
    pub(super) vertices: Vec<DVec3>,
    /// Vertices by group and cell of the match distance's size.
    pub(super) vertex_cells: FxHashMap<(usize, glam::I64Vec3), Vec<usize>>,
    /// Faces of one group share vertices and edges: 0 for the envelope (parts
    /// and nozzles), 1 + the node's index for a support.
    pub(super) group: usize,
    pub(super) edges: Vec<Edge>,
    /// Exact edges by their (smaller, larger) vertex pair.
    pub(super) by_ends: FxHashMap<(usize, usize), Vec<usize>>,
    /// Each loop edge with the parameters its fit must keep as nodes.
    pub(super) loop_breaks: Vec<(usize, Vec<f64>)>,
}

/// The edges of one opening loop: `(edge, first sample, last sample)` in loop
/// order, the last sample of the last part being the first sample again.
#[derive(Clone, Debug)]
pub(super) struct LoopEdges {
    pub(super) parts: Vec<(usize, usize, usize)>,
}

/// A hole: its loop's edges and (u, v) on the face.
pub(super) type Hole = (LoopEdges, Vec<DVec2>);

/// A hole across the seam: its loop's edges, (u, v) on the face and the
/// indices of its samples on the seam.
pub(super) type SeamHole = (LoopEdges, Vec<DVec2>, Vec<usize>);

/// A notch (`notch`: a piece of an opening loop across the seam between two
/// host patches) in its face's outer loop.
#[derive(Clone, Debug)]
pub(super) struct NotchUse {
    /// The side it bites into: [`Side::VMin`] or [`Side::VMax`].
    pub(super) side: Side,
    /// The u where it leaves the side and where it comes back, smaller first.
    pub(super) u: (f64, f64),
    /// The loop's edges along the notch, in the direction the face's outer
    /// loop runs there (increasing u on the v-min side, decreasing on the
    /// v-max side).
    pub(super) uses: Vec<OrientedEdge>,
}

/// A face's outer loop and holes.
pub(super) type Loops = (Vec<OrientedEdge>, Vec<Vec<OrientedEdge>>);

impl Builder {
    /// The vertex at `p`, added if no vertex lies within the match distance.
    /// Only vertices of the current [`group`](Self::group) are matched; the
    /// first one within the distance (lowest index) is taken.
    pub(super) fn vertex(&mut self, p: DVec3) -> usize {
        let cell = (p / self.tolerance).floor().as_i64vec3();
        let mut found: Option<usize> = None;
        for dx in -1..=1 {
            for dy in -1..=1 {
                for dz in -1..=1 {
                    let key = (self.group, cell + glam::I64Vec3::new(dx, dy, dz));
                    for &i in self
                        .vertex_cells
                        .get(&key)
                        .map(Vec::as_slice)
                        .unwrap_or(&[])
                    {
                        if self.vertices[i].distance(p) <= self.tolerance
                            && found.is_none_or(|f| i < f)
                        {
                            found = Some(i);
                        }
                    }
                }
            }
        }
        if let Some(i) = found {
            return i;
        }
        self.vertices.push(p);
        let i = self.vertices.len() - 1;
        self.vertex_cells
            .entry((self.group, cell))
            .or_default()
            .push(i);
        i
    }

    /// The edges through a loop's samples, mapped from the host part's frame
    /// into the vessel's: one closed edge, or several split at the samples
    /// `splits` (on the seam of a host the loop goes round or crosses). Each
    /// is a degree-1 [`EdgeCurve::Loop`] over the neck's parameter (one period
    /// on at the loop's closing sample), `neck_knots` being the distinct knots
    /// of the neck's u (its domain's ends first and last), whose interior ones
    /// are kept as breaks for the fit.
    pub(super) fn loop_edges(
        &mut self,
        curve: &IntersectionLoop,
        host_frame: &DAffine3,
        splits: &[usize],
        neck_knots: &[f64],
    ) -> Result<LoopEdges, String> {
        let mut points: Vec<DVec3> = curve
            .points
            .iter()
            .map(|p| host_frame.transform_point3(*p))
            .collect();
        points.push(points[0]);
        let n = curve.points.len();
        let (first, last) = (neck_knots[0], neck_knots[neck_knots.len() - 1]);
        let period = last - first;
        let mut params: Vec<f64> = curve.neck_uv.iter().map(|p| p.x).collect();
        params.push(params[0] + period);
        let breaks: Vec<f64> = (0..2)
            .flat_map(|turn| neck_knots.iter().map(move |k| k + f64::from(turn) * period))
            .collect();
        let mut bounds: Vec<usize> = vec![0];
        bounds.extend(splits.iter().copied().filter(|&k| k > 0 && k < n));
        bounds.push(n);
        let mut parts = Vec::with_capacity(bounds.len() - 1);
        for w in bounds.windows(2) {
            let (from, to) = (w[0], w[1]);
            let start = self.vertex(points[from]);
            let end = self.vertex(points[to]);
            let mut knots = Vec::with_capacity(to - from + 3);
            knots.push(params[from]);
            knots.extend_from_slice(&params[from..=to]);
            knots.push(params[to]);
            let line = KnotVector::try_new(1, knots)
                .and_then(|k| NurbsCurve::try_polynomial(k, &points[from..=to]))
                .map_err(|e| format!("an opening loop's samples do not make a curve: {e}"))?;
            self.edges.push(Edge {
                start,
                end,
                curve: EdgeCurve::Loop(line),
            });
            let edge = self.edges.len() - 1;
            self.loop_breaks.push((edge, breaks.clone()));
            parts.push((edge, from, to));
        }
        Ok(LoopEdges { parts })
    }

    /// The uses of a loop's edges along the loop's order, each with its slice
    /// of `pcurve` (one point per sample, the first repeated at the end).
    pub(super) fn along(edges: &LoopEdges, pcurve: &[DVec2]) -> Vec<OrientedEdge> {
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
    pub(super) fn against(mut uses: Vec<OrientedEdge>) -> Vec<OrientedEdge> {
        uses.reverse();
        uses.iter_mut().for_each(|e| e.forward = !e.forward);
        uses
    }

    /// The use of the exact edge along `curve` (from `uv_start` at the start of
    /// its range to `uv_end`), the edge shared with an earlier side whose curve
    /// coincides. `along` tells whether the loop runs along the curve.
    pub(super) fn side_use(
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
    pub(super) fn hole_use(
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

    /// A face between an outer loop and one hole on `surface`, each given by its
    /// edges and (u, v): the surface as it is, or with its seam moved half a
    /// turn ([`seam_moved`]) when the loops cross its seam.
    pub(super) fn annulus(
        &mut self,
        surface: &NurbsSurface,
        outer: (&LoopEdges, &[DVec2]),
        hole: (&LoopEdges, &[DVec2]),
    ) -> Result<(NurbsSurface, Loops), String> {
        let on = |builder: &mut Self, s: &NurbsSurface| -> Result<Loops, String> {
            let o = builder.hole_use(s, outer.0, outer.1, true)?;
            let h = builder.hole_use(s, hole.0, hole.1, false)?;
            Ok((o, vec![h]))
        };
        match on(self, surface) {
            Ok(loops) => Ok((surface.clone(), loops)),
            Err(_) if closed_in_u(surface) => {
                let moved = seam_moved(surface)?;
                let loops = on(self, &moved)?;
                Ok((moved, loops))
            }
            Err(e) => Err(e),
        }
    }

    /// The uses of a loop that goes round the host's pole, replacing the pole
    /// side (`pole_at_start`: the side v = v0), from the seam sample `split`
    /// round to it again, in the direction the face's outer loop runs there.
    pub(super) fn round_pole(
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
    pub(super) fn seam_arcs(
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
    pub(super) fn pad_round_pole(
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
    pub(super) fn patch_face(
        &mut self,
        surface: &NurbsSurface,
        bottom: Option<&(LoopEdges, &IntersectionLoop)>,
        round: Option<&(LoopEdges, &IntersectionLoop, usize)>,
        holes: &[Hole],
        across: &[SeamHole],
        notches: &[NotchUse],
    ) -> Result<Loops, String> {
        let ((u0, u1), (v0, v1)) = surface.domain();
        let on =
            |side: Side| -> Vec<&NotchUse> { notches.iter().filter(|n| n.side == side).collect() };
        let (mut bottom_notches, mut top_notches) = (on(Side::VMin), on(Side::VMax));
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
                    self.notched_side(
                        &mut outer,
                        &c,
                        v0,
                        std::mem::take(&mut bottom_notches),
                        true,
                    )?;
                }
            }
        }
        if !bottom_notches.is_empty() {
            return Err(
                "an opening across the patch's v-min seam, which is trimmed or a pole: \
                        not written yet"
                    .into(),
            );
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
                    self.notched_side(
                        &mut outer,
                        &top,
                        v1,
                        std::mem::take(&mut top_notches),
                        false,
                    )?;
                }
            }
        }
        if !top_notches.is_empty() {
            return Err(
                "an opening across the patch's v-max seam, which is trimmed or a pole: \
                        not written yet"
                    .into(),
            );
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

    /// The uses of a v-side `curve` (an isocurve at `v`, over the surface's
    /// u-range) cut at its notches, with the notches' uses between its
    /// pieces, in the direction of the face's outer loop: increasing u along
    /// the v-min side (`bottom`), decreasing along the v-max side.
    pub(super) fn notched_side(
        &mut self,
        outer: &mut Vec<OrientedEdge>,
        curve: &NurbsCurve,
        v: f64,
        mut notches: Vec<&NotchUse>,
        bottom: bool,
    ) -> Result<(), String> {
        let (u0, u1) = curve.domain();
        let piece = |low: f64, high: f64| -> Result<NurbsCurve, String> {
            let mut c = curve.clone();
            if low > u0 {
                c = c
                    .split_at(low)
                    .map(|(_, upper)| upper)
                    .map_err(|e| e.to_string())?;
            }
            if high < u1 {
                c = c
                    .split_at(high)
                    .map(|(lower, _)| lower)
                    .map_err(|e| e.to_string())?;
            }
            Ok(c)
        };
        // The pieces between notches, increasing u.
        notches.sort_by(|a, b| a.u.0.total_cmp(&b.u.0));
        let mut pieces = Vec::with_capacity(notches.len() + 1);
        let mut u = u0;
        for notch in &notches {
            if notch.u.0 < u {
                return Err("two openings' notches overlap on a patch's side".into());
            }
            pieces.push((u, notch.u.0));
            u = notch.u.1;
        }
        pieces.push((u, u1));
        let side = |builder: &mut Self,
                    outer: &mut Vec<OrientedEdge>,
                    (low, high): (f64, f64)|
         -> Result<(), String> {
            if high > low {
                let c = piece(low, high)?;
                outer.push(builder.side_use(c, DVec2::new(low, v), DVec2::new(high, v), bottom));
            }
            Ok(())
        };
        if bottom {
            for (k, notch) in notches.iter().enumerate() {
                side(self, outer, pieces[k])?;
                outer.extend(notch.uses.iter().cloned());
            }
            side(self, outer, pieces[notches.len()])
        } else {
            for (k, notch) in notches.iter().enumerate().rev() {
                side(self, outer, pieces[k + 1])?;
                outer.extend(notch.uses.iter().cloned());
            }
            side(self, outer, pieces[0])
        }
    }

    /// Whether a side collapses to a point (a pole).
    pub(super) fn degenerate(&self, curve: &NurbsCurve) -> bool {
        let points = curve.control_points();
        points
            .iter()
            .all(|p| p.distance(points[0]) <= self.tolerance)
    }
}
