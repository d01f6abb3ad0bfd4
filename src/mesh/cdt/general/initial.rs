//! The initial constrained Delaunay triangulation, built by spade.
//!
//! Loop vertices and seeds go into spade in a chart of the parameter plane mapped
//! by the patch's mean size metric, so its Delaunay triangles are roughly the
//! shapes refinement wants; every coordinate is validated before insertion. Each
//! loop segment goes in as a constraint during spade's bulk load
//! (`try_bulk_load_cdt`, while the triangulation round its ends is still small);
//! a segment that is not then an edge of the result — it crossed another loop, or
//! spade split it at a vertex it runs through — is an error (the boundary would
//! not be kept as given), as is a loop vertex that spade merged with another. Seeds spade rejects are only counted. The triangles inside the
//! region are found by a flood fill from the left side of every loop segment that
//! never crosses a loop segment, walked on spade's own face adjacency; reaching
//! the convex hull means the loops do not enclose a region, and reaching the right
//! side of a loop segment means a loop lies inside a hole (nested holes: the fill
//! from the inner loop covers the outer hole, whose segments would then be inside
//! the mesh instead of on its boundary). The result is copied into a [`TriMesh`]
//! for refinement.

use rustc_hash::FxHashSet as HashSet;

use glam::DVec2;
use rayon::prelude::*;
use spade::handles::FixedVertexHandle;
use spade::{ConstrainedDelaunayTriangulation, HasPosition, Point2, Triangulation};

use crate::mesh::cdt::metric::Metric;
use crate::mesh::cdt::patch::PatchInfo;
use crate::mesh::cdt::region::Region;
use crate::mesh::cdt::trimesh::TriMesh;
use crate::mesh::cdt::{CdtError, MeshStats};

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

/// spade's triangulation of the chart.
type Cdt = ConstrainedDelaunayTriangulation<ChartVertex>;

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

/// The triangles inside a region, in (u, v) only: nothing evaluated on the
/// surface yet.
pub(in crate::mesh::cdt) struct Inside {
    /// Every vertex's (u, v): the loop vertices first, in loop order, then the
    /// seeds spade kept.
    uvs: Vec<DVec2>,
    /// How many of `uvs` are loop vertices.
    loop_vertices: usize,
    /// The triangles inside, as indices into `uvs`.
    pub tris: Vec<[u32; 3]>,
    /// The loop segments, as (first, second) vertex indices.
    loop_edges: HashSet<(u32, u32)>,
}

impl Inside {
    /// Whether the edge between vertices `a` and `b` is a loop segment.
    pub fn is_loop_edge(&self, a: u32, b: u32) -> bool {
        self.loop_edges.contains(&(a, b)) || self.loop_edges.contains(&(b, a))
    }
}

/// Triangulates the region with its loop vertices (first, in loop order) and the
/// seeds; returns the mesh of the triangles inside.
pub(in crate::mesh::cdt) fn triangulate(
    info: &PatchInfo,
    region: &Region,
    seeds: &[DVec2],
    stats: &mut MeshStats,
) -> Result<TriMesh, CdtError> {
    let inside = triangulate_uv(info, region, seeds, stats)?;
    let (uvs, loop_vertices) = (&inside.uvs, inside.loop_vertices);
    // Keep the vertices the inside triangles use, loop vertices first.
    let mut new_index = vec![u32::MAX; uvs.len()];
    for (k, slot) in new_index.iter_mut().enumerate().take(loop_vertices) {
        *slot = k as u32;
    }
    let mut kept: Vec<u32> = (0..loop_vertices as u32).collect();
    for tri in &inside.tris {
        for &v in tri {
            if new_index[v as usize] == u32::MAX {
                new_index[v as usize] = kept.len() as u32;
                kept.push(v);
            }
        }
    }
    let verts = kept
        .par_iter()
        .with_min_len(crate::mesh::cdt::MIN_VERTICES)
        .map(|&k| info.vertex(uvs[k as usize]))
        .collect::<Result<Vec<_>, _>>()?;
    let tris: Vec<[u32; 3]> = inside
        .tris
        .iter()
        .map(|t| t.map(|v| new_index[v as usize]))
        .collect();
    // Loop vertices keep their indices, so the loop edges are unchanged.
    Ok(TriMesh::new(verts, tris, |a, b| inside.is_loop_edge(a, b)))
}

/// [`triangulate`] in (u, v) only: the constrained Delaunay triangles inside the
/// region, without evaluating a vertex on the surface (for a cavity, whose
/// vertices the mesh already holds).
pub(in crate::mesh::cdt) fn triangulate_uv(
    info: &PatchInfo,
    region: &Region,
    seeds: &[DVec2],
    stats: &mut MeshStats,
) -> Result<Inside, CdtError> {
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
    // The loop segments go in with the vertices: spade inserts each as soon as
    // both ends are in, while the triangulation round them is still small.
    let mut edges = Vec::with_capacity(loop_vertices);
    for &(_, first, len) in &loops {
        for k in 0..len {
            let (a, b) = (first as usize + k, first as usize + (k + 1) % len);
            edges.push([a, b]);
        }
    }
    let mut conflicts = 0usize;
    let cdt = Cdt::try_bulk_load_cdt(chart_vertices, edges, |_| conflicts += 1)
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
    // (loop index, segment's first vertex handle, second) of every loop segment.
    let mut starts = Vec::with_capacity(loop_vertices);
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
            // A segment spade refused crossed another one; a segment it split ran
            // through another vertex: either way it is not an edge of the result.
            if !cdt.exists_constraint(ha, hb) {
                stats.failed_constraints += 1;
                return Err(CdtError::ConstraintFailed {
                    loop_index,
                    segment: k,
                    reason: if conflicts > 0 {
                        "it crosses another loop segment"
                    } else {
                        "it runs through another vertex"
                    },
                });
            }
            loop_edges.insert((a, b));
            starts.push((loop_index, ha, hb));
        }
    }
    let tris = flood(&cdt, &starts)?;
    Ok(Inside {
        uvs,
        loop_vertices,
        tris,
        loop_edges,
    })
}

/// The inner faces reachable from the left side of a loop segment (`starts`: loop
/// index and vertex handles) without crossing one, as vertex ids in spade's face
/// order. Every constraint of `cdt` is a loop segment, so spade's own topology
/// answers both questions (which face lies left of a segment, whether an edge is
/// one) without an edge map. Each segment must then have the region on its left
/// only: a face on its right reached too means a loop lies inside a hole, and the
/// region is refused ([`CdtError::NestedLoop`]) rather than meshed over the hole.
fn flood(
    cdt: &Cdt,
    starts: &[(usize, FixedVertexHandle, FixedVertexHandle)],
) -> Result<Vec<[u32; 3]>, CdtError> {
    let mut seen = vec![false; cdt.num_all_faces()];
    let mut stack = Vec::new();
    for &(_, a, b) in starts {
        let edge = cdt
            .get_edge_from_neighbors(a, b)
            .ok_or(CdtError::RegionNotClosed)?;
        let face = edge.face().as_inner().ok_or(CdtError::RegionNotClosed)?;
        if !std::mem::replace(&mut seen[face.fix().index()], true) {
            stack.push(face);
        }
    }
    while let Some(face) = stack.pop() {
        for edge in face.adjacent_edges() {
            if edge.is_constraint_edge() {
                continue;
            }
            let next = edge
                .rev()
                .face()
                .as_inner()
                .ok_or(CdtError::RegionNotClosed)?;
            if !std::mem::replace(&mut seen[next.fix().index()], true) {
                stack.push(next);
            }
        }
    }
    for &(loop_index, a, b) in starts {
        let right = cdt
            .get_edge_from_neighbors(b, a)
            .and_then(|edge| edge.face().as_inner());
        if right.is_some_and(|face| seen[face.fix().index()]) {
            return Err(CdtError::NestedLoop { loop_index });
        }
    }
    Ok(cdt
        .inner_faces()
        .filter(|f| seen[f.fix().index()])
        .map(|f| f.vertices().map(|v| v.data().id))
        .collect())
}
