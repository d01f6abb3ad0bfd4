//! Chordal refinement: insert points until every triangle is within the tolerance.
//!
//! A triangle is measured where a flat triangle departs most from a smooth surface:
//! at its centroid and at the midpoint of each interior (non-loop) edge, each by
//! [`deviation`] (the distance from S at the parametric point to the triangle's
//! plane, and from the 3D point to the surface). For edges the plane is used rather
//! than the 3D segment: the parametric midpoint of an edge along a parallel near a
//! pole lies off the chord *within* the tangent plane (the parallel bends towards
//! the pole), which is no deviation of the surface from the triangle. Those
//! probes see as little as 15/16 of a triangle's largest deviation, so a
//! triangle within at them but near the limit (or with a loop segment, whose
//! midpoint is not probed) is also probed where a cubic model of the surface
//! over it peaks (see `peak`); on a plane, cylinder or sphere the closed-form
//! bound of `certify`, the largest distance over the whole triangle, decides
//! instead. Interior edges are also checked against the angle tolerance (angle between the exact
//! normals at its ends) and the maximum edge length. The worst of these, each as a
//! fraction of its limit, is the triangle's badness; a triangle that is flat or
//! turned over in 3D (its normal against a vertex normal) is infinitely bad. Each
//! pass splits every bad triangle at its worst point, worst first, skipping
//! triangles already changed in the pass, and restores the metric Delaunay property
//! by flips around the new vertex; passes repeat to a fixed point, with a vertex
//! budget. Loop edges are never split, so no vertex is added on the boundary,
//! except on a collapsed side: there a "shadow" vertex is put below each interior
//! vertex that faces a pole segment, which keeps the triangles around the pole
//! sector-shaped; all of them weld into the one pole vertex on output.

use glam::{DVec2, DVec3};
use rayon::prelude::*;

use crate::mesh::cdt::MIN_VERTICES as MIN_TRIANGLES;

use crate::mesh::TessellationOptions;
use crate::mesh::cdt::checks::certify::Bound;
use crate::mesh::cdt::checks::measure::{
    deviation, deviation_and_height, edge_probe_uv, edge_uv_at, end_normal,
};
use crate::mesh::cdt::checks::peak::{Cubic, PEAK_GATE, THIRDS, point_at, uv_at};
use crate::mesh::cdt::flip::{effective_uv, should_flip, strictly_ccw};
use crate::mesh::cdt::patch::PatchInfo;
use crate::mesh::cdt::trimesh::TriMesh;
use crate::mesh::cdt::{CdtError, MeshStats};

/// Most refinement passes.
const MAX_PASSES: usize = 200;
/// Flips allowed per triangle in the initial legalization.
const INITIAL_FLIPS_PER_TRIANGLE: usize = 20;
/// Flips allowed after one insertion.
const FLIPS_PER_INSERTION: usize = 2000;
/// How many times over refinement may grow the mesh it starts from (with at
/// least [`REFINEMENT_FLOOR`] vertices) before it is stopped as a runaway:
/// seeding sizes the mesh from the surface's curvature, so a healthy
/// refinement adds a small fraction of the vertices.
const REFINEMENT_GROWTH: usize = 8;
/// Vertices refinement may always reach, however few it starts from.
const REFINEMENT_FLOOR: usize = 50_000;
/// Relative twice-area (to the squared longest edge) below which a triangle is flat.
const FLAT: f64 = 1e-10;

/// Where to insert in a bad triangle.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Insert {
    /// Split the triangle at this point strictly inside it.
    Point(DVec2),
    /// Split this interior edge at its midpoint.
    Edge(usize),
}

/// A bad triangle's worst measure (as a fraction of its limit) and remedy.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Candidate {
    badness: f64,
    insert: Insert,
}

/// The limits triangles are held to.
struct Limits {
    tolerance: f64,
    angle: Option<f64>,
    max_edge: Option<f64>,
    /// Per loop vertex, the longest loop segment at it and the smallest cosine
    /// of the angle between the normals at the ends of one: an interior edge at
    /// the vertex may be that long and turn that much, since the caller's loop
    /// does (splitting interior edges could never make the triangles on that
    /// segment comply). Cosines, so that the angle (an `acos`) is taken only for
    /// an edge that turns more than the angle limit.
    allowance: Vec<(f64, f64)>,
    /// The closed-form bound of a plane, cylinder or sphere (`certify`): the
    /// largest distance over the whole triangle, which then decides.
    bound: Option<Bound>,
}

impl Limits {
    /// Length and cosine of the turn an interior edge between `a` and `b` is
    /// allowed.
    fn edge_allowance(&self, a: u32, b: u32) -> (f64, f64) {
        let at = |k: u32| {
            self.allowance
                .get(k as usize)
                .copied()
                .unwrap_or((0.0, 1.0))
        };
        let (x, y) = (at(a), at(b));
        (x.0.max(y.0), x.1.min(y.1))
    }
}

/// The allowances of [`Limits::allowance`] from the loop segments of `mesh`.
fn loop_allowances(info: &PatchInfo, mesh: &TriMesh) -> Vec<(f64, f64)> {
    let mut out = vec![(0.0f64, 1.0f64); mesh.verts.len()];
    for t in 0..mesh.tris.len() as u32 {
        for i in 0..3 {
            if !mesh.fixed[t as usize][i] {
                continue;
            }
            let (a, b) = mesh.edge(t, i);
            let (x, y) = (&mesh.verts[a as usize], &mesh.verts[b as usize]);
            let length = (x.point - y.point).length();
            let cos = end_normal(info, x, y.uv)
                .dot(end_normal(info, y, x.uv))
                .clamp(-1.0, 1.0);
            for k in [a, b] {
                let slot = &mut out[k as usize];
                *slot = (slot.0.max(length), slot.1.min(cos));
            }
        }
    }
    out
}

/// Refines `mesh` until every triangle is within `options`; at most `budget`
/// vertices.
pub(in crate::mesh::cdt) fn refine(
    info: &PatchInfo,
    mesh: &mut TriMesh,
    options: &TessellationOptions,
    budget: usize,
    stats: &mut MeshStats,
) -> Result<(), CdtError> {
    let limits = limits(info, mesh, options);
    let mut flips_left = INITIAL_FLIPS_PER_TRIANGLE * mesh.tris.len();
    let all: Vec<(u32, usize)> = (0..mesh.tris.len() as u32)
        .flat_map(|t| (0..3).map(move |i| (t, i)))
        .filter(|&(t, i)| mesh.adj[t as usize][i] > t)
        .collect();
    mesh.legalize(all, &mut flips_left, should_flip);
    run(info, mesh, &limits, budget, stats, Vec::new(), Vec::new())
}

/// Every triangle of a mesh measured against the limits: what [`refine`] starts
/// from, computed once when the caller wants to know whether any work is left.
pub(in crate::mesh::cdt) struct Assessment {
    limits: Limits,
    cache: Vec<Option<Candidate>>,
}

impl Assessment {
    /// Whether every triangle is within the limits.
    pub fn all_good(&self) -> bool {
        self.cache.iter().all(Option::is_none)
    }

    /// Whether triangle `t` is within the limits.
    #[cfg(test)]
    pub fn within(&self, t: usize) -> bool {
        self.cache[t].is_none()
    }
}

/// Measures every triangle of `mesh` (in parallel) without changing it; with
/// `within`, only the triangles a faster check (`screen`) did not already find
/// within the limits.
pub(in crate::mesh::cdt) fn assess_all(
    info: &PatchInfo,
    mesh: &TriMesh,
    options: &TessellationOptions,
    within: Option<&[bool]>,
) -> Assessment {
    let limits = limits(info, mesh, options);
    let cache = (0..mesh.tris.len() as u32)
        .into_par_iter()
        .with_min_len(MIN_TRIANGLES)
        .map(|t| {
            if within.is_some_and(|w| w[t as usize]) {
                None
            } else {
                assess(info, mesh, t, &limits)
            }
        })
        .collect();
    Assessment { limits, cache }
}

/// Whether the edge `i` of triangle `t` — a loop segment the caller chose itself
/// (a seam that belongs to the patch alone) — is within the limits as an interior
/// edge would have to be.
pub(in crate::mesh::cdt) fn edge_within(
    info: &PatchInfo,
    mesh: &TriMesh,
    t: u32,
    i: usize,
    options: &TessellationOptions,
) -> bool {
    let limits = Limits {
        tolerance: options.tolerance,
        angle: options.angle_tolerance.map(f64::to_radians),
        max_edge: options.max_edge_length,
        allowance: Vec::new(),
        bound: None,
    };
    let tri = mesh.tris[t as usize];
    let p = tri.map(|k| mesh.verts[k as usize].point);
    let normal = (p[1] - p[0]).cross(p[2] - p[0]);
    normal.length() > 0.0
        && edge_badness(info, mesh, tri, i, p[0], normal.normalize(), &limits).0 <= 1.0
}

/// [`refine`] of a mesh already measured by [`assess_all`] (no initial flips: the
/// caller built it well shaped); `mesh` must have its neighbour links and be
/// unchanged since.
pub(in crate::mesh::cdt) fn refine_assessed(
    info: &PatchInfo,
    mesh: &mut TriMesh,
    budget: usize,
    stats: &mut MeshStats,
    assessment: Assessment,
) -> Result<(), CdtError> {
    let assessed = vec![mesh.pass + 1; mesh.tris.len()];
    let Assessment { limits, cache } = assessment;
    run(info, mesh, &limits, budget, stats, cache, assessed)
}

/// The limits of `options` for `mesh`.
fn limits(info: &PatchInfo, mesh: &TriMesh, options: &TessellationOptions) -> Limits {
    Limits {
        tolerance: options.tolerance,
        angle: options.angle_tolerance.map(f64::to_radians),
        max_edge: options.max_edge_length,
        allowance: loop_allowances(info, mesh),
        bound: info.analytic.as_ref().and_then(Bound::of),
    }
}

/// The refinement passes, from a cache of measures (`assessed[t]` the pass each
/// was taken in; empty to measure everything first).
fn run(
    info: &PatchInfo,
    mesh: &mut TriMesh,
    limits: &Limits,
    budget: usize,
    stats: &mut MeshStats,
    mut cache: Vec<Option<Candidate>>,
    mut assessed: Vec<u32>,
) -> Result<(), CdtError> {
    let seeded = mesh.verts.len();
    let cap = seeded
        .saturating_mul(REFINEMENT_GROWTH)
        .max(REFINEMENT_FLOOR);
    let over = |limit: usize| {
        if limit == budget {
            CdtError::BudgetExceeded {
                max_vertices: limit,
                needed: limit + 1,
            }
        } else {
            CdtError::RefinementRunaway { seeded, limit }
        }
    };
    let budget = budget.min(cap);
    for _ in 0..MAX_PASSES {
        mesh.pass += 1;
        add_shadows(info, mesh, budget, stats)?;
        let stale: Vec<u32> = (0..mesh.tris.len() as u32)
            .filter(|&t| {
                t as usize >= assessed.len() || mesh.touched[t as usize] >= assessed[t as usize]
            })
            .collect();
        let fresh: Vec<Option<Candidate>> = stale
            .par_iter()
            .with_min_len(MIN_TRIANGLES)
            .map(|&t| assess(info, mesh, t, limits))
            .collect();
        cache.resize(mesh.tris.len(), None);
        assessed.resize(mesh.tris.len(), 0);
        for (&t, c) in stale.iter().zip(fresh) {
            cache[t as usize] = c;
            assessed[t as usize] = mesh.pass;
        }
        let mut bad: Vec<(f64, u32)> = cache
            .iter()
            .enumerate()
            .filter_map(|(t, c)| c.map(|c| (c.badness, t as u32)))
            .collect();
        if bad.is_empty() {
            return Ok(());
        }
        bad.sort_by(|a, b| b.0.total_cmp(&a.0).then(a.1.cmp(&b.1)));
        mesh.pass += 1;
        for (_, t) in bad {
            if mesh.touched[t as usize] == mesh.pass {
                continue;
            }
            let Some(candidate) = cache[t as usize] else {
                continue;
            };
            if mesh.verts.len() >= budget {
                return Err(over(budget));
            }
            let edges = match candidate.insert {
                Insert::Point(uv) => {
                    let x = mesh.push_vertex(info.vertex(uv)?);
                    mesh.split_triangle(t, x)
                }
                Insert::Edge(i) => {
                    let (a, b) = mesh.edge(t, i);
                    let mid = 0.5 * (mesh.verts[a as usize].uv + mesh.verts[b as usize].uv);
                    let x = mesh.push_vertex(info.vertex(mid)?);
                    mesh.split_edge(t, i, x)
                }
            };
            stats.refinement_insertions += 1;
            let mut flips = FLIPS_PER_INSERTION;
            mesh.legalize(edges, &mut flips, should_flip);
        }
    }
    let remaining = cache.iter().filter(|c| c.is_some()).count();
    Err(CdtError::NotConverged {
        passes: MAX_PASSES,
        remaining,
    })
}

/// Splits each pole segment under the interior vertex of its triangle, so that
/// every interior vertex facing a collapsed side has a pole vertex at its own u.
fn add_shadows(
    info: &PatchInfo,
    mesh: &mut TriMesh,
    budget: usize,
    stats: &mut MeshStats,
) -> Result<(), CdtError> {
    if !info.collapsed.iter().any(|&c| c) {
        return Ok(());
    }
    loop {
        let found: Vec<(u32, usize)> = (0..mesh.tris.len() as u32)
            .flat_map(|t| (0..3).map(move |i| (t, i)))
            .filter(|&(t, i)| shadow_at(mesh, t, i).is_some())
            .collect();
        if found.is_empty() {
            return Ok(());
        }
        for (t, i) in found {
            // Flips after an earlier split may have changed this triangle.
            let Some(uv) = shadow_at(mesh, t, i) else {
                continue;
            };
            if mesh.verts.len() >= budget {
                return Err(CdtError::BudgetExceeded {
                    max_vertices: budget,
                    needed: mesh.verts.len() + 1,
                });
            }
            let x = mesh.push_vertex(info.vertex(uv)?);
            let edges = mesh.split_edge(t, i, x);
            stats.refinement_insertions += 1;
            let mut flips = FLIPS_PER_INSERTION;
            mesh.legalize(edges, &mut flips, should_flip);
        }
    }
}

/// Where edge `i` of `t` needs a shadow: the edge is a pole segment, the third
/// vertex is not a pole vertex, and its projection falls strictly inside the edge.
fn shadow_at(mesh: &TriMesh, t: u32, i: usize) -> Option<DVec2> {
    let (a, b) = mesh.edge(t, i);
    let c = mesh.tris[t as usize][(i + 2) % 3];
    let v = |k: u32| &mesh.verts[k as usize];
    if !(mesh.fixed[t as usize][i] && v(a).pole && v(b).pole && !v(c).pole) {
        return None;
    }
    let (pa, ab) = (v(a).uv, v(b).uv - v(a).uv);
    let s = (v(c).uv - pa).dot(ab) / ab.length_squared();
    (s > 1e-9 && s < 1.0 - 1e-9).then(|| pa + ab * s)
}

/// The badness of edge `i` of triangle `tri` (plane through `origin` with unit
/// normal `unit`): its midpoint's deviation, and the angle and length limits, each
/// as a fraction of its limit; with the midpoint's deviation and signed height
/// over the plane.
fn edge_badness(
    info: &PatchInfo,
    mesh: &TriMesh,
    tri: [u32; 3],
    i: usize,
    origin: DVec3,
    unit: DVec3,
    limits: &Limits,
) -> (f64, f64, f64) {
    let j = (i + 1) % 3;
    let (x, y) = (&mesh.verts[tri[i] as usize], &mesh.verts[tri[j] as usize]);
    let mid = edge_probe_uv(x, y);
    let (deviation, height) =
        deviation_and_height(info, 0.5 * (x.point + y.point), mid, origin, unit);
    let mut badness = deviation / limits.tolerance;
    let (long, turn_cos) = limits.edge_allowance(tri[i], tri[j]);
    if let Some(angle) = limits.angle {
        let cos = end_normal(info, x, y.uv).dot(end_normal(info, y, x.uv));
        // Within the angle limit the edge cannot be bad (the loop's turn only
        // widens the limit): skip both acos.
        if cos < angle.cos() {
            let limit = angle.max(turn_cos.acos());
            if cos < limit.cos() {
                badness = badness.max(cos.clamp(-1.0, 1.0).acos() / limit);
            }
        }
    }
    if let Some(max) = limits.max_edge {
        badness = badness.max((x.point - y.point).length() / max.max(long));
    }
    (badness, deviation, height)
}

/// Whether `p` is strictly inside the (u, v) triangle `[a, b, c]`.
fn strictly_inside(p: DVec2, [a, b, c]: [DVec2; 3]) -> bool {
    strictly_ccw(a, b, p) && strictly_ccw(b, c, p) && strictly_ccw(c, a, p)
}

/// The measure of triangle `t`, or `None` when it is within the limits or
/// collapsed (two vertices at one 3D point: dropped on output).
fn assess(info: &PatchInfo, mesh: &TriMesh, t: u32, limits: &Limits) -> Option<Candidate> {
    let tri = mesh.tris[t as usize];
    let v = tri.map(|k| &mesh.verts[k as usize]);
    let p = v.map(|x| x.point);
    let weld = info.weld_tolerance;
    if (0..3).any(|i| (p[i] - p[(i + 1) % 3]).length() <= weld) {
        return None;
    }
    let uv = v.map(|x| x.uv);
    let eff = tri.map(|k| effective_uv(mesh, k, &tri));
    let centroid = (eff[0] + eff[1] + eff[2]) / 3.0;
    let inside = if strictly_inside(centroid, uv) {
        centroid
    } else {
        (uv[0] + uv[1] + uv[2]) / 3.0
    };
    let normal = (p[1] - p[0]).cross(p[2] - p[0]);
    let longest = (0..3)
        .map(|i| (p[(i + 1) % 3] - p[i]).length_squared())
        .fold(0.0, f64::max);
    // At a pole the normal that counts is the limit along the triangle's sector.
    let turned = (0..3).any(|k| {
        let n = if v[k].pole {
            info.normal(eff[k])
        } else {
            v[k].normal
        };
        n.dot(normal) <= 0.0
    });
    let area = normal.length();
    if area.is_nan() || area <= FLAT * longest || turned {
        return Some(Candidate {
            badness: f64::INFINITY,
            insert: Insert::Point(inside),
        });
    }
    let unit = normal.normalize();
    let tolerance = limits.tolerance;
    let (centroid_deviation, centroid_height) =
        deviation_and_height(info, (p[0] + p[1] + p[2]) / 3.0, centroid, p[0], unit);
    let mut worst = Candidate {
        badness: centroid_deviation / tolerance,
        insert: Insert::Point(inside),
    };
    // The largest deviation the plain probes measured, and whether an edge is a
    // loop segment (not probed).
    let (mut probed, mut loop_edge) = (centroid_deviation, false);
    for i in 0..3 {
        if mesh.fixed[t as usize][i] {
            loop_edge = true;
            continue;
        }
        let (badness, deviation, _) = edge_badness(info, mesh, tri, i, p[0], unit, limits);
        probed = probed.max(deviation);
        if badness > worst.badness {
            let (x, y) = (v[i], v[(i + 1) % 3]);
            let mid = edge_probe_uv(x, y);
            let real_mid = 0.5 * (x.uv + y.uv);
            let insert = if mid == real_mid {
                Insert::Edge(i)
            } else if strictly_inside(mid, uv) {
                Insert::Point(mid)
            } else {
                Insert::Point(inside)
            };
            worst = Candidate { badness, insert };
        }
    }
    if let Some(bound) = &limits.bound {
        // The closed form is the largest distance over the whole triangle.
        let badness = bound.deviation(p) / tolerance;
        if badness > worst.badness {
            worst = Candidate {
                badness,
                insert: Insert::Point(inside),
            };
        }
    } else if worst.badness <= 1.0 && (loop_edge || probed > PEAK_GATE * tolerance) {
        // Within at the probes but near the limit: the peak of the cubic
        // model (see `peak`).
        let thirds = [0, 1, 2].map(|i| {
            THIRDS.map(|s| {
                let at = edge_uv_at(v[i], v[(i + 1) % 3], s);
                (info.surface.point(info.wrap_u(at.x), at.y) - p[0]).dot(unit)
            })
        });
        let (l, _) = Cubic::new(thirds, centroid_height).peak();
        let at = uv_at(eff, l);
        let badness = deviation(info, point_at(p, l), at, p[0], unit) / tolerance;
        if badness > worst.badness {
            let insert = if strictly_inside(at, uv) {
                Insert::Point(at)
            } else {
                Insert::Point(inside)
            };
            worst = Candidate { badness, insert };
        }
    }
    (worst.badness > 1.0).then_some(worst)
}
