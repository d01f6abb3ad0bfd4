//! Openings in a structured mesh: the cavity of each hole cut out of the rings'
//! lattice and triangulated on its own.
//!
//! Sits inside `rings`: a closed patch with holes (a course, head or cone with
//! nozzle openings) keeps its chains — the bottom side, the lattice's rows, the top
//! side — and only the part of the lattice round each hole is taken out. A hole's
//! cavity spans the chains from the last one below the hole to the first one above
//! it (each at least half a row gap clear of it) and, on every chain, the vertices
//! between the last one left of the hole and the first one right of it (each at
//! least half a point step clear). The chains' strips are zipped round the
//! cavities; the cavity's boundary (its bottom chain's vertices left to right, its
//! right ends upwards, its top chain's vertices right to left, its left ends
//! downwards) is zipped to the hole's loop, choosing at each step the shorter
//! diagonal among the steps that make a strictly counter-clockwise triangle in
//! (u, v). With every triangle counter-clockwise and the two loops as the zip's
//! boundary, the triangles cover the ring between them exactly once, so that check
//! is the whole validity test. Cavities that overlap are merged; a merged cavity
//! with several holes, or a zip that gets stuck (a hole too far from convex), is
//! triangulated by spade (`initial`) instead. A cavity that would reach the seam
//! or a pole is not handled here: the caller then meshes the whole region by the
//! general path, which also reports any fault of the loops.

use glam::DVec2;
use rayon::prelude::*;

use super::flip::{incircle, strictly_ccw};
use super::initial;
use super::metric::Metric;
use super::patch::{PatchInfo, Vertex};
use super::region::{Region, UvLoop, bounds_of};
use super::rings::{Chain, Kind};
use super::trimesh::{NONE, TriMesh};
use super::{CdtError, MeshStats};

/// A triangle of a cavity: its vertices (counter-clockwise in (u, v)) and which of
/// its edges are loop segments.
type Triangle = ([u32; 3], [bool; 3]);

/// The cavity of one or more holes.
#[derive(Clone, Debug)]
pub(super) struct Cavity {
    /// First and last chain: the cavity lies between them.
    pub lo: usize,
    pub hi: usize,
    /// For each chain `lo..=hi`, the positions in the chain of the last vertex
    /// left of the cavity and the first one right of it.
    pub cuts: Vec<(usize, usize)>,
    /// The holes inside, as indices into the region's holes.
    pub holes: Vec<usize>,
    /// The holes' parameter bounds, merged.
    bounds: (DVec2, DVec2),
}

impl Cavity {
    /// The cuts `(left, right)` on chain `k`, when the cavity spans it.
    pub fn cut(&self, k: usize) -> Option<(usize, usize)> {
        (self.lo..=self.hi)
            .contains(&k)
            .then(|| self.cuts[k - self.lo])
    }
}

/// The cavities of `region`'s holes in the chains, none overlapping another in
/// any strip (each strip orders those crossing it by their cuts); `None` when a cavity would reach the seam, a
/// pole or past the outermost chains.
pub(super) fn plan(mesh: &TriMesh, chains: &[Chain], region: &Region) -> Option<Vec<Cavity>> {
    let mut cavities: Vec<Cavity> = Vec::with_capacity(region.holes.len());
    for (h, hole) in region.holes.iter().enumerate() {
        let bounds = loop_bounds(hole)?;
        cavities.push(place(mesh, chains, bounds, vec![h])?);
    }
    // Merge until no two share a strip and overlap on it.
    'merge: loop {
        for a in 0..cavities.len() {
            for b in a + 1..cavities.len() {
                if overlap(&cavities[a], &cavities[b]) {
                    let other = cavities.swap_remove(b);
                    let first = &cavities[a];
                    let bounds = (
                        first.bounds.0.min(other.bounds.0),
                        first.bounds.1.max(other.bounds.1),
                    );
                    let mut holes = first.holes.clone();
                    holes.extend(other.holes);
                    holes.sort_unstable();
                    cavities[a] = place(mesh, chains, bounds, holes)?;
                    continue 'merge;
                }
            }
        }
        break;
    }
    Some(cavities)
}

/// The parameter bounds of a loop's vertices, `None` when not finite.
fn loop_bounds(hole: &UvLoop) -> Option<(DVec2, DVec2)> {
    let bounds = bounds_of(&hole.uv);
    (bounds.0.is_finite() && bounds.1.is_finite()).then_some(bounds)
}

/// The cavity of holes with parameter bounds `bounds` in the chains.
fn place(
    mesh: &TriMesh,
    chains: &[Chain],
    bounds: (DVec2, DVec2),
    holes: Vec<usize>,
) -> Option<Cavity> {
    let (lo, hi) = bounds;
    // The last chain below the holes and the first above, half a gap clear.
    let below = chains.iter().rposition(|c| c.v < lo.y)?;
    let above = below + chains[below..].iter().position(|c| c.v > hi.y)?;
    let mut k0 = below;
    if k0 > 0 && lo.y - chains[k0].v < 0.5 * (chains[k0 + 1].v - chains[k0].v) {
        k0 -= 1;
    }
    let mut k1 = above;
    if k1 + 1 < chains.len() && chains[k1].v - hi.y < 0.5 * (chains[k1].v - chains[k1 - 1].v) {
        k1 += 1;
    }
    if !chains[k0..=k1].iter().all(|c| matches!(c.kind, Kind::Row)) {
        return None;
    }
    let cuts = chains[k0..=k1]
        .iter()
        .map(|c| {
            let u = |i: usize| mesh.verts[c.first as usize + i].uv.x;
            let n = c.len;
            // The last vertex left of the holes, half a step clear (not the seam's
            // first copy unless the chain has nothing else there).
            let mut left = (0..n).rposition(|i| u(i) < lo.x)?;
            if left > 0 && lo.x - u(left) < 0.5 * (u(left + 1) - u(left)) {
                left -= 1;
            }
            let mut right = left + (left..n).position(|i| u(i) > hi.x)?;
            if right + 1 < n && u(right) - hi.x < 0.5 * (u(right) - u(right - 1)) {
                right += 1;
            }
            // The seam stays outside: both ends strictly inside the chain.
            (left > 0 && right + 1 < n).then_some((left, right))
        })
        .collect::<Option<Vec<_>>>()?;
    Some(Cavity {
        lo: k0,
        hi: k1,
        cuts,
        holes,
        bounds,
    })
}

/// Whether two cavities share a strip and their cuts overlap (or touch) on one of
/// its chains.
fn overlap(a: &Cavity, b: &Cavity) -> bool {
    let (lo, hi) = (a.lo.max(b.lo), a.hi.min(b.hi));
    if lo >= hi {
        return false;
    }
    (lo..=hi).any(|k| {
        let (Some((al, ar)), Some((bl, br))) = (a.cut(k), b.cut(k)) else {
            return false;
        };
        al <= br && bl <= ar
    })
}

/// The boundary of a cavity as vertex indices of the mesh, counter-clockwise:
/// its bottom chain left to right, the right ends upwards, its top chain right to
/// left, the left ends downwards.
fn boundary(chains: &[Chain], cavity: &Cavity) -> Vec<u32> {
    let at = |k: usize, i: usize| chains[k].first + i as u32;
    let (lo, hi) = (cavity.lo, cavity.hi);
    let mut out = Vec::new();
    let (l0, r0) = cavity.cuts[0];
    out.extend((l0..=r0).map(|i| at(lo, i)));
    for k in lo + 1..hi {
        out.push(at(k, cavity.cuts[k - lo].1));
    }
    let (l1, r1) = cavity.cuts[hi - lo];
    out.extend((l1..=r1).rev().map(|i| at(hi, i)));
    for k in (lo + 1..hi).rev() {
        out.push(at(k, cavity.cuts[k - lo].0));
    }
    out
}

/// Triangulates every cavity into `mesh`: appends the holes' vertices and the
/// cavities' triangles (hole segments fixed) and returns the range of triangles
/// added. `None` when a cavity cannot be triangulated here (the caller falls back
/// to the general path, which reports what is wrong).
pub(super) fn fill(
    info: &PatchInfo,
    mesh: &mut TriMesh,
    chains: &[Chain],
    cavities: &[Cavity],
    region: &Region,
) -> Result<Option<std::ops::Range<u32>>, CdtError> {
    // Every hole's vertices, evaluated once, in hole order.
    let mut hole_first = Vec::with_capacity(region.holes.len());
    let mut uvs = Vec::with_capacity(region.vertex_count());
    for hole in &region.holes {
        hole_first.push((mesh.verts.len() + uvs.len()) as u32);
        uvs.extend_from_slice(&hole.uv);
    }
    if uvs.iter().any(|&uv| info.check_loop_point(uv).is_err()) {
        return Ok(None);
    }
    let verts: Vec<Vertex> = uvs
        .par_iter()
        .with_min_len(super::MIN_VERTICES)
        .map(|&uv| info.vertex_lazy(uv))
        .collect::<Result<_, _>>()?;
    mesh.verts.extend(verts);
    let start = mesh.tris.len() as u32;
    let pieces: Vec<Option<Vec<Triangle>>> = cavities
        .par_iter()
        .map(|cavity| {
            let outer = boundary(chains, cavity);
            if let [h] = cavity.holes[..] {
                let n = region.holes[h].uv.len() as u32;
                // The hole counter-clockwise: its loop reversed.
                let inner: Vec<u32> = (0..n).rev().map(|j| hole_first[h] + j).collect();
                let centre = 0.5 * (cavity.bounds.0 + cavity.bounds.1);
                let metric = info.metric_at(centre);
                if let Some(mut tris) = zip_ring(mesh, &metric, &outer, &inner) {
                    let chart = |k: u32| metric.chart(mesh.verts[k as usize].uv);
                    delaunay_flips(&mut tris, chart);
                    return Some(tris);
                }
            }
            by_spade(info, mesh, &outer, cavity, region, &hole_first)
        })
        .collect();
    for piece in pieces {
        let Some(tris) = piece else {
            return Ok(None);
        };
        for (tri, fixed) in tris {
            mesh.tris.push(tri);
            mesh.fixed.push(fixed);
            mesh.adj.push([NONE; 3]);
            mesh.touched.push(0);
        }
    }
    Ok(Some(start..mesh.tris.len() as u32))
}

/// Zips the cavity's boundary `outer` (counter-clockwise) with the hole `inner`
/// (counter-clockwise, inside it): triangles with their fixed flags (the hole's
/// segments), or `None` when no strictly counter-clockwise step is left.
///
/// Diagonals are compared in the size `metric` at the cavity, not in 3D: on a
/// course, whose triangles may run far along the axis but only a step round it,
/// that pairs each hole vertex with the chain vertices above or below it, as the
/// chordal tolerance wants.
fn zip_ring(
    mesh: &TriMesh,
    metric: &Metric,
    outer: &[u32],
    inner: &[u32],
) -> Option<Vec<Triangle>> {
    let (np, nq) = (outer.len(), inner.len());
    if np < 3 || nq < 3 {
        return None;
    }
    let uv = |k: u32| mesh.verts[k as usize].uv;
    let distance = |a: u32, b: u32| metric.length_sq(uv(a) - uv(b));
    // Start at the outer loop's first vertex and the hole vertex nearest to it.
    let q0 = (0..nq)
        .min_by(|&a, &b| distance(inner[a], outer[0]).total_cmp(&distance(inner[b], outer[0])))?;
    let p = |i: usize| outer[i % np];
    let q = |j: usize| inner[(q0 + j) % nq];
    let mut out = Vec::with_capacity(np + nq);
    let (mut i, mut j) = (0usize, 0usize);
    while i < np || j < nq {
        let can_p = i < np && strictly_ccw(uv(p(i)), uv(p(i + 1)), uv(q(j)));
        let can_q = j < nq && strictly_ccw(uv(p(i)), uv(q(j + 1)), uv(q(j)));
        let advance_p = match (can_p, can_q) {
            (true, true) => distance(p(i + 1), q(j)) <= distance(p(i), q(j + 1)),
            (true, false) => true,
            (false, true) => false,
            (false, false) => return None,
        };
        if advance_p {
            out.push(([p(i), p(i + 1), q(j)], [false; 3]));
            i += 1;
        } else {
            // Edge 1 (q(j + 1) → q(j)) is a hole segment.
            out.push(([p(i), q(j + 1), q(j)], [false, true, false]));
            j += 1;
        }
    }
    Some(out)
}

/// Lawson's flips on a zipped cavity until its triangles are Delaunay in `chart`
/// (the size metric at the cavity) with its fixed edges and its boundary kept:
/// the zip's greedy choices leave needles where a boundary vertex fans to many
/// hole vertices; after the flips the cavity is the constrained Delaunay
/// triangulation of its vertices, as spade would make it. An edge is flipped only
/// when both new triangles are strictly counter-clockwise in (u, v).
fn delaunay_flips(tris: &mut [Triangle], chart: impl Fn(u32) -> DVec2) {
    let mut edges: rustc_hash::FxHashMap<(u32, u32), (usize, usize)> =
        rustc_hash::FxHashMap::default();
    edges.reserve(3 * tris.len());
    for (t, (tri, _)) in tris.iter().enumerate() {
        for i in 0..3 {
            edges.insert((tri[i], tri[(i + 1) % 3]), (t, i));
        }
    }
    let mut stack: Vec<(u32, u32)> = edges.keys().copied().collect();
    stack.sort_unstable();
    // Each flip lowers the triangulation's lifted volume, so this ends; the cap
    // only guards against rounding cycles.
    let mut budget = 8 * tris.len() + 64;
    while let Some((a, b)) = stack.pop() {
        let (Some(&(t, i)), Some(&(s, j))) = (edges.get(&(a, b)), edges.get(&(b, a))) else {
            continue;
        };
        if tris[t].1[i] || tris[s].1[j] {
            continue;
        }
        let c = tris[t].0[(i + 2) % 3];
        let d = tris[s].0[(j + 2) % 3];
        let [pa, pb, pc, pd] = [a, b, c, d].map(&chart);
        if !incircle(pa, pb, pc, pd) {
            continue;
        }
        if !(strictly_ccw(pc, pa, pd) && strictly_ccw(pd, pb, pc)) {
            continue;
        }
        if budget == 0 {
            break;
        }
        budget -= 1;
        let (ft, fs) = (tris[t].1, tris[s].1);
        tris[t] = ([c, a, d], [ft[(i + 2) % 3], fs[(j + 1) % 3], false]);
        tris[s] = ([d, b, c], [fs[(j + 2) % 3], ft[(i + 1) % 3], false]);
        edges.remove(&(a, b));
        edges.remove(&(b, a));
        for (k, tri) in [(t, [c, a, d]), (s, [d, b, c])] {
            for e in 0..3 {
                edges.insert((tri[e], tri[(e + 1) % 3]), (k, e));
            }
        }
        stack.extend([(c, a), (a, d), (d, b), (b, c)]);
    }
}

/// The cavity triangulated by spade: the boundary as the outer loop, its holes as
/// holes, no seeds. `None` when spade's triangulation fails.
fn by_spade(
    info: &PatchInfo,
    mesh: &TriMesh,
    outer: &[u32],
    cavity: &Cavity,
    region: &Region,
    hole_first: &[u32],
) -> Option<Vec<Triangle>> {
    let mut sub = Region::new(UvLoop::new(
        outer.iter().map(|&k| mesh.verts[k as usize].uv).collect(),
    ));
    // Local vertex index → mesh vertex index.
    let mut map: Vec<u32> = outer.to_vec();
    for &h in &cavity.holes {
        let hole = &region.holes[h];
        map.extend((0..hole.uv.len() as u32).map(|j| hole_first[h] + j));
        sub = sub.with_hole(hole.clone());
    }
    let mut stats = MeshStats::default();
    // In (u, v) only: the cavity's vertices are the mesh's already.
    let local = initial::triangulate_uv(info, &sub, &[], &mut stats).ok()?;
    let n_outer = outer.len() as u32;
    local
        .tris
        .iter()
        .map(|tri| {
            // No seeds: every vertex is a loop vertex, in loop order.
            let mapped = tri.map(|k| map.get(k as usize).copied());
            let [Some(a), Some(b), Some(c)] = mapped else {
                return None;
            };
            // Only the holes' segments stay fixed; the cavity's boundary is
            // interior to the patch (or a side, fixed by the caller).
            let fixed = std::array::from_fn(|i| {
                let (x, y) = (tri[i], tri[(i + 1) % 3]);
                local.is_loop_edge(x, y) && !(x < n_outer && y < n_outer)
            });
            Some(([a, b, c], fixed))
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::DVec3;

    /// A flat lattice: `rows` chains of `n` vertices over the unit square, u
    /// from 0 (the seam) to 1, mapped to 10 × 10 mm.
    fn lattice(rows: usize, n: usize) -> (TriMesh, Vec<Chain>) {
        let mut mesh = TriMesh::default();
        let mut chains = Vec::new();
        for r in 0..rows {
            let v = r as f64 / (rows - 1) as f64;
            chains.push(Chain {
                v,
                kind: Kind::Row,
                first: mesh.verts.len() as u32,
                len: n,
            });
            for i in 0..n {
                mesh.verts
                    .push(vertex(DVec2::new(i as f64 / (n - 1) as f64, v)));
            }
        }
        (mesh, chains)
    }

    fn vertex(uv: DVec2) -> Vertex {
        Vertex {
            uv,
            point: DVec3::new(10.0 * uv.x, 10.0 * uv.y, 0.0),
            normal: DVec3::Z,
            metric: Metric::UNSET,
            pole: false,
        }
    }

    /// A clockwise circle of `n` vertices.
    fn circle(centre: DVec2, r: f64, n: usize) -> UvLoop {
        UvLoop::new(
            (0..n)
                .map(|k| {
                    let a = -std::f64::consts::TAU * k as f64 / n as f64;
                    centre + r * DVec2::new(a.cos(), a.sin())
                })
                .collect(),
        )
    }

    fn area(mesh: &TriMesh, tris: &[Triangle]) -> f64 {
        tris.iter()
            .map(|(t, _)| {
                let [a, b, c] = t.map(|k| mesh.verts[k as usize].uv);
                0.5 * (b - a).perp_dot(c - a)
            })
            .sum()
    }

    #[test]
    fn a_hole_gets_a_cavity_clear_of_it_and_a_valid_delaunay_ring() {
        let (mut mesh, chains) = lattice(9, 21);
        let hole = circle(DVec2::new(0.5, 0.5), 0.16, 40);
        let region = Region::new(UvLoop::new(vec![
            DVec2::ZERO,
            DVec2::X,
            DVec2::ONE,
            DVec2::Y,
        ]))
        .with_hole(hole.clone());
        let cavities = plan(&mesh, &chains, &region).expect("a cavity");
        assert_eq!(cavities.len(), 1);
        let cavity = &cavities[0];
        // Rows at 0.25 and 0.75 are the first clear of the hole (0.34..0.66) by
        // half a gap (0.0625); u cuts at 0.3 and 0.7 likewise.
        assert_eq!((cavity.lo, cavity.hi), (2, 6));
        assert!(
            cavity.cuts.iter().all(|&c| c == (6, 14)),
            "{:?}",
            cavity.cuts
        );
        let first = mesh.verts.len() as u32;
        mesh.verts.extend(hole.uv.iter().map(|&uv| vertex(uv)));
        let outer = boundary(&chains, cavity);
        let inner: Vec<u32> = (0..40).rev().map(|j| first + j).collect();
        let metric = Metric {
            uu: 1.0,
            uv: 0.0,
            vv: 1.0,
        };
        let mut tris = zip_ring(&mesh, &metric, &outer, &inner).expect("the zip");
        let expected = 0.4 * 0.5 + 0.5 * hole.signed_double_area();
        assert!((area(&mesh, &tris) - expected).abs() < 1e-12);
        let uv = |k: u32| mesh.verts[k as usize].uv;
        delaunay_flips(&mut tris, |k| metric.chart(uv(k)));
        assert!((area(&mesh, &tris) - expected).abs() < 1e-12);
        // Every triangle counter-clockwise, each hole segment kept once, fixed;
        // every interior edge locally Delaunay.
        let mut edges = std::collections::HashMap::new();
        for (t, (tri, fixed)) in tris.iter().enumerate() {
            assert!(strictly_ccw(uv(tri[0]), uv(tri[1]), uv(tri[2])));
            for i in 0..3 {
                edges.insert((tri[i], tri[(i + 1) % 3]), (t, i, fixed[i]));
            }
        }
        let fixed = edges.values().filter(|e| e.2).count();
        assert_eq!(fixed, 40);
        for (&(a, b), &(t, i, _)) in &edges {
            if let Some(&(s, j, _)) = edges.get(&(b, a)) {
                let c = tris[t].0[(i + 2) % 3];
                let d = tris[s].0[(j + 2) % 3];
                assert!(!incircle(uv(a), uv(b), uv(c), uv(d)));
            }
        }
    }

    #[test]
    fn close_holes_share_a_cavity_and_the_seam_is_left_alone() {
        let (mesh, chains) = lattice(9, 21);
        let square = Region::new(UvLoop::new(vec![
            DVec2::ZERO,
            DVec2::X,
            DVec2::ONE,
            DVec2::Y,
        ]));
        let two = square
            .clone()
            .with_hole(circle(DVec2::new(0.3, 0.3), 0.05, 12))
            .with_hole(circle(DVec2::new(0.36, 0.45), 0.05, 12))
            .with_hole(circle(DVec2::new(0.8, 0.5), 0.05, 12));
        let cavities = plan(&mesh, &chains, &two).expect("cavities");
        let holes: Vec<Vec<usize>> = cavities.iter().map(|c| c.holes.clone()).collect();
        assert_eq!(holes, vec![vec![0, 1], vec![2]]);
        let seam = square.with_hole(circle(DVec2::new(0.04, 0.5), 0.02, 12));
        assert!(plan(&mesh, &chains, &seam).is_none());
    }
}
