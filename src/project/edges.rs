//! Boundary and seam edges of a patch, from its mesh: the patch's sides, the
//! trimming loops of its openings and the tangent lines where it meets the next
//! patch.
//!
//! The mesh's boundary vertices lie on the exact edge curves (the mesher samples
//! shared edges once, from the curve), so these polylines are the exact edges to
//! the chordal tolerance. Vertices at the same position (the two sides of a closed
//! patch's parameter seam, a collapsed pole) are welded first, so the parameter
//! seam of a cylinder and the pole of a head are not drawn: only real edges are.

use rustc_hash::FxHashMap as HashMap;

use glam::{DAffine3, DVec3};

use super::silhouette::SurfacePoint;
use crate::mesh::Mesh;

/// Welding grid, mm: positions closer than this (after rounding) are one vertex.
const WELD: f64 = 1e-6;

/// The boundary polylines of `mesh` (part frame), mapped by `frame` into the vessel
/// frame, with the exact normals of their vertices. Closed loops repeat their
/// first point at the end.
pub fn boundary_polylines(mesh: &Mesh, frame: &DAffine3) -> Vec<Vec<SurfacePoint>> {
    let key = |p: DVec3| {
        (
            (p.x / WELD).round() as i64,
            (p.y / WELD).round() as i64,
            (p.z / WELD).round() as i64,
        )
    };
    let mut ids: HashMap<(i64, i64, i64), u32> = HashMap::default();
    let mut first: Vec<usize> = Vec::new();
    let welded: Vec<u32> = mesh
        .positions
        .iter()
        .enumerate()
        .map(|(i, &p)| {
            *ids.entry(key(p)).or_insert_with(|| {
                first.push(i);
                (first.len() - 1) as u32
            })
        })
        .collect();
    let mut directed: HashMap<(u32, u32), u32> = HashMap::default();
    for t in mesh.indices.chunks_exact(3) {
        for k in 0..3 {
            let (a, b) = (welded[t[k] as usize], welded[t[(k + 1) % 3] as usize]);
            if a != b {
                *directed.entry((a, b)).or_default() += 1;
            }
        }
    }
    // Boundary: a directed edge without its reverse.
    let mut next: HashMap<u32, Vec<u32>> = HashMap::default();
    let mut edges: Vec<(u32, u32)> = directed
        .keys()
        .filter(|(a, b)| !directed.contains_key(&(*b, *a)))
        .copied()
        .collect();
    edges.sort_unstable();
    for &(a, b) in &edges {
        next.entry(a).or_default().push(b);
    }
    let mut incoming: HashMap<u32, usize> = HashMap::default();
    for &(_, b) in &edges {
        *incoming.entry(b).or_default() += 1;
    }
    let point = |w: u32| {
        let i = first[w as usize];
        SurfacePoint {
            point: frame.transform_point3(mesh.positions[i]),
            normal: (frame.matrix3 * mesh.normals[i]).normalize(),
        }
    };
    let mut used: HashMap<(u32, u32), bool> = HashMap::default();
    let mut out = Vec::new();
    // Open chains start where nothing comes in; then loops.
    let mut starts: Vec<(u32, u32)> = edges
        .iter()
        .filter(|(a, _)| !incoming.contains_key(a))
        .copied()
        .collect();
    starts.extend(edges.iter().copied());
    for (a, b) in starts {
        if used.contains_key(&(a, b)) {
            continue;
        }
        used.insert((a, b), true);
        let mut chain = vec![a, b];
        let mut end = b;
        while let Some(&c) = next
            .get(&end)
            .and_then(|n| n.iter().find(|&&c| !used.contains_key(&(end, c))))
        {
            used.insert((end, c), true);
            chain.push(c);
            end = c;
            if c == a {
                break;
            }
        }
        out.push(chain.into_iter().map(point).collect());
    }
    out
}
