//! The mesher's result: the refined triangulation welded into a [`Mesh`], with the
//! (u, v) of every output vertex and the counts of what happened.
//!
//! Vertices that map to one 3D point (within 10⁻¹² of the patch size) become one
//! vertex: all vertices on a collapsed side (a pole, an apex) and the two copies of
//! a point on the seam of a patch closed in u (the only vertices looked up). Triangles that lose a vertex to the
//! weld are dropped and counted; any other triangle must have positive area and a
//! normal agreeing with the exact normals at its vertices, or the mesh is withheld
//! with an error.

use std::ops::Range;

use rayon::prelude::*;
use rustc_hash::FxHashMap as HashMap;

use glam::{DVec2, DVec3};

use super::CdtError;
use super::patch::PatchInfo;
use super::stats::MeshStats;
use super::structured::lattice::Copies;
use super::trimesh::TriMesh;
use crate::mesh::Mesh;

/// Relative twice-area (to the squared longest edge) below which a triangle is flat.
const FLAT: f64 = 1e-10;

/// A meshed region: the mesh, the parameters of its vertices and the statistics.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct RegionMesh {
    /// The triangle mesh.
    pub mesh: Mesh,
    /// (u, v) of each vertex as in the loops (u not wrapped); for a welded vertex,
    /// those of its first copy (a loop vertex when there is one).
    pub uvs: Vec<DVec2>,
    /// For each vertex, whether it ends a loop segment of the region (a fixed
    /// edge of the triangulation, the seam's included): every vertex on an edge
    /// that one triangle alone uses is one, since such edges are loop segments.
    /// The packer stores these exactly without recounting the mesh's edges
    /// ([`PackedMesh::pack_marked`](crate::mesh::PackedMesh::pack_marked)).
    pub on_loops: Vec<bool>,
    /// What happened.
    pub stats: MeshStats,
}

impl RegionMesh {
    /// The mesh of the transposed problem mapped back: (u, v) exchanged, normals
    /// turned over (`S_v × S_u = −S_u × S_v`) and triangles rewound so they are
    /// counter-clockwise in the original (u, v).
    pub(super) fn transposed(mut self) -> RegionMesh {
        for uv in &mut self.uvs {
            *uv = DVec2::new(uv.y, uv.x);
        }
        for n in &mut self.mesh.normals {
            *n = -*n;
        }
        for tri in self.mesh.indices.chunks_mut(3) {
            tri.swap(1, 2);
        }
        self
    }
}

/// Smallest interior angle of a triangle, as `(|a × b|, a · b)` of its two edges
/// at the vertex opposite its shortest side: the angle is their `atan2`, at most
/// 60°, so the pairs compare by `sin·cos'` against `sin'·cos` with no
/// trigonometry per triangle. `sides` are the squared lengths of the sides
/// (side i from vertex i to vertex i + 1) and `cross` is |a × b| (the same at
/// every vertex: twice the area), both computed already by the caller.
fn min_angle(p: [DVec3; 3], sides: [f64; 3], cross: f64) -> (f64, f64) {
    // The shortest side k is opposite vertex k + 2.
    let k = (0..3)
        .min_by(|&a, &b| sides[a].total_cmp(&sides[b]))
        .unwrap_or(0);
    let i = (k + 2) % 3;
    let (a, b) = (p[(i + 1) % 3] - p[i], p[(i + 2) % 3] - p[i]);
    (cross, a.dot(b))
}

/// Triangles per chunk of the output's checks.
const CHUNK: usize = 4096;

/// The checked triangles of one chunk.
struct Checked {
    /// Their welded indices, in order.
    indices: Vec<u32>,
    /// Triangles dropped because welding collapsed them.
    dropped: usize,
    /// The smallest angle, as [`min_angle`] gives it.
    smallest: (f64, f64),
}

/// The smaller of two angles as [`min_angle`] gives them (`a` when equal).
fn smaller(a: (f64, f64), b: (f64, f64)) -> (f64, f64) {
    if b.0 * a.1 < a.0 * b.1 { b } else { a }
}

/// Welds `mesh` into the output, checking every triangle (flat, collapsed or
/// turned against the surface normals is an error); with `copies`, a triangle
/// that is an exact quarter turn of one checked already (see
/// [`Copies`]) is only checked for collapse by welding.
pub(super) fn finish(
    info: &PatchInfo,
    mesh: &TriMesh,
    copies: Option<&Copies>,
    mut stats: MeshStats,
) -> Result<RegionMesh, CdtError> {
    let tol = info.weld_tolerance;
    let cell = |p: DVec3| {
        let c = (p / tol).floor();
        (c.x as i64, c.y as i64, c.z as i64)
    };
    let mut grid: HashMap<(i64, i64, i64), Vec<u32>> = HashMap::default();
    // Only vertices on a collapsed side (a pole) or on the seam of a region that
    // spans a whole period of a surface closed in u (its two sides at u = lo and
    // lo + period, the same points) can share a 3D point with another vertex: any
    // other two points of the region are distinct points of the surface.
    let ((u0, u1), _) = info.surface.domain();
    let period = u1 - u0;
    let lo = mesh
        .verts
        .iter()
        .map(|v| v.uv.x)
        .fold(f64::INFINITY, f64::min);
    let on_seam = |uv: DVec2| {
        if !info.closed_u {
            return false;
        }
        // `lo` is the least u, so the offset is rarely a period or more: the
        // remainder of one in [0, period) is the offset itself, without the
        // library's `fmod` (a call per vertex of every closed patch).
        let offset = uv.x - lo;
        let r = if (0.0..period).contains(&offset) {
            offset
        } else {
            offset.rem_euclid(period)
        };
        r.min(period - r) <= 1e-9 * period
    };
    let mut used = vec![false; mesh.verts.len()];
    // The ends of fixed edges (loop segments), by mesh vertex.
    let mut on_loop = vec![false; mesh.verts.len()];
    for (tri, fixed) in mesh.tris.iter().zip(&mesh.fixed) {
        for i in 0..3 {
            used[tri[i] as usize] = true;
            if fixed[i] {
                on_loop[tri[i] as usize] = true;
                on_loop[tri[(i + 1) % 3] as usize] = true;
            }
        }
    }
    let mut out = RegionMesh::default();
    let expected = mesh.verts.len();
    out.mesh.positions.reserve(expected);
    out.mesh.normals.reserve(expected);
    out.uvs.reserve(expected);
    out.on_loops.reserve(expected);
    out.mesh.indices.reserve(3 * mesh.tris.len());
    let mut index = vec![u32::MAX; mesh.verts.len()];
    for (k, v) in mesh.verts.iter().enumerate() {
        if !used[k] {
            continue;
        }
        if !(v.pole || on_seam(v.uv)) {
            index[k] = out.mesh.positions.len() as u32;
            out.mesh.positions.push(v.point);
            out.mesh.normals.push(v.normal);
            out.uvs.push(v.uv);
            out.on_loops.push(on_loop[k]);
            continue;
        }
        let c = cell(v.point);
        let mut found = None;
        'search: for dx in -1..=1 {
            for dy in -1..=1 {
                for dz in -1..=1 {
                    let Some(list) = grid.get(&(c.0 + dx, c.1 + dy, c.2 + dz)) else {
                        continue;
                    };
                    if let Some(&o) = list
                        .iter()
                        .find(|&&o| (out.mesh.positions[o as usize] - v.point).length() <= tol)
                    {
                        found = Some(o);
                        break 'search;
                    }
                }
            }
        }
        index[k] = match found {
            Some(o) => {
                out.on_loops[o as usize] |= on_loop[k];
                o
            }
            None => {
                let o = out.mesh.positions.len() as u32;
                out.mesh.positions.push(v.point);
                out.mesh.normals.push(v.normal);
                out.uvs.push(v.uv);
                out.on_loops.push(on_loop[k]);
                grid.entry(c).or_default().push(o);
                o
            }
        };
    }
    // The triangles, welded and checked a chunk at a time (in parallel on a
    // large patch: this was a serial tail of every big head's mesh), then joined
    // in order, so the result is the same for any number of threads.
    let check = |range: Range<usize>| -> Result<Checked, CdtError> {
        let mut chunk = Checked {
            indices: Vec::with_capacity(3 * range.len()),
            dropped: 0,
            smallest: (1.0, 0.0),
        };
        for t in range {
            let tri = mesh.tris[t];
            let welded = tri.map(|k| index[k as usize]);
            if welded[0] == welded[1] || welded[1] == welded[2] || welded[2] == welded[0] {
                chunk.dropped += 1;
                continue;
            }
            if copies.is_some_and(|c| {
                c.per_quarter > 0 && t >= c.per_quarter && c.exact[t % c.per_quarter]
            }) {
                chunk.indices.extend_from_slice(&welded);
                continue;
            }
            let p = welded.map(|k| out.mesh.positions[k as usize]);
            let normal = (p[1] - p[0]).cross(p[2] - p[0]);
            // Side i runs from vertex i to vertex i + 1.
            let sides = [0, 1, 2].map(|i| (p[(i + 1) % 3] - p[i]).length_squared());
            let longest = sides.into_iter().fold(0.0, f64::max);
            let turned = tri
                .iter()
                .any(|&k| mesh.verts[k as usize].normal.dot(normal) <= 0.0);
            let area = normal.length();
            if area.is_nan() || area <= FLAT * longest || turned {
                return Err(CdtError::InvalidTriangle { triangle: t });
            }
            chunk.smallest = smaller(chunk.smallest, min_angle(p, sides, area));
            chunk.indices.extend_from_slice(&welded);
        }
        Ok(chunk)
    };
    let count = mesh.tris.len();
    let chunks: Vec<Range<usize>> = (0..count.div_ceil(CHUNK))
        .map(|c| c * CHUNK..((c + 1) * CHUNK).min(count))
        .collect();
    let checked: Vec<Result<Checked, CdtError>> = if chunks.len() > 1 {
        chunks.into_par_iter().map(check).collect()
    } else {
        chunks.into_iter().map(check).collect()
    };
    // The smallest angle so far as (sine-like, cosine-like); (1, 0) is 90°.
    let mut smallest = (1.0, 0.0);
    for chunk in checked {
        let chunk = chunk?;
        stats.dropped_degenerate += chunk.dropped;
        smallest = smaller(smallest, chunk.smallest);
        out.mesh.indices.extend_from_slice(&chunk.indices);
    }
    stats.triangles = out.mesh.triangle_count();
    stats.min_angle_deg = if out.mesh.indices.is_empty() {
        0.0
    } else {
        smallest.0.atan2(smallest.1).to_degrees()
    };
    out.stats = stats;
    Ok(out)
}
