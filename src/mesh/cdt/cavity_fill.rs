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

use super::flip::{orient, strictly_ccw};
use super::metric::Metric;
use super::trimesh::TriMesh;

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

/// The zip's walk round a cavity with one hole: position `i` on the boundary,
/// `j` on the hole (counter-clockwise from the vertex nearest the boundary's
/// first), each step one triangle.
struct Walk<'a> {
    loops: &'a Loops,
    mesh: &'a TriMesh,
    /// Boundary and hole vertex counts.
    np: usize,
    nq: usize,
    /// The hole's first local index and the walk's first hole vertex (an
    /// offset in the hole's own, clockwise, order).
    start: u32,
    q0: usize,
}

impl<'a> Walk<'a> {
    fn new(loops: &'a Loops, mesh: &'a TriMesh) -> Option<Self> {
        let &[start] = &loops.starts[..] else {
            return None;
        };
        let np = start as usize;
        let nq = loops.map.len() - np;
        let mut walk = Self {
            loops,
            mesh,
            np,
            nq,
            start,
            q0: 0,
        };
        walk.q0 = (0..nq).min_by(|&a, &b| {
            let (a, b) = (start + a as u32, start + b as u32);
            walk.distance(a, 0).total_cmp(&walk.distance(b, 0))
        })?;
        Some(walk)
    }

    fn distance(&self, a: u32, b: u32) -> f64 {
        let chart = |k: u32| DVec2::from_array(self.loops.chart[k as usize]);
        chart(a).distance(chart(b))
    }

    fn uv(&self, k: u32) -> DVec2 {
        self.loops.uv(self.mesh, k)
    }

    /// The boundary's `i`-th vertex.
    fn p(&self, i: usize) -> u32 {
        (i % self.np) as u32
    }

    /// The hole's `j`-th vertex counter-clockwise: its loop walked backwards.
    fn q(&self, j: usize) -> u32 {
        self.start + ((self.q0 + self.nq - j % self.nq) % self.nq) as u32
    }

    /// The triangle of the step from (i, j) along the boundary (`advance_p`) or
    /// the hole.
    fn triangle(&self, i: usize, j: usize, advance_p: bool) -> [u32; 3] {
        if advance_p {
            [self.p(i), self.p(i + 1), self.q(j)]
        } else {
            [self.p(i), self.q(j + 1), self.q(j)]
        }
    }

    /// Whether the walk may take that step: a loop left to walk and the
    /// triangle strictly counter-clockwise.
    fn can(&self, i: usize, j: usize, advance_p: bool) -> bool {
        let left = if advance_p { i < self.np } else { j < self.nq };
        left && {
            let [a, b, c] = self.triangle(i, j, advance_p).map(|k| self.uv(k));
            strictly_ccw(a, b, c)
        }
    }

    /// The step's triangle and its new diagonal's length (the edge from the
    /// vertex it advanced to).
    fn step(&self, i: usize, j: usize, advance_p: bool) -> ([u32; 3], f64) {
        let tri = self.triangle(i, j, advance_p);
        let (a, b) = if advance_p { (1, 2) } else { (0, 1) };
        (tri, self.distance(tri[a], tri[b]))
    }

    fn greedy(&self) -> Option<Vec<[u32; 3]>> {
        let mut out = Vec::with_capacity(self.np + self.nq);
        let (mut i, mut j) = (0usize, 0usize);
        while i < self.np || j < self.nq {
            let advance_p = match (self.can(i, j, true), self.can(i, j, false)) {
                (true, true) => self.step(i, j, true).1 <= self.step(i, j, false).1,
                (true, false) => true,
                (false, true) => false,
                (false, false) => return None,
            };
            out.push(self.step(i, j, advance_p).0);
            if advance_p {
                i += 1;
            } else {
                j += 1;
            }
        }
        Some(out)
    }

    fn least(&self) -> Option<Vec<[u32; 3]>> {
        let (np, nq) = (self.np, self.nq);
        let width = nq + 1;
        let mut cost = vec![f64::INFINITY; (np + 1) * width];
        // Whether (i, j) was reached by advancing on the boundary (else the hole).
        let mut from_p = vec![false; (np + 1) * width];
        cost[0] = 0.0;
        for i in 0..=np {
            for j in 0..=nq {
                let c = cost[i * width + j];
                if !c.is_finite() {
                    continue;
                }
                for (advance_p, at) in [(true, (i + 1) * width + j), (false, i * width + j + 1)] {
                    if !self.can(i, j, advance_p) {
                        continue;
                    }
                    let next = c + self.step(i, j, advance_p).1;
                    if next < cost[at] {
                        (cost[at], from_p[at]) = (next, advance_p);
                    }
                }
            }
        }
        if !cost[np * width + nq].is_finite() {
            return None;
        }
        let mut out = Vec::with_capacity(np + nq);
        let (mut i, mut j) = (np, nq);
        while i > 0 || j > 0 {
            let advance_p = from_p[i * width + j];
            if advance_p {
                i -= 1;
            } else {
                j -= 1;
            }
            out.push(self.step(i, j, advance_p).0);
        }
        out.reverse();
        Some(out)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::cdt::patch::Vertex;
    use glam::DVec3;

    /// A mesh of bare (u, v) vertices.
    fn mesh_of(uvs: impl IntoIterator<Item = DVec2>) -> TriMesh {
        let mut mesh = TriMesh::default();
        mesh.verts.extend(uvs.into_iter().map(|uv| Vertex {
            uv,
            point: DVec3::new(uv.x, uv.y, 0.0),
            normal: DVec3::Z,
            metric: Metric::UNSET,
            pole: false,
        }));
        mesh
    }

    const ISOTROPIC: Metric = Metric {
        uu: 1.0,
        uv: 0.0,
        vv: 1.0,
    };

    /// The loops of a cavity whose boundary is the mesh's first `np` vertices
    /// and whose holes are `holes`.
    fn loops_of(
        mesh: &TriMesh,
        np: u32,
        holes: impl IntoIterator<Item = std::ops::Range<u32>>,
        metric: &Metric,
    ) -> Loops {
        Loops::new(mesh, &(0..np).collect::<Vec<_>>(), holes, metric).expect("loops")
    }

    /// Twice the area the triangles cover, in (u, v).
    fn double_area(mesh: &TriMesh, tris: &[[u32; 3]]) -> f64 {
        let uv = |k: u32| mesh.verts[k as usize].uv;
        tris.iter()
            .map(|t| orient(uv(t[0]), uv(t[1]), uv(t[2])))
            .sum()
    }

    fn double_area_of(pts: &[DVec2]) -> f64 {
        (0..pts.len())
            .map(|k| pts[k].perp_dot(pts[(k + 1) % pts.len()]))
            .sum()
    }

    #[test]
    fn a_zip_the_greedy_walk_cannot_finish_is_found_by_the_least_diagonals() {
        // A cavity of a generated plant's course (its boundary, then its hole,
        // clockwise) and the size metric there: a convex opening close to the
        // bottom row, where the greedy walk pairs the hole with the wrong row.
        let outer = [
            [0.614222018, 0.0],
            [0.625, 0.0],
            [0.635777982, 0.0],
            [0.639439295, 0.5],
            [0.629813098, 0.5],
            [0.620186902, 0.5],
            [0.610560705, 0.5],
        ];
        let hole = [
            [0.625871739, 0.06249439],
            [0.626763493, 0.062177212],
            [0.627621718, 0.06162726],
            [0.628387967, 0.060857453],
            [0.629010507, 0.059909796],
            [0.629455312, 0.058848241],
            [0.629711874, 0.057745101],
            [0.629791913, 0.056666667],
            [0.629711874, 0.055588232],
            [0.629455312, 0.054485092],
            [0.629010507, 0.053423537],
            [0.628387967, 0.05247588],
            [0.627621718, 0.051706073],
            [0.626763493, 0.051156121],
            [0.625871739, 0.050838944],
            [0.625, 0.05074],
            [0.624128261, 0.050838944],
            [0.623236507, 0.051156121],
            [0.622378282, 0.051706073],
            [0.621612033, 0.05247588],
            [0.620989493, 0.053423537],
            [0.620544688, 0.054485092],
            [0.620288126, 0.055588232],
            [0.620208087, 0.056666667],
            [0.620288126, 0.057745101],
            [0.620544688, 0.058848241],
            [0.620989493, 0.059909796],
            [0.621612033, 0.060857453],
            [0.622378282, 0.06162726],
            [0.623236507, 0.062177212],
            [0.624128261, 0.06249439],
            [0.625, 0.062593333],
        ];
        let pts: Vec<DVec2> = outer
            .iter()
            .chain(&hole)
            .map(|&p| DVec2::from_array(p))
            .collect();
        let mesh = mesh_of(pts.iter().copied());
        let (np, n) = (outer.len() as u32, pts.len() as u32);
        let metric = Metric {
            uu: 11124.125563292135,
            uv: 0.0,
            vv: 0.7763158295853231,
        };
        let loops = loops_of(&mesh, np, std::iter::once(np..n), &metric);
        assert!(
            loops.zip_greedy(&mesh).is_none(),
            "the greedy walk gets stuck"
        );
        let tris = loops.zip(&mesh).expect("a zip");
        assert!(loops.cover(&mesh, &tris));
        let expected = double_area_of(&pts[..np as usize]) + double_area_of(&pts[np as usize..]);
        assert!((double_area(&mesh, &tris) - expected).abs() < 1e-12);
        let tris = loops.finish(&mesh, tris).expect("flipped");
        assert_eq!(
            tris.iter().flat_map(|t| t.1).filter(|&f| f).count(),
            hole.len()
        );
    }

    /// A course-like cavity: a slab `width` × 1 with `columns` + 1 vertices
    /// along its bottom and top (collinear) and, when `middle`, one more on
    /// each side at half height (a lattice row's ends), round `holes` (each its
    /// centre, semi-axes and vertex count: ellipses, clockwise). Its points,
    /// boundary length and hole ranges.
    fn slab(
        width: f64,
        columns: usize,
        middle: bool,
        holes: &[(DVec2, DVec2, usize)],
    ) -> (Vec<DVec2>, u32, Vec<std::ops::Range<u32>>) {
        let step = width / columns as f64;
        let mut pts: Vec<DVec2> = (0..=columns)
            .map(|i| DVec2::new(step * i as f64, 0.0))
            .collect();
        if middle {
            pts.push(DVec2::new(width, 0.5));
        }
        pts.extend(
            (0..=columns)
                .rev()
                .map(|i| DVec2::new(step * i as f64, 1.0)),
        );
        if middle {
            pts.push(DVec2::new(0.0, 0.5));
        }
        let np = pts.len() as u32;
        let mut ranges = Vec::new();
        for &(centre, axes, n) in holes {
            let first = pts.len() as u32;
            pts.extend((0..n).map(|k| {
                let a = -std::f64::consts::TAU * k as f64 / n as f64;
                centre + axes * DVec2::new(a.cos(), a.sin())
            }));
            ranges.push(first..pts.len() as u32);
        }
        (pts, np, ranges)
    }

    /// Twice the area of a cavity: its boundary less its holes.
    fn cavity_double_area(pts: &[DVec2], np: u32, holes: &[std::ops::Range<u32>]) -> f64 {
        let loop_area =
            |r: std::ops::Range<u32>| double_area_of(&pts[r.start as usize..r.end as usize]);
        loop_area(0..np) + holes.iter().cloned().map(loop_area).sum::<f64>()
    }

    #[test]
    fn the_sweep_covers_stacked_and_side_by_side_holes_once() {
        // A course's cavity in its size metric: wide, flat holes, two stacked
        // and one beside them, between two rows of a few vertices each.
        let holes = [
            (DVec2::new(1.2, 0.3), DVec2::new(0.9, 0.05), 24),
            (DVec2::new(1.3, 0.72), DVec2::new(0.7, 0.04), 16),
            (DVec2::new(3.0, 0.5), DVec2::new(0.5, 0.1), 12),
        ];
        let (pts, np, ranges) = slab(4.0, 4, true, &holes);
        let mesh = mesh_of(pts.iter().copied());
        let loops = loops_of(&mesh, np, ranges.clone(), &ISOTROPIC);
        let tris = loops.sweep(&mesh).expect("a cover");
        let n = pts.len();
        // Euler: a polygon of n vertices with h holes has n + 2h − 2 triangles.
        assert_eq!(tris.len(), n + 2 * holes.len() - 2);
        assert!((0..n as u32).all(|k| tris.iter().flatten().any(|&x| x == k)));
        let expected = cavity_double_area(&pts, np, &ranges);
        assert!((double_area(&mesh, &tris) - expected).abs() < 1e-12);
        // Flipped to Delaunay, every hole segment is fixed.
        let flipped = loops.finish(&mesh, tris).expect("flipped");
        let fixed = flipped.iter().flat_map(|t| t.1).filter(|&f| f).count();
        assert_eq!(fixed, 24 + 16 + 12);
    }

    #[test]
    fn the_sweep_leaves_the_flips_less_to_do_than_ear_clipping() {
        // Stacked flat holes in a narrow slab (the course's common case): the
        // sweep lays the rungs between them, ear clipping fans across the slab.
        let holes = [
            (DVec2::new(1.0, 0.25), DVec2::new(0.5, 0.02), 20),
            (DVec2::new(1.0, 0.75), DVec2::new(0.45, 0.02), 20),
        ];
        let (pts, np, ranges) = slab(2.0, 2, false, &holes);
        let mesh = mesh_of(pts.iter().copied());
        let loops = loops_of(&mesh, np, ranges, &ISOTROPIC);
        let edges = |tris: &[[u32; 3]]| -> rustc_hash::FxHashSet<(u32, u32)> {
            tris.iter()
                .flat_map(|t| {
                    (0..3).map(move |i| (t[i].min(t[(i + 1) % 3]), t[i].max(t[(i + 1) % 3])))
                })
                .collect()
        };
        let delaunay = |tris: Vec<[u32; 3]>| -> Vec<[u32; 3]> {
            let flipped = loops.finish(&mesh, tris).expect("flipped");
            flipped.iter().map(|t| t.0).collect()
        };
        let swept = loops.sweep(&mesh).expect("a sweep");
        let clipped = loops.ears(&mesh).expect("ears");
        let target = edges(&delaunay(swept.clone()));
        assert_eq!(
            target,
            edges(&delaunay(clipped.clone())),
            "one Delaunay triangulation"
        );
        let off = |tris: &[[u32; 3]]| edges(tris).difference(&target).count();
        assert!(
            off(&swept) * 2 < off(&clipped),
            "swept {} edges off, ear-clipped {}",
            off(&swept),
            off(&clipped)
        );
    }

    proptest::proptest! {
        #![proptest_config(proptest::prelude::ProptestConfig::with_cases(256))]
        /// Holes in cells of a grid over the slab (so none overlap), of any
        /// flatness and vertex count, with the chart stretched as a course's
        /// metric stretches it: the sweep always covers the cavity once.
        #[test]
        fn the_sweep_covers_any_cavity_of_separate_holes(
            columns in 1usize..8,
            middle: bool,
            cells in proptest::collection::vec((proptest::bool::weighted(0.6), 0.1f64..0.45, 0.02f64..0.45, 3usize..28), 12),
            stretch in 0.05f64..20.0,
        ) {
            let (cols, rows) = (4, 3);
            let (width, cell_h) = (4.0, 1.0 / rows as f64);
            let holes: Vec<(DVec2, DVec2, usize)> = cells
                .iter()
                .enumerate()
                .filter(|(_, c)| c.0)
                .map(|(i, &(_, rx, ry, n))| {
                    let (col, row) = ((i % cols) as f64, (i / cols) as f64);
                    let centre = DVec2::new((col + 0.5) * width / cols as f64, (row + 0.5) * cell_h);
                    (centre, DVec2::new(rx * width / cols as f64, ry * cell_h), n)
                })
                .collect();
            proptest::prop_assume!(holes.len() >= 2);
            let (pts, np, ranges) = slab(width, columns, middle, &holes);
            let mesh = mesh_of(pts.iter().copied());
            let metric = Metric { uu: 1.0, uv: 0.0, vv: stretch * stretch };
            let loops = loops_of(&mesh, np, ranges.clone(), &metric);
            let tris = loops.sweep(&mesh);
            proptest::prop_assert!(tris.is_some(), "no sweep");
            let tris = tris.unwrap_or_default();
            proptest::prop_assert_eq!(tris.len(), pts.len() + 2 * holes.len() - 2);
            let expected = cavity_double_area(&pts, np, &ranges);
            proptest::prop_assert!((double_area(&mesh, &tris) - expected).abs() < 1e-9);
        }
    }

    #[test]
    fn ear_clipping_loses_no_collinear_vertex() {
        // A rectangle with many vertices along its bottom and top (collinear,
        // which ear clipping drops) round two holes one above the other.
        let mut pts: Vec<DVec2> = (0..=10).map(|i| DVec2::new(0.1 * i as f64, 0.0)).collect();
        pts.extend((0..=10).rev().map(|i| DVec2::new(0.1 * i as f64, 2.0)));
        let np = pts.len() as u32;
        let circle = |c: DVec2, r: f64, n: usize| -> Vec<DVec2> {
            (0..n)
                .map(|k| {
                    let a = -std::f64::consts::TAU * k as f64 / n as f64;
                    c + r * DVec2::new(a.cos(), a.sin())
                })
                .collect()
        };
        let (a, b) = (
            circle(DVec2::new(0.5, 0.5), 0.3, 20),
            circle(DVec2::new(0.5, 1.5), 0.2, 12),
        );
        pts.extend(&a);
        pts.extend(&b);
        let mesh = mesh_of(pts.iter().copied());
        let (na, n) = (np + a.len() as u32, pts.len() as u32);
        let loops = loops_of(&mesh, np, [np..na, na..n], &ISOTROPIC);
        // Ear clipping alone leaves row vertices out.
        let mut raw: Vec<u32> = Vec::new();
        earcut::Earcut::new().earcut(loops.chart.iter().copied(), &loops.starts, &mut raw);
        assert!((0..np).any(|k| !raw.contains(&k)));
        let tris = loops.ears(&mesh).expect("a cover");
        assert!((0..n).all(|k| tris.iter().flatten().any(|&x| x == k)));
        let expected =
            double_area_of(&pts[..np as usize]) + double_area_of(&a) + double_area_of(&b);
        assert!((double_area(&mesh, &tris) - expected).abs() < 1e-12);
        let tris = loops.finish(&mesh, tris).expect("flipped");
        assert_eq!(tris.iter().flat_map(|t| t.1).filter(|&f| f).count(), 32);
    }

    #[test]
    fn a_bad_triangulation_is_not_taken_for_a_cover() {
        let pts = [
            DVec2::ZERO,
            DVec2::X,
            DVec2::ONE,
            DVec2::Y,
            DVec2::new(0.4, 0.4),
            DVec2::new(0.4, 0.6),
            DVec2::new(0.6, 0.5),
        ];
        let mesh = mesh_of(pts);
        let loops = loops_of(&mesh, 4, std::iter::once(4..7), &ISOTROPIC);
        let good = loops.ears(&mesh).expect("a cover");
        assert!(loops.cover(&mesh, &good));
        // The square's two triangles ignore the hole; one triangle dropped
        // leaves a segment out; a triangle turned round is clockwise.
        assert!(!loops.cover(&mesh, &[[0, 1, 2], [0, 2, 3]]));
        assert!(!loops.cover(&mesh, &good[1..]));
        let mut turned = good.clone();
        turned[0].swap(1, 2);
        assert!(!loops.cover(&mesh, &turned));
    }
}
