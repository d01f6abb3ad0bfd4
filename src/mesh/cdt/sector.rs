//! Whole surfaces of revolution meshed a quarter turn at a time.
//!
//! Sits in front of the structured path (`rings`): a head, a plain course or a
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
//! control points are turned copies to rounding, which [`quarter`] checks).

use glam::{DVec2, DVec3, DVec4};

use super::CdtError;
use super::lattice::{Copies, Rings};
use super::patch::PatchInfo;
use super::region::{Region, UvLoop};
use super::trimesh::{NONE, TriMesh};
use crate::nurbs::builders::FULL_TURN_KNOTS;

/// Quarters of the turn.
pub(super) const QUARTERS: usize = 4;
/// Largest difference, relative to the surface's size, between a quarter's
/// control points and the first quarter's turned, and between the rings' spacing
/// in different quarters (relative to the period).
const SYMMETRY: f64 = 1e-12;

/// The first quarter of `region` — the patch's whole parameter rectangle, closed
/// in u, without holes — when the patch and its rings repeat every quarter turn
/// about Z; `None` otherwise.
pub(super) fn quarter(info: &PatchInfo, region: &Region) -> Option<Region> {
    if !info.closed_u || !region.holes.is_empty() || !quarter_turned(info) {
        return None;
    }
    let ((u0, u1), _) = info.surface.domain();
    let (lo, hi) = region.bounds();
    if lo.x != u0 || hi.x != u1 {
        return None;
    }
    let width = (u1 - u0) / QUARTERS as f64;
    let eps = SYMMETRY * (u1 - u0);
    let pts = &region.outer.uv;
    // Every loop vertex on the rectangle; the two rings' u values.
    let on = |a: f64, b: f64| (a - b).abs() <= eps;
    if !pts
        .iter()
        .all(|p| p.y == lo.y || p.y == hi.y || on(p.x, lo.x) || on(p.x, hi.x))
    {
        return None;
    }
    let ring = |v: f64| {
        let mut u: Vec<f64> = pts.iter().filter(|p| p.y == v).map(|p| p.x).collect();
        u.sort_by(f64::total_cmp);
        u.dedup();
        u
    };
    let first = |u: &[f64]| -> Option<Vec<f64>> {
        // A pole: its two corners only.
        if u.len() == 2 {
            return Some(vec![u0, u0 + width]);
        }
        let n = u.len() - 1;
        if !n.is_multiple_of(QUARTERS) || !on(u[0], u0) || !on(u[n], u1) {
            return None;
        }
        let m = n / QUARTERS;
        let repeats =
            (1..QUARTERS).all(|q| (0..=m).all(|k| on(u[q * m + k], u[k] + q as f64 * width)));
        if !repeats {
            return None;
        }
        let mut part = u[..=m].to_vec();
        part[0] = u0;
        part[m] = u0 + width;
        Some(part)
    };
    let bottom = first(&ring(lo.y))?;
    let top = first(&ring(hi.y))?;
    // The quarter's rectangle: the bottom ring left to right, the top ring back.
    let mut outer: Vec<DVec2> = bottom.iter().map(|&u| DVec2::new(u, lo.y)).collect();
    outer.extend(top.iter().rev().map(|&u| DVec2::new(u, hi.y)));
    Some(Region::new(UvLoop::new(outer)))
}

/// Whether the surface is a full turn about Z in four quarter spans, each
/// quarter's control points the first quarter's turned by its multiple of 90°.
fn quarter_turned(info: &PatchInfo) -> bool {
    let s = info.surface;
    let knots = s.u_knots();
    if knots.degree() != 2 || knots.as_slice() != FULL_TURN_KNOTS {
        return false;
    }
    let points = s.homogeneous_points();
    let nu = 2 * QUARTERS + 1;
    if !points.len().is_multiple_of(nu) {
        return false;
    }
    let nv = points.len() / nu;
    let size = points
        .iter()
        .map(|p| p.truncate().length())
        .fold(0.0f64, f64::max)
        .max(1.0);
    let eps = SYMMETRY * size;
    // Column c is column c mod 2 of the first quarter turned c / 2 times (the
    // last, c = 8, closes the turn onto the first).
    (2..nu).all(|c| {
        (0..nv).all(|j| {
            let turned = turn_h(points[(c % 2) * nv + j], c / 2);
            (turned - points[c * nv + j]).abs().max_element() <= eps
        })
    })
}

/// `p` turned by `q` quarter turns about Z, exactly.
pub(super) fn turn(p: DVec3, q: usize) -> DVec3 {
    // Adding 0.0 turns a −0.0 into 0.0, so that points on the axis stay bitwise
    // the same.
    match q % QUARTERS {
        0 => p,
        1 => DVec3::new(-p.y + 0.0, p.x, p.z),
        2 => DVec3::new(-p.x + 0.0, -p.y + 0.0, p.z),
        _ => DVec3::new(p.y, -p.x + 0.0, p.z),
    }
}

/// [`turn`] of a homogeneous point.
fn turn_h(p: DVec4, q: usize) -> DVec4 {
    turn(p.truncate(), q).extend(p.w)
}

/// The structured mesh of the whole turn from that of its first quarter, meshed
/// within `quarter` (see [`quarter`]): the quarter's vertices turned into the
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
