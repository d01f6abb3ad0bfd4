//! Local mending of a structured mesh: where the screen finds a triangle of a
//! strip outside the limits, the triangle and a neighbour in its strip become a
//! quad, and the quad is re-triangulated as a fan around the exact surface point
//! at its centre.
//!
//! Sits between `rings` (which zips the strips and screens them) and the caller's
//! refinement (which takes whatever still fails). Two rows whose point counts
//! differ drift in and out of phase along the strip; where a vertex of one row
//! stands right above a vertex of the other, the zip's two triangles are
//! right-angled, their circumcircles about 15 % wider than the lattice's
//! equilateral ones, and they deviate about 30 % more. The same happens next to a
//! side whose loop vertices are spaced for the boundary curve, not for the rows.
//! A fan of four around the quad's centre halves those triangles' height; the
//! quad's boundary edges are kept, so the mesh stays conforming with no search and
//! no neighbour links, and only the new triangles are screened again.

use std::ops::Range;

use glam::DVec2;
use rayon::prelude::*;

use crate::mesh::cdt::CdtError;
use crate::mesh::cdt::checks::screen::Screen;
use crate::mesh::cdt::patch::PatchInfo;
use crate::mesh::cdt::trimesh::{NONE, TriMesh};

/// Mends the strips of `mesh` (triangles `strips[k]`, screened `flags[k]`;
/// `zipped[k]` when strip k lies between two rows, the only strips mended) and
/// returns, for every triangle of the mended mesh in order, whether it is within
/// the limits, and the number of vertices added. The triangles are reordered strip by strip, each strip's kept
/// triangles first and its fans after them.
pub(super) fn mend(
    info: &PatchInfo,
    screen: &Screen,
    mesh: &mut TriMesh,
    strips: &[Range<u32>],
    zipped: &[bool],
    flags: Vec<Vec<bool>>,
) -> Result<(Vec<bool>, usize), CdtError> {
    let pairs: Vec<Vec<(u32, u32)>> = strips
        .iter()
        .zip(&flags)
        .zip(zipped)
        .map(|((range, f), &zipped)| {
            if zipped {
                pair_up(mesh, range.clone(), f)
            } else {
                Vec::new()
            }
        })
        .collect();
    if pairs.iter().all(Vec::is_empty) {
        return Ok((flags.into_iter().flatten().collect(), 0));
    }
    // The quads' boundaries (counter-clockwise, with the fixed flags of their
    // edges) and centres.
    let quads: Vec<Vec<Quad>> = pairs
        .iter()
        .map(|list| list.iter().filter_map(|&(s, t)| quad(mesh, s, t)).collect())
        .collect();
    let centres: Vec<Vec<_>> = quads
        .par_iter()
        .map(|list| list.iter().map(|q| info.vertex(q.centre)).collect())
        .collect::<Result<_, _>>()?;
    let old_tris = std::mem::take(&mut mesh.tris);
    let old_fixed = std::mem::take(&mut mesh.fixed);
    let mut within = Vec::with_capacity(old_tris.len());
    let mut fans: Vec<Range<u32>> = Vec::new();
    for (k, range) in strips.iter().enumerate() {
        let mut replaced = vec![false; range.len()];
        for t in quads[k].iter().flat_map(|q| q.pair) {
            replaced[(t - range.start) as usize] = true;
        }
        for t in range.clone() {
            if !replaced[(t - range.start) as usize] {
                mesh.tris.push(old_tris[t as usize]);
                mesh.fixed.push(old_fixed[t as usize]);
                within.push(flags[k][(t - range.start) as usize]);
            }
        }
        let start = mesh.tris.len() as u32;
        for (q, centre) in quads[k].iter().zip(&centres[k]) {
            let c = mesh.push_vertex(*centre);
            for i in 0..4 {
                mesh.tris.push([q.corners[i], q.corners[(i + 1) % 4], c]);
                mesh.fixed.push([q.fixed[i], false, false]);
            }
        }
        let end = mesh.tris.len() as u32;
        within.resize(end as usize, false);
        if end > start {
            fans.push(start..end);
        }
    }
    mesh.adj = vec![[NONE; 3]; mesh.tris.len()];
    mesh.touched = vec![0; mesh.tris.len()];
    let screened: Vec<Vec<bool>> = fans
        .par_iter()
        .map(|range| screen.strip(mesh, range.clone()))
        .collect();
    for (range, flags) in fans.iter().zip(screened) {
        within[range.start as usize..range.end as usize].copy_from_slice(&flags);
    }
    Ok((within, quads.iter().map(Vec::len).sum()))
}

/// A quad made of two triangles: its corners counter-clockwise in (u, v), whether
/// each boundary edge (corner i to i + 1) is a loop segment, and the (u, v) of its
/// centre.
struct Quad {
    pair: [u32; 2],
    corners: [u32; 4],
    fixed: [bool; 4],
    centre: DVec2,
}

/// Pairs every triangle of the strip `range` that failed the screen (`flags`) with
/// a neighbour in the strip (they share a diagonal): the next one when it failed
/// too, else the previous one when free and failed, else the free one across the
/// longer shared edge. A triangle with no free neighbour is left as it is.
fn pair_up(mesh: &TriMesh, range: Range<u32>, flags: &[bool]) -> Vec<(u32, u32)> {
    let n = flags.len();
    let mut used = vec![false; n];
    let mut out = Vec::new();
    let shared = |a: usize, b: usize| {
        let (x, y) = (
            mesh.tris[range.start as usize + a],
            mesh.tris[range.start as usize + b],
        );
        let common: Vec<u32> = x.iter().copied().filter(|k| y.contains(k)).collect();
        match common[..] {
            [p, q] => (mesh.verts[p as usize].point - mesh.verts[q as usize].point).length(),
            _ => -1.0,
        }
    };
    for i in 0..n {
        if flags[i] || used[i] {
            continue;
        }
        let next = (i + 1 < n && !used[i + 1]).then_some(i + 1);
        let previous = (i > 0 && !used[i - 1]).then(|| i - 1);
        let failed = |j: Option<usize>| j.filter(|&j| !flags[j]);
        let partner = failed(next)
            .or(failed(previous))
            .or(match (previous, next) {
                (Some(p), Some(q)) => Some(if shared(i, p) >= shared(i, q) { p } else { q }),
                (p, q) => p.or(q),
            });
        if let Some(j) = partner.filter(|&j| shared(i, j) > 0.0) {
            used[i] = true;
            used[j] = true;
            out.push((range.start + i.min(j) as u32, range.start + i.max(j) as u32));
        }
    }
    out
}

/// The quad of triangles `s` and `t`, which share an edge.
fn quad(mesh: &TriMesh, s: u32, t: u32) -> Option<Quad> {
    let (a, b) = (mesh.tris[s as usize], mesh.tris[t as usize]);
    // Edge i of `a` (a[i] → a[i + 1]) runs the other way in `b`.
    let (i, j) = (0..3).find_map(|i| {
        let (p, q) = (a[i], a[(i + 1) % 3]);
        (0..3)
            .find(|&j| b[j] == q && b[(j + 1) % 3] == p)
            .map(|j| (i, j))
    })?;
    let (p, q, r) = (a[i], a[(i + 1) % 3], a[(i + 2) % 3]);
    let x = b[(j + 2) % 3];
    // Boundary counter-clockwise: q → r → p (in `a`), p → x → q (in `b`).
    let (fa, fb) = (mesh.fixed[s as usize], mesh.fixed[t as usize]);
    let corners = [q, r, p, x];
    let fixed = [
        fa[(i + 1) % 3],
        fa[(i + 2) % 3],
        fb[(j + 1) % 3],
        fb[(j + 2) % 3],
    ];
    let centre = corners
        .iter()
        .map(|&k| mesh.verts[k as usize].uv)
        .sum::<DVec2>()
        / 4.0;
    Some(Quad {
        pair: [s, t],
        corners,
        fixed,
        centre,
    })
}

/// Rounds of [`bisect`].
const BISECT_ROUNDS: usize = 3;

/// Splits what `mend` left outside the limits: the edge of each failing triangle
/// whose chord strays farthest from the surface at its middle (the longest among
/// equals) is cut at the surface point of its parametric midpoint, with the
/// triangle across it (conforming), and the four new
/// triangles are screened; up to [`BISECT_ROUNDS`] times. Loop segments and the
/// seam (edges with no triangle across them here) are not cut: a triangle failing
/// there is left to refinement, as is anything still failing after the last round.
/// Returns the number of vertices added.
pub(super) fn bisect(
    info: &PatchInfo,
    screen: &Screen,
    mesh: &mut TriMesh,
    within: &mut Vec<bool>,
) -> Result<usize, CdtError> {
    let mut added = 0;
    for _ in 0..BISECT_ROUNDS {
        let failing: Vec<u32> = (0..within.len() as u32)
            .filter(|&t| !within[t as usize])
            .collect();
        if failing.is_empty() {
            break;
        }
        // The longest interior edge of each failing triangle, by its directed
        // vertex pair (ranked in parallel: three surface points per triangle).
        let choose = |&t: &u32| {
            let tri = mesh.tris[t as usize];
            // Each edge by how far its chord's midpoint lies off the surface (the
            // edge that bends most is the one to cut: on a course, the short edge
            // round the axis, not the long straight one along it), then by length.
            let rank = |i: usize| {
                let (p, q) = (
                    &mesh.verts[tri[i] as usize],
                    &mesh.verts[tri[(i + 1) % 3] as usize],
                );
                let uv = 0.5 * (p.uv + q.uv);
                let sagitta = (info.surface.point(info.wrap_u(uv.x), uv.y)
                    - 0.5 * (p.point + q.point))
                    .length();
                let sagitta = if sagitta.is_finite() { sagitta } else { 0.0 };
                // Sagittas within a hundredth of the tolerance count as equal.
                let bend = (sagitta / (0.01 * screen.tolerance())).floor();
                (bend, (p.point - q.point).length_squared())
            };
            let i = (0..3)
                .filter(|&i| !mesh.fixed[t as usize][i])
                .map(|i| (i, rank(i)))
                .max_by(|(_, a), (_, b)| a.0.total_cmp(&b.0).then(a.1.total_cmp(&b.1)))
                .map(|(i, _)| i)?;
            let (p, q) = (tri[i], tri[(i + 1) % 3]);
            let pole = mesh.verts[p as usize].pole || mesh.verts[q as usize].pole;
            (!pole).then_some(((p, q), (t, i)))
        };
        let wanted: rustc_hash::FxHashMap<(u32, u32), (u32, usize)> = failing
            .par_iter()
            .with_min_len(crate::mesh::cdt::MIN_VERTICES)
            .filter_map(choose)
            .collect();
        // The triangles across those edges: each holds the wanted edge's first
        // vertex, so only triangles with a marked vertex are looked up.
        let mut marked = vec![false; mesh.verts.len()];
        for &(p, _) in wanted.keys() {
            marked[p as usize] = true;
        }
        let mut cuts: Vec<[(u32, usize); 2]> = Vec::new();
        let mut taken = vec![false; mesh.tris.len()];
        for (s, tri) in mesh.tris.iter().enumerate() {
            if !tri.iter().any(|&k| marked[k as usize]) {
                continue;
            }
            for j in 0..3 {
                let key = (tri[(j + 1) % 3], tri[j]);
                if let Some(&(t, i)) = wanted.get(&key)
                    && !taken[t as usize]
                    && !taken[s]
                {
                    taken[t as usize] = true;
                    taken[s] = true;
                    cuts.push([(t, i), (s as u32, j)]);
                }
            }
        }
        if cuts.is_empty() {
            break;
        }
        added += cuts.len();
        let mids: Vec<_> = cuts
            .par_iter()
            .with_min_len(crate::mesh::cdt::MIN_VERTICES)
            .map(|[(t, i), _]| {
                let tri = mesh.tris[*t as usize];
                let (p, q) = (tri[*i], tri[(*i + 1) % 3]);
                info.vertex(0.5 * (mesh.verts[p as usize].uv + mesh.verts[q as usize].uv))
            })
            .collect::<Result<_, _>>()?;
        let mut changed = Vec::with_capacity(4 * cuts.len());
        for (cut, mid) in cuts.iter().zip(mids) {
            let m = mesh.push_vertex(mid);
            for &(t, i) in cut {
                let tri = mesh.tris[t as usize];
                let fixed = mesh.fixed[t as usize];
                let (p, q, r) = (tri[i], tri[(i + 1) % 3], tri[(i + 2) % 3]);
                let (fq, fr) = (fixed[(i + 1) % 3], fixed[(i + 2) % 3]);
                // (p, q, r) → (p, m, r) in place and (m, q, r) appended.
                mesh.tris[t as usize] = [p, m, r];
                mesh.fixed[t as usize] = [false, false, fr];
                mesh.tris.push([m, q, r]);
                mesh.fixed.push([false, fq, false]);
                mesh.adj.push([NONE; 3]);
                mesh.touched.push(0);
                within.push(false);
                changed.push(t);
                changed.push(mesh.tris.len() as u32 - 1);
            }
        }
        let flags = screen.triangles(mesh, &changed);
        for (&t, ok) in changed.iter().zip(flags) {
            within[t as usize] = ok;
        }
    }
    Ok(added)
}
