//! Whole surfaces of revolution meshed a quarter turn at a time.
//!
//! Sits in front of the structured path (`structured`): a head, a plain course or a
//! flange face is a profile turned a full turn about Z in four rational quarter
//! arcs, each the one before it turned by 90°. When the patch has no openings and
//! its two rings (the loop vertices its neighbours share) are spaced alike in
//! every quarter — circle edges are sampled in multiples of eight segments, so
//! they are — the structured mesh of one quarter, with its two meridian edges
//! treated as the seam is (rows end on them, nothing is inserted on them), is the
//! mesh of every quarter. Rows, zipping, screening and mending run on the first
//! quarter only; the other three are its vertices turned by an exact quarter turn
//! ((x, y) → (−y, x): no rounding), the ring vertices evaluated where they are so
//! that neighbours share them to the bit, and the meridian vertices shared between
//! neighbouring quarters. A big head's meshing costs about a quarter of what it
//! did, and every vertex is within rounding of the surface (the quarters'
//! control points are turned copies to rounding, which `quarter::quarter`
//! checks).

use glam::DVec2;

use super::lattice::{Copies, Rings};
use crate::mesh::cdt::CdtError;
use crate::mesh::cdt::patch::PatchInfo;
use crate::mesh::cdt::quarter::{QUARTERS, turn};
use crate::mesh::cdt::region::Region;
use crate::mesh::cdt::trimesh::{NONE, TriMesh};

/// The structured mesh of the whole turn from that of its first quarter, meshed
/// within `quarter` (see `quarter::quarter`): the quarter's vertices turned into the
/// other three (ring vertices evaluated in place), the meridian between two
/// quarters shared, the triangles' flags and screen verdicts copied. The seam is
/// the first quarter's left meridian and the last quarter's right one. `None`
/// when the quarter's two meridians do not have their vertices at the same v.
pub(super) fn whole_turn(
    info: &PatchInfo,
    quarter: &Region,
    part: Rings,
) -> Result<Option<Rings>, CdtError> {
    let (lo, hi) = quarter.bounds();
    let width = hi.x - lo.x;
    let Rings {
        mesh,
        seam,
        within,
        insertions,
        ..
    } = part;
    let n = mesh.verts.len();
    // Each left-meridian vertex and the right-meridian vertex at its v.
    let left: Vec<usize> = (0..n)
        .filter(|&k| !mesh.verts[k].pole && mesh.verts[k].uv.x == lo.x)
        .collect();
    let mut right: Vec<(f64, usize)> = (0..n)
        .filter(|&k| !mesh.verts[k].pole && mesh.verts[k].uv.x == hi.x)
        .map(|k| (mesh.verts[k].uv.y, k))
        .collect();
    right.sort_by(|a, b| a.0.total_cmp(&b.0));
    if left.len() != right.len() {
        return Ok(None);
    }
    let mut across = vec![u32::MAX; n];
    for &k in &left {
        let v = mesh.verts[k].uv.y;
        let Ok(at) = right.binary_search_by(|(w, _)| w.total_cmp(&v)) else {
            return Ok(None);
        };
        across[k] = right[at].1 as u32;
    }
    let ring = |uv: DVec2| uv.y == lo.y || uv.y == hi.y;
    // A later quarter's copy of vertex k is its exact quarter turn unless it is
    // evaluated in place (a ring vertex), on a meridian (the left one is the
    // previous quarter's right one; the last quarter's right one welds to the
    // first quarter's left one) or at a pole (welded).
    let turned_exactly: Vec<bool> = mesh
        .verts
        .iter()
        .map(|v| v.uv.x != lo.x && v.uv.x != hi.x && !ring(v.uv) && !v.pole)
        .collect();
    let exact: Vec<bool> = mesh
        .tris
        .iter()
        .map(|t| t.iter().all(|&k| turned_exactly[k as usize]))
        .collect();
    // Every quarter has the first one's triangles, flags and screen verdicts;
    // no neighbour links (as every structured mesh): refinement builds them.
    let count = QUARTERS * mesh.tris.len();
    let mut out = TriMesh {
        verts: Vec::with_capacity(QUARTERS * n),
        tris: Vec::with_capacity(count),
        adj: vec![[NONE; 3]; count],
        fixed: mesh.fixed.repeat(QUARTERS),
        touched: mesh.touched.repeat(QUARTERS),
        pass: mesh.pass,
    };
    out.verts.extend_from_slice(&mesh.verts);
    out.tris.extend_from_slice(&mesh.tris);
    // `index[k]`: where vertex k of the quarter went in the current quarter.
    let mut previous: Vec<u32> = (0..n as u32).collect();
    let mut seam_all: Vec<(u32, usize)> = seam
        .iter()
        .copied()
        .filter(|&(t, i)| {
            let tri = mesh.tris[t as usize];
            mesh.verts[tri[i] as usize].uv.x == lo.x
        })
        .collect();
    for q in 1..QUARTERS {
        let shift = q as f64 * width;
        let mut index = vec![u32::MAX; n];
        for k in 0..n {
            if across[k] != u32::MAX {
                // The left meridian is the previous quarter's right one.
                index[k] = previous[across[k] as usize];
                continue;
            }
            let v = &mesh.verts[k];
            let uv = DVec2::new(v.uv.x + shift, v.uv.y);
            let vertex = if ring(v.uv) && !v.pole {
                let mut own = info.vertex_lazy(uv)?;
                own.metric = v.metric;
                own
            } else {
                let mut turned = *v;
                turned.uv = uv;
                turned.point = turn(v.point, q);
                turned.normal = turn(v.normal, q);
                turned
            };
            index[k] = out.verts.len() as u32;
            out.verts.push(vertex);
        }
        let base = out.tris.len() as u32;
        out.tris
            .extend(mesh.tris.iter().map(|t| t.map(|k| index[k as usize])));
        if q + 1 == QUARTERS {
            seam_all.extend(seam.iter().copied().filter_map(|(t, i)| {
                let tri = mesh.tris[t as usize];
                (mesh.verts[tri[i] as usize].uv.x == hi.x).then_some((base + t, i))
            }));
        }
        previous = index;
    }
    Ok(Some(Rings {
        mesh: out,
        seam: seam_all,
        within: within.map(|w| w.repeat(QUARTERS)),
        insertions: QUARTERS * insertions,
        copies: Some(Copies {
            per_quarter: mesh.tris.len(),
            exact,
        }),
    }))
}
