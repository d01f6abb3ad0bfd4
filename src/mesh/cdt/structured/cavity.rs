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
//! downwards) and its holes are triangulated by `ring` (zipped to a single hole,
//! swept round several, ear-clipped when neither works, flipped to Delaunay),
//! unless the patch's last
//! meshing kept a cavity with the very same inputs (`kept`), whose triangles are
//! then taken. Cavities that overlap are merged; a cavity `ring` cannot cover is
//! triangulated by spade (`initial`) instead. A cavity that would reach the seam
//! or a pole is not handled here:
//! the caller then meshes the whole region by the general path, which also
//! reports any fault of the loops.

use std::sync::Arc;

use glam::DVec2;
use rayon::prelude::*;

use super::cavity_fill::{Loops, Triangle, numbering};
use super::kept::{CavityInput, Kept, Memo};
use super::lattice::{Chain, Kind};
use crate::mesh::cdt::general::initial;
use crate::mesh::cdt::patch::{PatchInfo, Vertex};
use crate::mesh::cdt::plan::{CAVITY_FILLS, CavityFill};
use crate::mesh::cdt::region::{Region, UvLoop, bounds_of};
use crate::mesh::cdt::trimesh::{NONE, TriMesh};
use crate::mesh::cdt::{CdtError, MeshStats};

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

/// One cavity's triangles in the mesh, as [`fill`] left them.
pub(super) struct Filled {
    /// Its range of the mesh's triangles.
    pub range: std::ops::Range<u32>,
    /// Its inputs and triangles, to keep (unless spade triangulated it; taken
    /// from the memo's kept cavities when they had them).
    pub kept: Option<Arc<Kept>>,
}

/// Triangulates every cavity into `mesh` by the first of [`CAVITY_FILLS`] that
/// is accepted (see `plan`: the triangles `memo` kept for a cavity with the
/// same inputs, a zip for one hole, the sweep or ear clipping for several,
/// spade when none gives a valid cover):
/// appends the holes' vertices and the cavities' triangles (hole segments
/// fixed) and returns each cavity's range of triangles, in order, with what to
/// keep of it (the caller records it in `memo` once screened). `None` when a
/// cavity cannot be triangulated here (the caller falls back to the general
/// path, which reports what is wrong).
pub(super) fn fill(
    info: &PatchInfo,
    mesh: &mut TriMesh,
    chains: &[Chain],
    cavities: &[Cavity],
    region: &Region,
    memo: &mut Memo,
) -> Result<Option<Vec<Filled>>, CdtError> {
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
    let chunks: Vec<Vec<Vertex>> = uvs
        .par_chunks(crate::mesh::cdt::MIN_VERTICES)
        .map(|chunk| info.vertices_lazy(chunk))
        .collect::<Result<_, _>>()?;
    mesh.verts.reserve(uvs.len());
    for chunk in chunks {
        mesh.verts.extend(chunk);
    }
    let (kept, record) = (memo.kept, memo.record);
    let pieces: Vec<Option<Piece>> = cavities
        .par_iter()
        .map(|cavity| {
            let outer = boundary(chains, cavity);
            let centre = 0.5 * (cavity.bounds.0 + cavity.bounds.1);
            let holes: Vec<std::ops::Range<u32>> = (cavity.holes.iter())
                .map(|&h| hole_first[h]..hole_first[h] + region.holes[h].uv.len() as u32)
                .collect();
            let metric = info.metric_at(centre);
            let (map, starts) = numbering(&outer, &holes);
            // Only when a cavity is looked up or kept.
            let input = (kept.is_some() || record).then(|| {
                CavityInput::new(
                    map.iter().map(|&k| mesh.verts[k as usize].uv).collect(),
                    starts.clone(),
                    &metric,
                )
            });
            if let (Some(kept), Some(input)) = (kept, &input)
                && let Some(same) = kept.find(input)
                && let Some(triangles) = to_mesh(&map, same.triangles())
            {
                // Kept again for the next meshing.
                return Some(Piece {
                    triangles,
                    found: Some(same.clone()),
                    fill: CavityFill::Kept,
                });
            }
            // The fills of the table after `Kept`, up to spade: the first that
            // gives triangles is taken if they survive the flips to Delaunay.
            if let Some(loops) = Loops::numbered(mesh, map, starts, &metric)
                && let Some((fill, tris)) = CAVITY_FILLS.iter().find_map(|&fill| {
                    match fill {
                        CavityFill::Zip => loops.zip(mesh),
                        CavityFill::Sweep => loops.sweep(mesh),
                        CavityFill::Ears => loops.ears(mesh),
                        CavityFill::Kept | CavityFill::Spade => None,
                    }
                    .map(|tris| (fill, tris))
                })
                && let Some(local) = loops.finish_local(mesh, tris)
            {
                return Some(Piece {
                    triangles: to_mesh(loops.map(), &local)?,
                    found: input.map(|input| Kept::new(input, local)),
                    fill,
                });
            }
            let triangles = by_spade(info, mesh, &outer, cavity, region, &hole_first)?;
            Some(Piece {
                triangles,
                found: None,
                fill: CavityFill::Spade,
            })
        })
        .collect();
    let mut filled = Vec::with_capacity(pieces.len());
    // The strips' triangles were reserved for; the cavities' are added at once.
    let added: usize = pieces.iter().flatten().map(|p| p.triangles.len()).sum();
    mesh.tris.reserve(added);
    mesh.fixed.reserve(added);
    mesh.adj.reserve(added);
    mesh.touched.reserve(added);
    for piece in pieces {
        let Some(piece) = piece else {
            return Ok(None);
        };
        memo.reused += usize::from(piece.fill == CavityFill::Kept);
        memo.fills[piece.fill.index()] += 1;
        let start = mesh.tris.len() as u32;
        for (tri, fixed) in piece.triangles {
            mesh.tris.push(tri);
            mesh.fixed.push(fixed);
            mesh.adj.push([NONE; 3]);
            mesh.touched.push(0);
        }
        filled.push(Filled {
            range: start..mesh.tris.len() as u32,
            kept: piece.found.filter(|_| record),
        });
    }
    Ok(Some(filled))
}

/// `tris` in a cavity's local numbering as mesh triangles (`map`: local index →
/// mesh vertex); `None` for an index past the cavity's vertices (none is: kept
/// triangles come with inputs of the same length).
fn to_mesh(map: &[u32], tris: &[Triangle]) -> Option<Vec<Triangle>> {
    tris.iter()
        .map(|&(t, f)| {
            let [a, b, c] = t.map(|k| map.get(k as usize).copied());
            Some(([a?, b?, c?], f))
        })
        .collect()
}

/// One cavity's triangles (mesh vertices), with its inputs and local triangles
/// to keep (unless spade triangulated it), and the fill that gave them
/// ([`CavityFill::Kept`]: taken from the kept ones).
struct Piece {
    triangles: Vec<Triangle>,
    found: Option<Arc<Kept>>,
    fill: CavityFill,
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
    use crate::mesh::cdt::flip::{incircle, orient, strictly_ccw};
    use crate::mesh::cdt::metric::Metric;
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

    /// The unit square with `holes`.
    fn square(holes: impl IntoIterator<Item = UvLoop>) -> Region {
        let outer = UvLoop::new(vec![DVec2::ZERO, DVec2::X, DVec2::ONE, DVec2::Y]);
        holes
            .into_iter()
            .fold(Region::new(outer), Region::with_hole)
    }

    /// The region's hole vertices appended to `mesh`, and each hole's range.
    fn add_holes(mesh: &mut TriMesh, region: &Region) -> Vec<std::ops::Range<u32>> {
        region
            .holes
            .iter()
            .map(|hole| {
                let first = mesh.verts.len() as u32;
                mesh.verts.extend(hole.uv.iter().map(|&uv| vertex(uv)));
                first..mesh.verts.len() as u32
            })
            .collect()
    }

    const ISOTROPIC: Metric = Metric {
        uu: 1.0,
        uv: 0.0,
        vv: 1.0,
    };

    /// The area of the cavity's boundary rectangle less its holes.
    fn cavity_area(mesh: &TriMesh, chains: &[Chain], cavity: &Cavity, holes: &[&UvLoop]) -> f64 {
        let u = |k: usize, i: usize| mesh.verts[chains[k].first as usize + i].uv.x;
        let (l, r) = cavity.cuts[0];
        let width = u(cavity.lo, r) - u(cavity.lo, l);
        let height = chains[cavity.hi].v - chains[cavity.lo].v;
        width * height + 0.5 * holes.iter().map(|h| h.signed_double_area()).sum::<f64>()
    }

    /// Asserts that `tris` cover the cavity less its holes once: every triangle
    /// strictly counter-clockwise, the area the cavity's (`expected`), every hole
    /// segment (`segments` of them) an edge once and fixed, no other edge fixed,
    /// every interior edge locally Delaunay in `metric`.
    fn assert_delaunay_cover(
        mesh: &TriMesh,
        tris: &[Triangle],
        expected: f64,
        segments: usize,
        metric: &Metric,
    ) {
        let uv = |k: u32| mesh.verts[k as usize].uv;
        let area: f64 = tris
            .iter()
            .map(|(t, _)| 0.5 * orient(uv(t[0]), uv(t[1]), uv(t[2])))
            .sum();
        assert!((area - expected).abs() < 1e-12, "{area} against {expected}");
        let mut edges = std::collections::HashMap::new();
        for (t, (tri, fixed)) in tris.iter().enumerate() {
            assert!(strictly_ccw(uv(tri[0]), uv(tri[1]), uv(tri[2])));
            for i in 0..3 {
                let old = edges.insert((tri[i], tri[(i + 1) % 3]), (t, i, fixed[i]));
                assert!(old.is_none(), "an edge twice");
            }
        }
        assert_eq!(edges.values().filter(|e| e.2).count(), segments);
        let chart = |k: u32| metric.chart(uv(k));
        for (&(a, b), &(t, i, fixed)) in &edges {
            if let Some(&(s, j, _)) = edges.get(&(b, a)) {
                assert!(!fixed, "a fixed edge inside the cavity");
                let c = tris[t].0[(i + 2) % 3];
                let d = tris[s].0[(j + 2) % 3];
                assert!(!incircle(chart(a), chart(b), chart(c), chart(d)));
            }
        }
    }

    #[test]
    fn a_hole_gets_a_cavity_clear_of_it_and_a_valid_delaunay_ring() {
        let (mut mesh, chains) = lattice(9, 21);
        let hole = circle(DVec2::new(0.5, 0.5), 0.16, 40);
        let region = square([hole.clone()]);
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
        let ranges = add_holes(&mut mesh, &region);
        let outer = boundary(&chains, cavity);
        let loops = Loops::new(&mesh, &outer, ranges, &ISOTROPIC).expect("loops");
        let expected = cavity_area(&mesh, &chains, cavity, &[&hole]);
        assert!((expected - (0.4 * 0.5 + 0.5 * hole.signed_double_area())).abs() < 1e-12);
        // Zipped, and ear-clipped: both valid, Delaunay once flipped.
        for tris in [loops.zip(&mesh), loops.ears(&mesh)] {
            let tris = loops
                .finish(&mesh, tris.expect("a cover"))
                .expect("flipped");
            assert_delaunay_cover(&mesh, &tris, expected, 40, &ISOTROPIC);
        }
    }

    #[test]
    fn holes_sharing_a_cavity_are_swept_or_ear_clipped_with_every_row_vertex_kept() {
        // Three rows; a large opening low down and a small one just under the
        // middle row, whose cavity therefore reaches the top row and takes in
        // the large one's (as on a long course with a small nozzle above a
        // manway). Ear clipping drops the rows' collinear vertices; fans bring
        // them back.
        let (mut mesh, chains) = lattice(3, 41);
        let big = circle(DVec2::new(0.5, 0.14), 0.1, 48);
        let small = circle(DVec2::new(0.5, 0.47), 0.01, 16);
        let region = square([big.clone(), small.clone()]);
        let cavities = plan(&mesh, &chains, &region).expect("cavities");
        assert_eq!(cavities.len(), 1);
        let cavity = &cavities[0];
        assert_eq!(cavity.holes, vec![0, 1]);
        assert_eq!((cavity.lo, cavity.hi), (0, 2));
        let ranges = add_holes(&mut mesh, &region);
        let outer = boundary(&chains, cavity);
        let metric = Metric {
            uu: 40.0,
            uv: 0.0,
            vv: 1.0,
        };
        let loops = Loops::new(&mesh, &outer, ranges, &metric).expect("loops");
        assert!(loops.zip(&mesh).is_none(), "a zip takes one hole");
        // Swept (the mesher's way), and ear-clipped (its fallback).
        let expected = cavity_area(&mesh, &chains, cavity, &[&big, &small]);
        for tris in [loops.sweep(&mesh), loops.ears(&mesh)] {
            let tris = tris.expect("a cover of the cavity");
            let tris = loops.finish(&mesh, tris).expect("flipped");
            let used: std::collections::HashSet<u32> = tris.iter().flat_map(|t| t.0).collect();
            assert!(outer.iter().all(|k| used.contains(k)), "a row vertex lost");
            assert_delaunay_cover(&mesh, &tris, expected, 64, &metric);
        }
    }

    #[test]
    fn close_holes_share_a_cavity_and_the_seam_is_left_alone() {
        let (mesh, chains) = lattice(9, 21);
        let two = square([
            circle(DVec2::new(0.3, 0.3), 0.05, 12),
            circle(DVec2::new(0.36, 0.45), 0.05, 12),
            circle(DVec2::new(0.8, 0.5), 0.05, 12),
        ]);
        let cavities = plan(&mesh, &chains, &two).expect("cavities");
        let holes: Vec<Vec<usize>> = cavities.iter().map(|c| c.holes.clone()).collect();
        assert_eq!(holes, vec![vec![0, 1], vec![2]]);
        let seam = square([circle(DVec2::new(0.04, 0.5), 0.02, 12)]);
        assert!(plan(&mesh, &chains, &seam).is_none());
    }
}
