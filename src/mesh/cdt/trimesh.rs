//! The triangulation the refinement works on: vertices with their exact surface
//! data, counter-clockwise (u, v) triangles with neighbour links, and the loop
//! segments marked as fixed edges that are never flipped.
//!
//! Spade builds the initial constrained triangulation; it is copied here because
//! refinement only ever inserts at known places (a triangle's centroid or an edge's
//! midpoint), so no point location is needed, and because its flips must follow the
//! surface's metric rather than the plane's. Every operation keeps the (u, v)
//! triangulation valid: splits put the new vertex strictly inside the triangle or on
//! the edge, and [`flip`](TriMesh::flip) is only called on strictly convex quads.
//! Edge `i` of a triangle runs from its vertex `i` to vertex `i + 1`.

use super::patch::Vertex;

/// No neighbour (a fixed edge on the boundary of the region).
pub(super) const NONE: u32 = u32::MAX;

/// Triangles with neighbour links over a vertex table.
#[derive(Clone, Debug, Default)]
pub(super) struct TriMesh {
    /// Vertices.
    pub verts: Vec<Vertex>,
    /// Vertex indices of each triangle, counter-clockwise in (u, v).
    pub tris: Vec<[u32; 3]>,
    /// Neighbour across edge `i`, or [`NONE`].
    pub adj: Vec<[u32; 3]>,
    /// Whether edge `i` is a loop segment (or part of one on a collapsed side).
    pub fixed: Vec<[bool; 3]>,
    /// Pass number of the last change of each triangle.
    pub touched: Vec<u32>,
    /// The current pass number.
    pub pass: u32,
}

impl TriMesh {
    /// A mesh of `tris` over `verts`; `is_fixed(a, b)` says whether the edge
    /// between vertices `a` and `b` is a loop segment. The triangles must form a
    /// valid triangulation (each directed edge at most once).
    pub fn new(
        verts: Vec<Vertex>,
        tris: Vec<[u32; 3]>,
        is_fixed: impl Fn(u32, u32) -> bool,
    ) -> Self {
        let mut directed: rustc_hash::FxHashMap<(u32, u32), (u32, usize)> =
            rustc_hash::FxHashMap::default();
        directed.reserve(tris.len() * 3);
        for (t, tri) in tris.iter().enumerate() {
            for i in 0..3 {
                directed.insert((tri[i], tri[(i + 1) % 3]), (t as u32, i));
            }
        }
        let mut adj = vec![[NONE; 3]; tris.len()];
        let mut fixed = vec![[false; 3]; tris.len()];
        for (t, tri) in tris.iter().enumerate() {
            for i in 0..3 {
                let (a, b) = (tri[i], tri[(i + 1) % 3]);
                if let Some(&(n, _)) = directed.get(&(b, a)) {
                    adj[t][i] = n;
                }
                fixed[t][i] = is_fixed(a, b);
            }
        }
        let touched = vec![0; tris.len()];
        Self {
            verts,
            tris,
            adj,
            fixed,
            touched,
            pass: 0,
        }
    }

    /// The vertices of edge `i` of triangle `t`.
    pub fn edge(&self, t: u32, i: usize) -> (u32, u32) {
        let tri = self.tris[t as usize];
        (tri[i], tri[(i + 1) % 3])
    }

    /// The index in triangle `n` of its edge shared with triangle `t`.
    fn index_of(&self, n: u32, t: u32) -> usize {
        let links = self.adj[n as usize];
        (0..3).find(|&k| links[k] == t).unwrap_or(0)
    }

    /// Redirects `n`'s link to `old` towards `new` (nothing for [`NONE`]).
    fn repoint(&mut self, n: u32, old: u32, new: u32) {
        if n != NONE {
            let k = self.index_of(n, old);
            self.adj[n as usize][k] = new;
        }
    }

    /// Writes triangle `t` (pushing it when `t` is the next index).
    fn put(&mut self, t: u32, tri: [u32; 3], adj: [u32; 3], fixed: [bool; 3]) {
        let t = t as usize;
        if t == self.tris.len() {
            self.tris.push(tri);
            self.adj.push(adj);
            self.fixed.push(fixed);
            self.touched.push(self.pass);
        } else {
            self.tris[t] = tri;
            self.adj[t] = adj;
            self.fixed[t] = fixed;
            self.touched[t] = self.pass;
        }
    }

    /// Adds a vertex; returns its index.
    pub fn push_vertex(&mut self, v: Vertex) -> u32 {
        self.verts.push(v);
        (self.verts.len() - 1) as u32
    }

    /// Splits triangle `t` at the new vertex `x` (strictly inside it); returns the
    /// edges opposite `x` for legalization.
    pub fn split_triangle(&mut self, t: u32, x: u32) -> Vec<(u32, usize)> {
        let [a, b, c] = self.tris[t as usize];
        let [nab, nbc, nca] = self.adj[t as usize];
        let [fab, fbc, fca] = self.fixed[t as usize];
        let t1 = self.tris.len() as u32;
        let t2 = t1 + 1;
        self.put(t, [a, b, x], [nab, t1, t2], [fab, false, false]);
        self.put(t1, [b, c, x], [nbc, t2, t], [fbc, false, false]);
        self.put(t2, [c, a, x], [nca, t, t1], [fca, false, false]);
        self.repoint(nbc, t, t1);
        self.repoint(nca, t, t2);
        vec![(t, 0), (t1, 0), (t2, 0)]
    }

    /// Splits edge `i` of triangle `t` at the new vertex `x` (on the edge), and the
    /// neighbour across it if any; returns the outer edges for legalization.
    pub fn split_edge(&mut self, t: u32, i: usize, x: u32) -> Vec<(u32, usize)> {
        let rot = |k: usize| (i + k) % 3;
        let tri = self.tris[t as usize];
        let (links, flags) = (self.adj[t as usize], self.fixed[t as usize]);
        let (a, b, c) = (tri[rot(0)], tri[rot(1)], tri[rot(2)]);
        let (n, nbc, nca) = (links[rot(0)], links[rot(1)], links[rot(2)]);
        let (fab, fbc, fca) = (flags[rot(0)], flags[rot(1)], flags[rot(2)]);
        let ta = self.tris.len() as u32;
        if n == NONE {
            self.put(t, [a, x, c], [NONE, ta, nca], [fab, false, fca]);
            self.put(ta, [x, b, c], [NONE, nbc, t], [fab, fbc, false]);
            self.repoint(nbc, t, ta);
            return vec![(t, 2), (ta, 1)];
        }
        let j = self.index_of(n, t);
        let rot2 = |k: usize| (j + k) % 3;
        let (tri2, links2, flags2) = (
            self.tris[n as usize],
            self.adj[n as usize],
            self.fixed[n as usize],
        );
        let d = tri2[rot2(2)];
        let (nad, ndb) = (links2[rot2(1)], links2[rot2(2)]);
        let (fad, fdb) = (flags2[rot2(1)], flags2[rot2(2)]);
        let tb = ta + 1;
        self.put(t, [a, x, c], [tb, ta, nca], [fab, false, fca]);
        self.put(ta, [x, b, c], [n, nbc, t], [fab, fbc, false]);
        self.put(n, [b, x, d], [ta, tb, ndb], [fab, false, fdb]);
        self.put(tb, [x, a, d], [t, nad, n], [fab, fad, false]);
        self.repoint(nbc, t, ta);
        self.repoint(nad, n, tb);
        vec![(t, 2), (ta, 1), (n, 2), (tb, 1)]
    }

    /// The quad around edge `i` of `t`: `(a, b, c, d)` with `t = (a, b, c)` and the
    /// neighbour `(b, a, d)`, and the neighbour's index; `None` on a boundary.
    pub fn quad(&self, t: u32, i: usize) -> Option<([u32; 4], u32)> {
        let n = self.adj[t as usize][i];
        if n == NONE {
            return None;
        }
        let tri = self.tris[t as usize];
        let j = self.index_of(n, t);
        let d = self.tris[n as usize][(j + 2) % 3];
        Some(([tri[i], tri[(i + 1) % 3], tri[(i + 2) % 3], d], n))
    }

    /// Flips edge `i` of `t` (the quad must be strictly convex); returns the four
    /// outer edges for legalization.
    pub fn flip(&mut self, t: u32, i: usize) -> Vec<(u32, usize)> {
        let Some(([a, b, c, d], n)) = self.quad(t, i) else {
            return Vec::new();
        };
        let j = self.index_of(n, t);
        let (links, flags) = (self.adj[t as usize], self.fixed[t as usize]);
        let (links2, flags2) = (self.adj[n as usize], self.fixed[n as usize]);
        let (nbc, nca) = (links[(i + 1) % 3], links[(i + 2) % 3]);
        let (fbc, fca) = (flags[(i + 1) % 3], flags[(i + 2) % 3]);
        let (nad, ndb) = (links2[(j + 1) % 3], links2[(j + 2) % 3]);
        let (fad, fdb) = (flags2[(j + 1) % 3], flags2[(j + 2) % 3]);
        self.put(t, [c, a, d], [nca, nad, n], [fca, fad, false]);
        self.put(n, [d, b, c], [ndb, nbc, t], [fdb, fbc, false]);
        self.repoint(nad, n, t);
        self.repoint(nbc, t, n);
        vec![(t, 0), (t, 1), (n, 0), (n, 1)]
    }

    /// Flips edges from `stack` while `should_flip` asks for it (fixed and boundary
    /// edges never), at most `*flips_left` times in all.
    pub fn legalize(
        &mut self,
        mut stack: Vec<(u32, usize)>,
        flips_left: &mut usize,
        should_flip: impl Fn(&TriMesh, u32, usize) -> bool,
    ) {
        while let Some((t, i)) = stack.pop() {
            if *flips_left == 0 {
                return;
            }
            if self.fixed[t as usize][i] || self.adj[t as usize][i] == NONE {
                continue;
            }
            if should_flip(self, t, i) {
                *flips_left -= 1;
                stack.extend(self.flip(t, i));
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use glam::{DVec2, DVec3};

    use super::*;
    use crate::mesh::cdt::flip::strictly_ccw;
    use crate::mesh::cdt::metric::Metric;

    fn vertex(uv: DVec2) -> Vertex {
        Vertex {
            uv,
            point: uv.extend(0.0),
            normal: DVec3::Z,
            metric: Metric {
                uu: 1.0,
                uv: 0.0,
                vv: 1.0,
            },
            pole: false,
        }
    }

    /// Neighbour links are mutual, every triangle is counter-clockwise, the area is
    /// kept, and exactly the boundary edges are fixed.
    fn assert_valid(m: &TriMesh) {
        let mut area = 0.0;
        for t in 0..m.tris.len() as u32 {
            let [a, b, c] = m.tris[t as usize].map(|k| m.verts[k as usize].uv);
            assert!(
                strictly_ccw(a, b, c),
                "triangle {t} is not counter-clockwise"
            );
            area += 0.5 * (b - a).perp_dot(c - a);
            for i in 0..3 {
                let n = m.adj[t as usize][i];
                assert_eq!(n == NONE, m.fixed[t as usize][i], "edge {i} of {t}");
                if n != NONE {
                    let (x, y) = m.edge(t, i);
                    let j = m.index_of(n, t);
                    assert_eq!(m.edge(n, j), (y, x), "edge {i} of {t} and its twin");
                    assert_eq!(m.adj[n as usize][j], t);
                }
            }
        }
        assert!((area - 1.0).abs() < 1e-12, "area {area}");
    }

    #[test]
    fn splits_and_flips_keep_the_triangulation_valid() {
        let corners = [(0.0, 0.0), (1.0, 0.0), (1.0, 1.0), (0.0, 1.0)];
        let verts = corners.map(|(u, v)| vertex(DVec2::new(u, v))).to_vec();
        let boundary = |a: u32, b: u32| (a + 1) % 4 == b || (b + 1) % 4 == a;
        let mut m = TriMesh::new(verts, vec![[0, 1, 2], [0, 2, 3]], boundary);
        assert_valid(&m);
        let mut state = 0x2545_f491_4f6c_dd1du64;
        let mut next = |n: usize| {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            (state % n as u64) as usize
        };
        for _ in 0..600 {
            let t = next(m.tris.len()) as u32;
            let i = next(3);
            let [a, b, c] = m.tris[t as usize].map(|k| m.verts[k as usize].uv);
            match next(3) {
                0 => {
                    let x = m.push_vertex(vertex((a + b + c) / 3.0));
                    m.split_triangle(t, x);
                }
                1 => {
                    let (p, q) = m.edge(t, i);
                    let mid = 0.5 * (m.verts[p as usize].uv + m.verts[q as usize].uv);
                    let x = m.push_vertex(vertex(mid));
                    m.split_edge(t, i, x);
                }
                _ => {
                    if let Some(([p, q, r, s], _)) = m.quad(t, i) {
                        let uv = |k: u32| m.verts[k as usize].uv;
                        if strictly_ccw(uv(r), uv(p), uv(s)) && strictly_ccw(uv(s), uv(q), uv(r)) {
                            m.flip(t, i);
                        }
                    }
                }
            }
            assert_valid(&m);
        }
    }
}
