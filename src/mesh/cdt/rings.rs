//! The structured path: a whole patch closed in u (a head, a course, a cone, a
//! flange face — no opening in it) meshed ring by ring without a triangulation
//! search.
//!
//! Such a patch's region is its parameter rectangle cut at a seam: the two v sides
//! (given rings of loop vertices, or a pole) and the two copies of the seam. The
//! seed lattice's rows (see `seed`) already are parallels sized by the curvature
//! metric; here every row runs from seam to seam and consecutive rows — the bottom
//! ring, the rows, the top ring — are zipped into a strip of triangles, choosing at
//! each step the shorter diagonal in 3D. A pole is met by a fan of sector-shaped
//! triangles whose pole vertices weld into one on output. The seam's vertices are
//! the rows' ends (the seam belongs to this patch alone, so no neighbour has to
//! agree with them); the v sides keep the loop's vertices exactly.
//!
//! The result goes through the same checks as the general path (every triangle's
//! deviation, angle and edge limits, seam edges included): when all pass it is the
//! mesh; otherwise the caller refines it like any other. No spade, no flood fill and
//! no hashing in the common case: this is where whole heads and courses get their
//! speed.

use std::ops::Range;

use glam::DVec2;
use rayon::prelude::*;

use super::patch::{PatchInfo, Vertex};
use super::region::Region;
use super::trimesh::{NONE, TriMesh};
use super::{CdtError, seed};

/// Relative tolerance (to the region's extent) of "on a side of the rectangle".
const ON_SIDE: f64 = 1e-12;

/// A v side of the region: its loop vertices' u values (increasing, seam to seam),
/// or a pole.
enum Side {
    Ring(Vec<f64>),
    Pole,
}

/// A structured mesh of a whole closed patch.
pub(super) struct Rings {
    /// The triangles, strip by strip from the bottom chain up.
    pub mesh: TriMesh,
    /// The seam edges, as `(triangle, edge)`: left unfixed so that the checks probe
    /// them; the caller fixes them (with [`fix_seam`]) before output or refinement.
    pub seam: Vec<(u32, usize)>,
    /// Each strip's range of triangles.
    pub strips: Vec<Range<u32>>,
}

/// The structured mesh of `region` when it is a whole patch closed in u; `None`
/// for any other region.
pub(super) fn triangulate(
    info: &PatchInfo,
    region: &Region,
    budget: usize,
) -> Result<Option<Rings>, CdtError> {
    let Some((bottom, top)) = sides(info, region) else {
        return Ok(None);
    };
    let (lo, hi) = region.bounds();
    let rows = seed::rows(info, region, budget)?;
    if rows.is_empty() && matches!((&bottom, &top), (Side::Pole, Side::Pole)) {
        return Ok(None);
    }
    // Chains bottom to top: (v, u values) or a pole at v.
    let mut chains: Vec<(f64, Option<Vec<f64>>)> = Vec::with_capacity(rows.len() + 2);
    chains.push((lo.y, ring(bottom)));
    chains.extend(rows.into_iter().map(|(v, u)| (v, Some(u))));
    chains.push((hi.y, ring(top)));
    let uvs: Vec<Vec<DVec2>> = chains
        .iter()
        .map(|(v, u)| {
            u.as_ref()
                .map(|u| u.iter().map(|&u| DVec2::new(u, *v)).collect())
                .unwrap_or_default()
        })
        .collect();
    let mut verts: Vec<Vertex> = Vec::new();
    let mut first: Vec<u32> = Vec::with_capacity(uvs.len());
    let evaluated: Vec<Vec<Vertex>> = uvs
        .par_iter()
        .map(|row| row.iter().map(|&uv| info.vertex(uv)).collect())
        .collect::<Result<_, _>>()?;
    for row in evaluated {
        first.push(verts.len() as u32);
        verts.extend(row);
    }
    let mut mesh = TriMesh {
        verts,
        ..TriMesh::default()
    };
    let mut seam = Vec::new();
    let mut strips = Vec::with_capacity(chains.len());
    let last_chain = chains.len() - 1;
    for k in 0..last_chain {
        let start = mesh.tris.len() as u32;
        let (a, b) = (&uvs[k], &uvs[k + 1]);
        match (a.is_empty(), b.is_empty()) {
            (false, false) => zip(
                &mut mesh,
                (first[k], a.len()),
                (first[k + 1], b.len()),
                &mut seam,
            ),
            (true, false) => fan(info, &mut mesh, (first[k + 1], b.len()), chains[k].0, true)?,
            (false, true) => fan(info, &mut mesh, (first[k], a.len()), chains[k + 1].0, false)?,
            (true, true) => return Ok(None),
        }
        // The given v sides are loop segments.
        let side_row = if k == 0 {
            Some((first[0], a.len(), true))
        } else {
            None
        };
        let top_row = (k + 1 == last_chain).then(|| (first[k + 1], b.len(), false));
        for (start, len, bottom) in side_row.into_iter().chain(top_row) {
            if len > 0 {
                fix_ring(&mut mesh, start, len, bottom);
            }
        }
        strips.push(start..mesh.tris.len() as u32);
    }
    Ok(Some(Rings { mesh, seam, strips }))
}

/// Marks the seam edges fixed (loop segments of the region).
pub(super) fn fix_seam(mesh: &mut TriMesh, seam: &[(u32, usize)]) {
    for &(t, i) in seam {
        mesh.fixed[t as usize][i] = true;
    }
}

/// The region's v sides, when it is a whole patch closed in u: one outer loop on
/// the rectangle `lo..hi` spanning one period, every vertex on one of its sides.
fn sides(info: &PatchInfo, region: &Region) -> Option<(Side, Side)> {
    if !info.closed_u || !region.holes.is_empty() {
        return None;
    }
    let (lo, hi) = region.bounds();
    let ((u0, u1), (v0, v1)) = info.surface.domain();
    let eps = ON_SIDE * ((hi - lo).max_element() + (u1 - u0) + (v1 - v0));
    if ((hi.x - lo.x) - (u1 - u0)).abs() > eps || hi.y - lo.y <= eps {
        return None;
    }
    let on = |a: f64, b: f64| (a - b).abs() <= eps;
    let pts = &region.outer.uv;
    if !pts
        .iter()
        .all(|p| on(p.y, lo.y) || on(p.y, hi.y) || on(p.x, lo.x) || on(p.x, hi.x))
    {
        return None;
    }
    let side = |v: f64, collapsed: bool| -> Option<Side> {
        let mut u: Vec<f64> = pts.iter().filter(|p| on(p.y, v)).map(|p| p.x).collect();
        u.sort_by(f64::total_cmp);
        if u.len() < 2 || !on(u[0], lo.x) || !on(u[u.len() - 1], hi.x) {
            return None;
        }
        if collapsed && u.len() == 2 {
            return Some(Side::Pole);
        }
        Some(Side::Ring(u))
    };
    let bottom = side(lo.y, info.collapsed[2] && on(lo.y, v0))?;
    let top = side(hi.y, info.collapsed[3] && on(hi.y, v1))?;
    Some((bottom, top))
}

/// A side's u values, `None` for a pole.
fn ring(side: Side) -> Option<Vec<f64>> {
    match side {
        Side::Ring(u) => Some(u),
        Side::Pole => None,
    }
}

/// Pushes a triangle (counter-clockwise in (u, v)) with no neighbours.
fn push(mesh: &mut TriMesh, tri: [u32; 3]) -> u32 {
    mesh.tris.push(tri);
    mesh.adj.push([NONE; 3]);
    mesh.fixed.push([false; 3]);
    mesh.touched.push(0);
    (mesh.tris.len() - 1) as u32
}

/// Zips the chain `a` (lower v) with the chain `b` (upper v), each `(first vertex,
/// count)` running seam to seam; records the two seam edges.
fn zip(mesh: &mut TriMesh, a: (u32, usize), b: (u32, usize), seam: &mut Vec<(u32, usize)>) {
    let (mut i, mut j) = (0usize, 0usize);
    let (na, nb) = (a.1 - 1, b.1 - 1);
    let at = |mesh: &TriMesh, k: u32| mesh.verts[k as usize].point;
    let mut first = true;
    while i < na || j < nb {
        let (ai, bj) = (a.0 + i as u32, b.0 + j as u32);
        let advance_a = if i == na {
            false
        } else if j == nb {
            true
        } else {
            // The shorter diagonal: a[i+1]–b[j] (advance a) or a[i]–b[j+1].
            let da = (at(mesh, ai + 1) - at(mesh, bj)).length_squared();
            let db = (at(mesh, ai) - at(mesh, bj + 1)).length_squared();
            da <= db
        };
        let t = if advance_a {
            i += 1;
            push(mesh, [ai, ai + 1, bj])
        } else {
            j += 1;
            push(mesh, [ai, bj + 1, bj])
        };
        if first {
            // Edge 2 (last vertex → first) of the first triangle is b[0]–a[0].
            seam.push((t, 2));
            first = false;
        }
        if i == na && j == nb {
            // The right seam a[na]–b[nb]: edge 1 of [a, a+1, b], edge 0 of
            // [a, b+1, b].
            seam.push((t, if advance_a { 1 } else { 0 }));
        }
    }
}

/// A fan from the chain `row` to the pole at `v`: one pole vertex under the
/// middle of each row segment (they weld into one on output). `below` when the
/// pole is under the row (lower v).
fn fan(
    info: &PatchInfo,
    mesh: &mut TriMesh,
    row: (u32, usize),
    v: f64,
    below: bool,
) -> Result<(), CdtError> {
    for k in 0..row.1 as u32 - 1 {
        let (x, y) = (row.0 + k, row.0 + k + 1);
        let u = 0.5 * (mesh.verts[x as usize].uv.x + mesh.verts[y as usize].uv.x);
        let p = mesh.push_vertex(info.vertex(DVec2::new(u, v))?);
        if below {
            push(mesh, [p, y, x]);
        } else {
            push(mesh, [x, y, p]);
        }
    }
    Ok(())
}

/// Marks the loop segments of a ring: the edges between consecutive ring vertices
/// `start..start + len` in the triangles of the strip above (`bottom`) or below it.
fn fix_ring(mesh: &mut TriMesh, start: u32, len: usize, bottom: bool) {
    let end = start + len as u32;
    let in_ring = |k: u32| (start..end).contains(&k);
    for t in 0..mesh.tris.len() {
        let tri = mesh.tris[t];
        for i in 0..3 {
            let (x, y) = (tri[i], tri[(i + 1) % 3]);
            // Ring segments run with increasing index along the bottom ring's
            // triangles and decreasing along the top ring's.
            let segment = if bottom { y == x + 1 } else { x == y + 1 };
            if in_ring(x) && in_ring(y) && segment {
                mesh.fixed[t][i] = true;
            }
        }
    }
}
