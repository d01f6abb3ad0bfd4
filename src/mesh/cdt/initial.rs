//! The initial constrained Delaunay triangulation, built by spade.
//!
//! Loop vertices and seeds go into spade in a chart of the parameter plane mapped
//! by the patch's mean size metric, so its Delaunay triangles are roughly the
//! shapes refinement wants; every coordinate is validated before insertion. Each loop segment
//! is then added as a constraint with `can_add_constraint` / `try_add_constraint`;
//! a segment that crosses another loop, or runs through another vertex, is an error
//! (the boundary would not be kept as given), as is a loop vertex that spade merged
//! with another. Seeds spade rejects are only counted. The triangles inside the
//! region are found by a flood fill from the left side of every loop segment that
//! never crosses a loop segment; reaching the convex hull means the loops do not
//! enclose a region. The result is copied into a [`TriMesh`] for refinement.

use std::collections::VecDeque;

use rustc_hash::{FxHashMap as HashMap, FxHashSet as HashSet};

use glam::DVec2;
use rayon::prelude::*;
use spade::{ConstrainedDelaunayTriangulation, HasPosition, Point2, Triangulation};

use super::metric::Metric;
use super::patch::PatchInfo;
use super::region::Region;
use super::trimesh::TriMesh;
use super::{CdtError, MeshStats};

/// A vertex in spade's chart, carrying its index in the mesher's vertex list.
#[derive(Clone, Copy, Debug)]
struct ChartVertex {
    position: Point2<f64>,
    id: u32,
}

impl HasPosition for ChartVertex {
    type Scalar = f64;

    fn position(&self) -> Point2<f64> {
        self.position
    }
}

/// The chart position of `uv`, validated for spade.
fn chart(metric: &Metric, uv: DVec2) -> Result<Point2<f64>, spade::InsertionError> {
    let p = metric.chart(uv);
    spade::validate_coordinate(p.x)?;
    spade::validate_coordinate(p.y)?;
    Ok(Point2::new(p.x, p.y))
}

/// Size of the seeds' offsets in the chart, in units of the target size.
const JITTER: f64 = 1e-7;

/// A seed's chart position moved by a deterministic offset of about [`JITTER`]:
/// the seed lattice is exactly regular, so four of its points are often
/// co-circular and spade's exact in-circle predicate leaves its fast filter for the
/// adaptive path on almost every test (half of a course's meshing time). The
/// offsets (a low-discrepancy sequence in the seed's index) break those ties
/// without moving any vertex: the seed keeps its (u, v), only the tie-break of
/// the triangulation changes, and refinement's flips settle the connectivity in
/// the true metric anyway.
fn jitter(position: Point2<f64>, k: usize) -> Point2<f64> {
    const PHI: f64 = 0.618_033_988_749_894_9;
    const PLASTIC: f64 = 0.754_877_666_246_692_8;
    let share = |a: f64| (k as f64 * a).fract() - 0.5;
    Point2::new(
        position.x + JITTER * share(PHI),
        position.y + JITTER * share(PLASTIC),
    )
}

/// Samples per direction of the region's bounds for the chart's metric.
const CHART_SAMPLES: usize = 3;

/// The metric of spade's chart: the size metric averaged over the region's
/// bounds, so that where it hardly varies (a course, a cone) spade's Delaunay
/// triangles already are the metric-Delaunay ones refinement keeps, and few flips
/// remain to be made; the patch's mean |S_u|, |S_v| scales where the size metric
/// is degenerate.
fn chart_metric(info: &PatchInfo, region: &Region) -> Metric {
    let (lo, hi) = region.bounds();
    let mut samples = Vec::with_capacity(CHART_SAMPLES * CHART_SAMPLES);
    for i in 0..CHART_SAMPLES {
        for j in 0..CHART_SAMPLES {
            let t = DVec2::new(i as f64 + 0.5, j as f64 + 0.5) / CHART_SAMPLES as f64;
            samples.push(info.metric_at(lo + (hi - lo) * t));
        }
    }
    let mean = Metric::mean(&samples);
    let det = mean.uu * mean.vv - mean.uv * mean.uv;
    if mean.uu.is_finite()
        && mean.vv.is_finite()
        && mean.uu > 0.0
        && det > 1e-12 * mean.uu * mean.vv
    {
        mean
    } else {
        Metric {
            uu: info.scale.x * info.scale.x,
            uv: 0.0,
            vv: info.scale.y * info.scale.y,
        }
    }
}

/// Triangulates the region with its loop vertices (first, in loop order) and the
/// seeds; returns the mesh of the triangles inside.
pub(super) fn triangulate(
    info: &PatchInfo,
    region: &Region,
    seeds: &[DVec2],
    stats: &mut MeshStats,
) -> Result<TriMesh, CdtError> {
    let mut uvs: Vec<DVec2> = Vec::with_capacity(region.vertex_count() + seeds.len());
    let mut chart_vertices = Vec::with_capacity(uvs.capacity());
    // (loop index, first id) of each loop.
    let metric = chart_metric(info, region);
    let mut loops: Vec<(usize, u32, usize)> = Vec::new();
    for (loop_index, l) in region.loops().enumerate() {
        loops.push((loop_index, uvs.len() as u32, l.uv.len()));
        for &uv in &l.uv {
            let bad = |reason| CdtError::InvalidLoop { loop_index, reason };
            info.check_loop_point(uv).map_err(bad)?;
            let position =
                chart(&metric, uv).map_err(|_| bad("a coordinate is outside spade's range"))?;
            let position = jitter(position, uvs.len());
            chart_vertices.push(ChartVertex {
                position,
                id: uvs.len() as u32,
            });
            uvs.push(uv);
        }
    }
    let loop_vertices = uvs.len();
    for (k, &uv) in seeds.iter().enumerate() {
        match chart(&metric, uv) {
            Ok(position) => {
                let position = jitter(position, loop_vertices + k);
                chart_vertices.push(ChartVertex {
                    position,
                    id: uvs.len() as u32,
                });
                uvs.push(uv);
            }
            Err(_) => stats.failed_insertions += 1,
        }
    }
    let mut cdt = ConstrainedDelaunayTriangulation::<ChartVertex>::bulk_load(chart_vertices)
        .map_err(CdtError::Triangulation)?;
    let mut handle = vec![None; uvs.len()];
    for h in cdt.fixed_vertices() {
        handle[cdt.vertex(h).data().id as usize] = Some(h);
    }
    stats.failed_insertions += handle[loop_vertices..]
        .iter()
        .filter(|h| h.is_none())
        .count();
    let mut loop_edges: HashSet<(u32, u32)> = HashSet::default();
    for &(loop_index, first, len) in &loops {
        let lost = (0..len).find(|&k| handle[first as usize + k].is_none());
        if let Some(vertex) = lost {
            return Err(CdtError::LoopVertexLost { loop_index, vertex });
        }
        for k in 0..len {
            let (a, b) = (first + k as u32, first + ((k + 1) % len) as u32);
            let (Some(ha), Some(hb)) = (handle[a as usize], handle[b as usize]) else {
                continue;
            };
            let fail = |reason| CdtError::ConstraintFailed {
                loop_index,
                segment: k,
                reason,
            };
            if !cdt.exists_constraint(ha, hb) {
                if !cdt.can_add_constraint(ha, hb) {
                    stats.failed_constraints += 1;
                    return Err(fail("it crosses another loop segment"));
                }
                let added = cdt.try_add_constraint(ha, hb);
                if added.len() != 1 {
                    stats.failed_constraints += 1;
                    return Err(fail(if added.is_empty() {
                        "spade refused it"
                    } else {
                        "it runs through another vertex"
                    }));
                }
            }
            loop_edges.insert((a, b));
        }
    }
    let faces: Vec<[u32; 3]> = cdt
        .inner_faces()
        .map(|f| f.vertices().map(|v| v.data().id))
        .collect();
    let inside = flood(&faces, &loop_edges)?;
    // Keep the vertices the inside triangles use, loop vertices first.
    let mut new_index = vec![u32::MAX; uvs.len()];
    for (k, slot) in new_index.iter_mut().enumerate().take(loop_vertices) {
        *slot = k as u32;
    }
    let mut kept: Vec<u32> = (0..loop_vertices as u32).collect();
    for tri in &inside {
        for &v in tri {
            if new_index[v as usize] == u32::MAX {
                new_index[v as usize] = kept.len() as u32;
                kept.push(v);
            }
        }
    }
    let verts = kept
        .par_iter()
        .map(|&k| info.vertex(uvs[k as usize]))
        .collect::<Result<Vec<_>, _>>()?;
    let tris: Vec<[u32; 3]> = inside
        .iter()
        .map(|t| t.map(|v| new_index[v as usize]))
        .collect();
    // Loop vertices keep their indices, so the loop edges are unchanged.
    Ok(TriMesh::new(verts, tris, |a, b| {
        loop_edges.contains(&(a, b)) || loop_edges.contains(&(b, a))
    }))
}

/// The faces reachable from the left side of a loop segment without crossing one.
fn flood(faces: &[[u32; 3]], loop_edges: &HashSet<(u32, u32)>) -> Result<Vec<[u32; 3]>, CdtError> {
    let mut directed: HashMap<(u32, u32), usize> = HashMap::default();
    directed.reserve(faces.len() * 3);
    for (f, tri) in faces.iter().enumerate() {
        for i in 0..3 {
            directed.insert((tri[i], tri[(i + 1) % 3]), f);
        }
    }
    let mut seen = vec![false; faces.len()];
    let mut queue = VecDeque::new();
    let mut starts: Vec<&(u32, u32)> = loop_edges.iter().collect();
    starts.sort_unstable();
    for edge in starts {
        let f = *directed.get(edge).ok_or(CdtError::RegionNotClosed)?;
        if !seen[f] {
            seen[f] = true;
            queue.push_back(f);
        }
    }
    while let Some(f) = queue.pop_front() {
        let tri = faces[f];
        for i in 0..3 {
            let (a, b) = (tri[i], tri[(i + 1) % 3]);
            if loop_edges.contains(&(a, b)) || loop_edges.contains(&(b, a)) {
                continue;
            }
            let n = *directed.get(&(b, a)).ok_or(CdtError::RegionNotClosed)?;
            if !seen[n] {
                seen[n] = true;
                queue.push_back(n);
            }
        }
    }
    Ok(faces
        .iter()
        .zip(&seen)
        .filter(|&(_, &s)| s)
        .map(|(&t, _)| t)
        .collect())
}
