//! The zip of a cavity with one hole ([`Loops::zip`](super::Loops::zip)):
//! both loops walked counter-clockwise, one triangle a step, greedily by the
//! shorter diagonal, or by dynamic programming over the walk's positions for the
//! zip of least total diagonal length when the greedy walk gets stuck.

use glam::DVec2;

use super::Loops;
use crate::mesh::cdt::flip::strictly_ccw;
use crate::mesh::cdt::trimesh::TriMesh;

/// The zip's walk round a cavity with one hole: position `i` on the boundary,
/// `j` on the hole (counter-clockwise from the vertex nearest the boundary's
/// first), each step one triangle.
pub(super) struct Walk<'a> {
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
    pub(super) fn new(loops: &'a Loops, mesh: &'a TriMesh) -> Option<Self> {
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

    pub(super) fn greedy(&self) -> Option<Vec<[u32; 3]>> {
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

    pub(super) fn least(&self) -> Option<Vec<[u32; 3]>> {
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
