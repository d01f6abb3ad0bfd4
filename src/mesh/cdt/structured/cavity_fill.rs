//! One cavity of a structured mesh triangulated to its holes, without a
//! triangulation search: a zip for one hole, a sweep (`sweep`) for several,
//! ear clipping when neither gives a cover, then Lawson's flips to the
//! constrained Delaunay triangulation.
//!
//! Sits inside `cavity::fill`, which cuts the cavities out of the rings' lattice
//! and hands each one here as its boundary (chain vertices, counter-clockwise)
//! and its holes (loop vertices, clockwise, as the region holds them). The
//! cavity's vertices all exist already; no vertex is added. Every result is
//! checked to cover the cavity less its holes exactly once: each triangle
//! strictly counter-clockwise in (u, v) and the loops as the triangles'
//! boundary. The caller falls back to spade when no way gives one.

use glam::DVec2;

use crate::mesh::cdt::flip::{orient, strictly_ccw};
use crate::mesh::cdt::metric::Metric;
use crate::mesh::cdt::trimesh::TriMesh;
use zip::Walk;

#[cfg(test)]
mod tests;
mod zip;

thread_local! {
    /// Each thread's ear clipper and Lawson flipper, kept between cavities: both
    /// keep scratch buffers sized to the largest cavity seen (allocating them
    /// afresh was a good part of a small cavity's time); results do not depend
    /// on what they held before.
    static EARCUT: std::cell::RefCell<earcut::Earcut<f64>> =
        std::cell::RefCell::new(earcut::Earcut::new());
    static REFINER: std::cell::RefCell<earcut::Refiner> =
        std::cell::RefCell::new(earcut::Refiner::new());
}

/// A cavity triangle: its mesh vertices (counter-clockwise in (u, v)) and which
/// of its edges are hole segments.
pub(super) type Triangle = ([u32; 3], [bool; 3]);

/// A cavity's loops in one local numbering: its boundary first, then each hole;
/// `next` follows every loop in the direction that keeps the cavity on its left
/// (the boundary counter-clockwise, the holes clockwise).
pub(super) struct Loops {
    /// Local index → mesh vertex index.
    map: Vec<u32>,
    /// Local index → the next vertex of its loop.
    next: Vec<u32>,
    /// First local index of each hole.
    starts: Vec<u32>,
    /// Vertex positions in the cavity's size metric (the chart).
    chart: Vec<[f64; 2]>,
}

impl Loops {
    /// The loops of a cavity with boundary `outer` and holes `holes` (each a run
    /// of consecutive mesh vertices, clockwise); `chart` maps (u, v) to the
    /// cavity's size metric. `None` when a loop has fewer than three vertices.
    #[cfg(test)]
    pub fn new(
        mesh: &TriMesh,
        outer: &[u32],
        holes: impl IntoIterator<Item = std::ops::Range<u32>>,
        metric: &Metric,
    ) -> Option<Self> {
        let holes: Vec<_> = holes.into_iter().collect();
        let (map, starts) = numbering(outer, &holes);
        Self::numbered(mesh, map, starts, metric)
    }

    /// [`new`](Self::new) from the cavity's local numbering ([`numbering`]).
    pub fn numbered(
        mesh: &TriMesh,
        map: Vec<u32>,
        starts: Vec<u32>,
        metric: &Metric,
    ) -> Option<Self> {
        let n = map.len() as u32;
        let mut next: Vec<u32> = (1..=n).collect();
        let mut first = 0u32;
        for &end in starts.iter().chain([&n]) {
            if end < first + 3 {
                return None;
            }
            next[end as usize - 1] = first;
            first = end;
        }
        let chart = map
            .iter()
            .map(|&k| metric.chart(mesh.verts[k as usize].uv).to_array())
            .collect();
        Some(Self {
            map,
            next,
            starts,
            chart,
        })
    }

    /// The mesh vertex of each local index.
    pub fn map(&self) -> &[u32] {
        &self.map
    }

    /// Whether `a → b` is a loop segment, in its loop's direction.
    fn segment(&self, a: u32, b: u32) -> bool {
        self.next[a as usize] == b
    }

    /// Whether local vertex `a` is a hole's.
    fn on_hole(&self, a: u32) -> bool {
        self.starts.first().is_some_and(|&s| a >= s)
    }

    /// The (u, v) of local vertex `k`.
    fn uv(&self, mesh: &TriMesh, k: u32) -> DVec2 {
        mesh.verts[self.map[k as usize] as usize].uv
    }

    /// The one hole zipped to the boundary, or `None` when the cavity has not
    /// exactly one hole or no zip has all its triangles strictly
    /// counter-clockwise: [`Self::zip_greedy`], or when that gets stuck (a hole
    /// far from convex) the zip with the least total diagonal length among all
    /// valid ones, by dynamic programming over the walk's positions.
    pub fn zip(&self, mesh: &TriMesh) -> Option<Vec<[u32; 3]>> {
        let walk = Walk::new(self, mesh)?;
        walk.greedy().or_else(|| walk.least())
    }

    /// The one hole zipped to the boundary greedily: both loops walked
    /// counter-clockwise from the boundary's first vertex and the hole vertex
    /// nearest it (in the size metric, not in 3D: on a course, whose triangles
    /// may run far along the axis but only a step round it, that pairs each hole
    /// vertex with the chain vertices above or below it, as the chordal
    /// tolerance wants), taking at each step the shorter diagonal among the
    /// strictly counter-clockwise triangles. With every triangle
    /// counter-clockwise and the two loops as the zip's boundary, the triangles
    /// cover the ring between them exactly once. `None` when it gets stuck.
    #[cfg(test)]
    pub fn zip_greedy(&self, mesh: &TriMesh) -> Option<Vec<[u32; 3]>> {
        Walk::new(self, mesh)?.greedy()
    }

    /// The cavity triangulated by the sweep (`sweep`: pieces monotone round
    /// the course, each walked with a stack) in the chart; `None` unless the
    /// result covers the cavity less its holes exactly once (see
    /// [`Self::cover`]).
    pub fn sweep(&self, mesh: &TriMesh) -> Option<Vec<[u32; 3]>> {
        let tris = super::sweep::triangulate(&self.next, &self.chart)?;
        self.cover(mesh, &tris).then_some(tris)
    }

    /// The cavity triangulated by ear clipping (the `earcut` crate) in the chart,
    /// the boundary as the polygon and the holes as its holes; `None` unless the
    /// result covers the cavity less its holes exactly once (see [`Self::cover`]).
    ///
    /// The chart goes to earcut turned a quarter (its x is the chart's v): earcut
    /// bridges each hole from its least-x vertex and clips ears along the
    /// bridged polygon, so turned it bridges a course's wide, flat holes across
    /// their thin side to the loop below, and its ears come out closer to the
    /// rungs between facing chains that the Delaunay flips end at. Unturned, it
    /// left fans across the cavity's width that took many more flips: when ear
    /// clipping was the way for every cavity of several holes (before the
    /// sweep), turning it took a 100-edit tick at 3 000 vessels from 43.3 to
    /// 39.7 ms of CPU (three alternating runs) and 4 % of its instructions.
    ///
    /// Ear clipping drops a loop vertex lying exactly on the line through its
    /// neighbours (a row's vertices along the cavity's bottom and top); the
    /// triangle on the chord that skips such vertices is fanned back to them from
    /// its third vertex.
    pub fn ears(&self, mesh: &TriMesh) -> Option<Vec<[u32; 3]>> {
        let n = self.map.len();
        let mut local: Vec<u32> = Vec::with_capacity(3 * (n + 2 * self.starts.len()));
        EARCUT.with_borrow_mut(|e| {
            let turned = self.chart.iter().map(|&[x, y]| [y, -x]);
            e.earcut(turned, &self.starts, &mut local);
        });
        let mut used = vec![false; n];
        for &k in &local {
            used[k as usize] = true;
        }
        let uv = |k: u32| self.uv(mesh, k);
        let mut tris: Vec<[u32; 3]> = Vec::with_capacity(n + 2 * self.starts.len());
        for t in local.chunks_exact(3) {
            let mut tri = [t[0], t[1], t[2]];
            if orient(uv(tri[0]), uv(tri[1]), uv(tri[2])) < 0.0 {
                tri.swap(1, 2);
            }
            let skipped = (0..3).find_map(|i| {
                let (a, b) = (tri[i], tri[(i + 1) % 3]);
                let mut between = Vec::new();
                let mut k = self.next[a as usize];
                while k != b && !used[k as usize] && between.len() < n {
                    between.push(k);
                    k = self.next[k as usize];
                }
                (k == b && !between.is_empty()).then_some((i, between))
            });
            match skipped {
                Some((i, between)) => {
                    let (a, b, c) = (tri[i], tri[(i + 1) % 3], tri[(i + 2) % 3]);
                    let chain: Vec<u32> = [a].into_iter().chain(between).chain([b]).collect();
                    tris.extend(chain.windows(2).map(|w| [w[0], w[1], c]));
                }
                None => tris.push(tri),
            }
        }
        self.cover(mesh, &tris).then_some(tris)
    }

    /// Whether `tris` cover the cavity less its holes exactly once: every
    /// triangle strictly counter-clockwise in (u, v), every loop segment an edge
    /// of one triangle in its loop's direction and every other edge shared by
    /// two in opposite directions. The triangles' boundary is then the loops, and
    /// a chain of positively oriented triangles with that boundary covers what
    /// the loops enclose once, whatever ear clipping did with near-degenerate
    /// input.
    fn cover(&self, mesh: &TriMesh, tris: &[[u32; 3]]) -> bool {
        let uv = |k: u32| self.uv(mesh, k);
        let n = self.map.len();
        // The triangles' directed edges by first vertex: vertex a's ends are
        // `ends[first[a]..first[a + 1]]` (a handful each; no hashing).
        let mut first = vec![0u32; n + 1];
        for tri in tris {
            if tri.iter().any(|&k| k as usize >= n)
                || !strictly_ccw(uv(tri[0]), uv(tri[1]), uv(tri[2]))
            {
                return false;
            }
            for &a in tri {
                first[a as usize + 1] += 1;
            }
        }
        for a in 0..n {
            first[a + 1] += first[a];
        }
        let mut ends = vec![0u32; 3 * tris.len()];
        let mut fill = first.clone();
        for tri in tris {
            for i in 0..3 {
                let a = tri[i] as usize;
                ends[fill[a] as usize] = tri[(i + 1) % 3];
                fill[a] += 1;
            }
        }
        let out = |a: u32| &ends[first[a as usize] as usize..first[a as usize + 1] as usize];
        (0..n as u32).all(|a| {
            let ends = out(a);
            // No edge twice; each loop segment once, in its loop's direction;
            // every other edge paired with its reverse.
            ends.iter()
                .enumerate()
                .all(|(i, &b)| !ends[..i].contains(&b) && self.segment(a, b) != out(b).contains(&a))
                && ends.contains(&self.next[a as usize])
        })
    }

    /// `tris` (a valid cover) flipped to Delaunay in the chart by Lawson's flips
    /// (the loop segments, which no other cavity triangle shares, stay), as mesh
    /// triangles with their hole segments fixed. `None` when a flip left a
    /// triangle not strictly counter-clockwise in (u, v).
    #[cfg(test)]
    pub fn finish(&self, mesh: &TriMesh, tris: Vec<[u32; 3]>) -> Option<Vec<Triangle>> {
        let local = self.finish_local(mesh, tris)?;
        Some(
            local
                .iter()
                .map(|&(t, f)| (t.map(|k| self.map[k as usize]), f))
                .collect(),
        )
    }

    /// [`finish`](Self::finish) in the cavity's local numbering (its boundary's
    /// vertices, then each hole's, as [`new`](Self::new) takes them).
    pub fn finish_local(&self, mesh: &TriMesh, tris: Vec<[u32; 3]>) -> Option<Vec<Triangle>> {
        let mut flat: Vec<u32> = tris.into_iter().flatten().collect();
        REFINER.with_borrow_mut(|r| r.refine(&mut flat, &self.chart));
        let uv = |k: u32| self.uv(mesh, k);
        flat.chunks_exact(3)
            .map(|t| {
                let tri = [t[0], t[1], t[2]];
                strictly_ccw(uv(tri[0]), uv(tri[1]), uv(tri[2])).then(|| {
                    // Only the holes' segments stay fixed: the cavity's boundary
                    // is interior to the patch (or a side, fixed by the caller).
                    let fixed = std::array::from_fn(|i| {
                        let (a, b) = (tri[i], tri[(i + 1) % 3]);
                        self.segment(a, b) && self.on_hole(a)
                    });
                    (tri, fixed)
                })
            })
            .collect()
    }
}

/// A cavity's local numbering: local index → mesh vertex (the boundary's
/// vertices `outer`, then each hole's run), and where each hole starts in it.
pub(super) fn numbering(outer: &[u32], holes: &[std::ops::Range<u32>]) -> (Vec<u32>, Vec<u32>) {
    let mut map: Vec<u32> =
        Vec::with_capacity(outer.len() + holes.iter().map(|h| h.len()).sum::<usize>());
    map.extend_from_slice(outer);
    let mut starts = Vec::with_capacity(holes.len());
    for hole in holes {
        starts.push(map.len() as u32);
        map.extend(hole.clone());
    }
    (map, starts)
}
