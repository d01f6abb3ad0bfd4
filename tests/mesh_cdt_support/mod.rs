//! Helpers of the `mesh_cdt` tests: boundary loops sampled like the Tessellate
//! stage samples them, the chordal and validity checks, topology checks, and the
//! test parts (in `parts`).

mod parts;

pub use parts::*;

use std::collections::{HashMap, HashSet};
use std::time::Instant;

use glam::{DVec2, DVec3};
use rayon::prelude::*;
use vesselcad::mesh::cdt::{
    MeshStats, Region, RegionMesh, UvLoop, mesh_patch_region, mesh_region_with_uvs, wrap_u,
};
use vesselcad::mesh::{Mesh, TessellationOptions};
use vesselcad::nurbs::NurbsSurface;
use vesselcad::parts::Patch;

/// Slack on the inversion-based checks: rounding only. The mesher bounds the
/// distance of a surface point it reaches by Gauss–Newton from each probe, which
/// is never less than the closest-point distance the check computes.
pub const INVERSION_SLACK: f64 = 1.0 + 1e-9;
/// Samples per segment when measuring a side's chord deviation.
pub const SIDE_SAMPLES: usize = 8;

/// The default options at `tolerance` mm.
pub fn options(tolerance: f64) -> TessellationOptions {
    TessellationOptions::chord(tolerance)
}

/// Largest distance from the side's curve to its chords with `n` uniform segments.
pub fn side_deviation(s: &NurbsSurface, a: DVec2, b: DVec2, n: usize) -> f64 {
    let at = |t: f64| {
        let p = a + (b - a) * t;
        s.point(wrap_u(s, p.x), p.y)
    };
    let mut worst = 0.0f64;
    for k in 0..n {
        let (t0, t1) = (k as f64 / n as f64, (k + 1) as f64 / n as f64);
        let (p0, p1) = (at(t0), at(t1));
        for m in 1..SIDE_SAMPLES {
            let q = at(t0 + (t1 - t0) * m as f64 / SIDE_SAMPLES as f64);
            let d = p1 - p0;
            let t = if d.length_squared() > 0.0 {
                ((q - p0).dot(d) / d.length_squared()).clamp(0.0, 1.0)
            } else {
                0.0
            };
            worst = worst.max((q - (p0 + d * t)).length());
        }
    }
    worst
}

/// The points of side `a → b` (excluding `b`), uniform along it, with chord
/// deviation within `tol`; only `a` when the side collapses to a point.
pub fn side(s: &NurbsSurface, a: DVec2, b: DVec2, tol: f64) -> Vec<DVec2> {
    let pa = s.point(wrap_u(s, a.x), a.y);
    let collapsed = (0..=8).all(|k| {
        let p = a + (b - a) * (k as f64 / 8.0);
        (s.point(wrap_u(s, p.x), p.y) - pa).length() < 1e-9
    });
    if collapsed {
        return vec![a];
    }
    let mut n = 1;
    loop {
        let dev = side_deviation(s, a, b, n);
        if dev <= tol {
            break;
        }
        n = (n + 1).max((n as f64 * (dev / tol).sqrt()).ceil() as usize);
    }
    (0..n)
        .map(|k| a + (b - a) * (k as f64 / n as f64))
        .collect()
}

/// A counter-clockwise loop around the parameter box `lo..hi`, sides sampled.
pub fn box_loop(s: &NurbsSurface, lo: DVec2, hi: DVec2, tol: f64) -> UvLoop {
    let c = [lo, DVec2::new(hi.x, lo.y), hi, DVec2::new(lo.x, hi.y)];
    let mut uv = Vec::new();
    for k in 0..4 {
        uv.extend(side(s, c[k], c[(k + 1) % 4], tol));
    }
    UvLoop::new(uv)
}

/// The whole patch with sampled sides.
pub fn full_region(s: &NurbsSurface, tol: f64) -> Region {
    let ((u0, u1), (v0, v1)) = s.domain();
    Region::new(box_loop(s, DVec2::new(u0, v0), DVec2::new(u1, v1), tol))
}

/// S at `uv`, u wrapped.
pub fn surface_at(s: &NurbsSurface, uv: DVec2) -> DVec3 {
    let ((_, _), (v0, v1)) = s.domain();
    let v = if closed(s, true) {
        v0 + (uv.y - v0).rem_euclid(v1 - v0)
    } else {
        uv.y
    };
    s.point(wrap_u(s, uv.x), v)
}

/// A point a whole side of the domain collapses to, and whether that side runs
/// along u (a side v = const) or along v.
pub struct Pole {
    /// The point.
    pub point: DVec3,
    /// The side is `v = const`, so the pole's u is arbitrary.
    pub along_u: bool,
}

/// Whether the surface's u0 and u1 edges (or, `along_v`, v0 and v1) coincide.
pub fn closed(s: &NurbsSurface, along_v: bool) -> bool {
    let ((u0, u1), (v0, v1)) = s.domain();
    (0..=8).all(|k| {
        let t = k as f64 / 8.0;
        let (a, b) = if along_v {
            let u = u0 + (u1 - u0) * t;
            (s.point(u, v0), s.point(u, v1))
        } else {
            let v = v0 + (v1 - v0) * t;
            (s.point(u0, v), s.point(u1, v))
        };
        (a - b).length() < 1e-9
    })
}

/// Parameters of a triangle's corners for measuring: each closed direction
/// unwrapped next to the first regular corner, and a pole corner given the mean
/// of the other two corners' free parameter. `closed_uv`: [`closed`] along u and v.
pub fn corner_uvs(
    s: &NurbsSurface,
    out: &RegionMesh,
    tri: [usize; 3],
    poles: &[Pole],
    closed_uv: [bool; 2],
) -> [DVec2; 3] {
    let ((u0, u1), (v0, v1)) = s.domain();
    let pole_of = |k: usize| {
        poles
            .iter()
            .find(|p| (out.mesh.positions[k] - p.point).length() < 1e-9)
    };
    let mut uv = tri.map(|k| out.uvs[k]);
    if let Some(r) = (0..3).find(|&i| pole_of(tri[i]).is_none()).map(|i| uv[i]) {
        for p in &mut uv {
            if closed_uv[0] {
                p.x += ((r.x - p.x) / (u1 - u0)).round() * (u1 - u0);
            }
            if closed_uv[1] {
                p.y += ((r.y - p.y) / (v1 - v0)).round() * (v1 - v0);
            }
        }
    }
    for i in 0..3 {
        if let Some(pole) = pole_of(tri[i]) {
            let others: Vec<DVec2> = (0..3).filter(|&j| j != i).map(|j| uv[j]).collect();
            let mean = 0.5 * (others[0] + others[1]);
            if pole.along_u {
                uv[i].x = mean.x;
            } else {
                uv[i].y = mean.y;
            }
        }
    }
    uv
}

/// Points where a whole side of the domain collapses.
pub fn pole_points(s: &NurbsSurface) -> Vec<Pole> {
    let ((u0, u1), (v0, v1)) = s.domain();
    [(v0, true), (v1, true), (u0, false), (u1, false)]
        .into_iter()
        .filter_map(|(w, along_u)| {
            let at = |t: f64| {
                if along_u {
                    s.point(u0 + (u1 - u0) * t, w)
                } else {
                    s.point(w, v0 + (v1 - v0) * t)
                }
            };
            let point = at(0.0);
            (0..=8)
                .all(|k| (at(k as f64 / 8.0) - point).length() < 1e-9)
                .then_some(Pole { point, along_u })
        })
        .collect()
}

/// Most triangles of one mesh whose centroid and edge midpoints are checked by
/// point inversion (evenly strided; the plane check covers every triangle).
pub const INVERSION_CHECKS: usize = 400;

/// Asserts the chordal bound, valid triangles and kept loop vertices; returns the
/// largest deviation found at a parametric centroid.
pub fn check(s: &NurbsSurface, region: &Region, out: &RegionMesh, tol: f64, what: &str) -> f64 {
    let m = &out.mesh;
    let poles = pole_points(s);
    let closed_uv = [closed(s, false), closed(s, true)];
    let count = m.triangle_count();
    let stride = count.div_ceil(INVERSION_CHECKS).max(1);
    let worst = (0..count)
        .into_par_iter()
        .map(|t| {
            let tri = [0, 1, 2].map(|k| m.indices[3 * t + k] as usize);
            let p = tri.map(|k| m.positions[k]);
            let normal = (p[1] - p[0]).cross(p[2] - p[0]);
            assert!(normal.length() > 0.0, "{what}: triangle {t} has zero area");
            for &k in &tri {
                assert!(
                    normal.dot(m.normals[k]) > 0.0,
                    "{what}: triangle {t} is turned against the normal at vertex {k}"
                );
            }
            let unit = normal.normalize();
            let uv = corner_uvs(s, out, tri, &poles, closed_uv);
            let centroid_uv = (uv[0] + uv[1] + uv[2]) / 3.0;
            let plane = (surface_at(s, centroid_uv) - p[0]).dot(unit).abs();
            assert!(
                plane <= tol * (1.0 + 1e-9),
                "{what}: triangle {t} deviates {plane} from the surface at its centroid"
            );
            if t % stride == 0 {
                let centroid = (p[0] + p[1] + p[2]) / 3.0;
                let mut probes = vec![centroid];
                probes.extend((0..3).map(|i| 0.5 * (p[i] + p[(i + 1) % 3])));
                for q in probes {
                    let d = s.closest_point(q).unwrap().distance;
                    assert!(
                        d <= INVERSION_SLACK * tol,
                        "{what}: triangle {t}: point {q} of it is {d} from the surface"
                    );
                }
            }
            plane
        })
        .reduce(|| 0.0, f64::max);
    // Loop vertices on sides a neighbour shares are kept exactly. The seam of a
    // patch closed across its whole period belongs to that patch alone, so the
    // mesher may place its own vertices on it; there the mesh must instead be
    // stitched: every open edge runs between two kept loop vertices.
    let on_seam = seam_test(s, region, closed_uv);
    let mut kept = Vec::new();
    for l in region.loops() {
        for &uv in &l.uv {
            if on_seam(uv) {
                continue;
            }
            let x = surface_at(s, uv);
            assert!(
                m.positions.iter().any(|&p| (p - x).length() < 1e-9),
                "{what}: loop vertex {uv} is missing"
            );
            kept.push(x);
        }
    }
    let mut uses: HashMap<(u32, u32), u32> = HashMap::new();
    for tri in m.indices.chunks(3) {
        for i in 0..3 {
            let (a, b) = (tri[i], tri[(i + 1) % 3]);
            *uses.entry((a.min(b), a.max(b))).or_default() += 1;
        }
    }
    for (&(a, b), &n) in &uses {
        assert!(n <= 2, "{what}: edge {a}-{b} is shared by {n} triangles");
        if n == 1 {
            for k in [a, b] {
                let x = m.positions[k as usize];
                assert!(
                    kept.iter().any(|&p| (p - x).length() < 1e-9),
                    "{what}: open edge {a}-{b} leaves the region's sides at {x}"
                );
            }
        }
    }
    worst
}

/// Whether a parameter point lies strictly inside the seam of a region that spans
/// the whole period of a closed direction (its two copies of the seam): between
/// the seam's two ends, the lowest and highest loop vertices on it (the corners
/// of a rectangle; for a nozzle neck, the end of its bottom loop and the top).
fn seam_test(s: &NurbsSurface, region: &Region, closed_uv: [bool; 2]) -> impl Fn(DVec2) -> bool {
    let (lo, hi) = region.bounds();
    let ((u0, u1), (v0, v1)) = s.domain();
    let eps = 1e-12 * ((hi - lo).max_element() + (u1 - u0) + (v1 - v0));
    let whole_u = closed_uv[0] && ((hi.x - lo.x) - (u1 - u0)).abs() <= eps;
    let whole_v = closed_uv[1] && ((hi.y - lo.y) - (v1 - v0)).abs() <= eps;
    let at = move |x: f64, a: f64, b: f64| (x - a).abs() <= eps || (x - b).abs() <= eps;
    // The ends of each seam: the extreme loop vertices on its copies.
    let ends = |on: &dyn Fn(DVec2) -> Option<f64>| {
        region
            .loops()
            .flat_map(|l| l.uv.iter().copied())
            .filter_map(on)
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), x| {
                (a.min(x), b.max(x))
            })
    };
    let u_seam = ends(&|p: DVec2| at(p.x, lo.x, hi.x).then_some(p.y));
    let v_seam = ends(&|p: DVec2| at(p.y, lo.y, hi.y).then_some(p.x));
    move |uv: DVec2| {
        let inside = |x: f64, (a, b): (f64, f64)| x > a + eps && x < b - eps;
        (whole_u && at(uv.x, lo.x, hi.x) && inside(uv.y, u_seam))
            || (whole_v && at(uv.y, lo.y, hi.y) && inside(uv.x, v_seam))
    }
}

/// Meshes the whole patch at `tol` and checks it; returns the stats.
pub fn mesh_and_check(patch: &Patch, tol: f64, what: &str) -> MeshStats {
    let s = &patch.surface;
    let region = full_region(s, tol);
    let start = Instant::now();
    let out = mesh_region_with_uvs(s, &region, &options(tol))
        .unwrap_or_else(|e| panic!("{what} ({}) at {tol}: {e}", patch.name));
    println!(
        "meshing {what} {} at {tol}: {:?} {} triangles, min angle {:.1}",
        patch.name,
        start.elapsed(),
        out.stats.triangles,
        out.stats.min_angle_deg
    );
    check(
        s,
        &region,
        &out,
        tol,
        &format!("{what} {} at {tol}", patch.name),
    );
    assert!(out.stats.min_angle_deg > 0.0);
    out.stats
}

/// [`mesh_and_check`] through the analytic entry point
/// ([`mesh_patch_region`]: the pipeline's, whose structured path screens
/// triangles in closed form and by the peak model instead of measuring each);
/// the same checks.
pub fn mesh_and_check_analytic(patch: &Patch, tol: f64, what: &str) -> MeshStats {
    let s = &patch.surface;
    let region = full_region(s, tol);
    let out = mesh_patch_region(patch, &region, &options(tol))
        .unwrap_or_else(|e| panic!("{what} ({}) at {tol}: {e}", patch.name));
    check(
        s,
        &region,
        &out,
        tol,
        &format!("{what} {} at {tol}, analytic", patch.name),
    );
    assert!(out.stats.min_angle_deg > 0.0);
    out.stats
}

/// The directed edges of a mesh, each with how often it occurs.
pub fn edge_uses(m: &Mesh) -> HashMap<(u32, u32), usize> {
    let mut uses = HashMap::new();
    for t in m.indices.chunks(3) {
        for i in 0..3 {
            *uses.entry((t[i], t[(i + 1) % 3])).or_insert(0) += 1;
        }
    }
    uses
}

/// Asserts an oriented manifold (every directed edge once) and returns the number
/// of boundary loops (chains of edges without a reverse twin).
pub fn boundary_loops(m: &Mesh) -> usize {
    let uses = edge_uses(m);
    assert!(
        uses.values().all(|&n| n == 1),
        "an edge is used twice in one direction"
    );
    let mut next: HashMap<u32, u32> = HashMap::new();
    for &(a, b) in uses.keys() {
        if !uses.contains_key(&(b, a)) {
            assert!(
                next.insert(a, b).is_none(),
                "vertex {a} starts two boundary edges"
            );
        }
    }
    let mut loops = 0;
    let mut seen = HashSet::new();
    let mut starts: Vec<u32> = next.keys().copied().collect();
    starts.sort_unstable();
    for start in starts {
        if seen.contains(&start) {
            continue;
        }
        loops += 1;
        let mut v = start;
        while seen.insert(v) {
            v = next[&v];
        }
        assert_eq!(v, start, "a boundary chain does not close");
    }
    loops
}

/// Whether `p` is inside the polygon `poly` (even-odd).
pub fn in_polygon(p: DVec2, poly: &[DVec2]) -> bool {
    let mut inside = false;
    for k in 0..poly.len() {
        let (a, b) = (poly[k], poly[(k + 1) % poly.len()]);
        if (a.y > p.y) != (b.y > p.y) && p.x < a.x + (p.y - a.y) * (b.x - a.x) / (b.y - a.y) {
            inside = !inside;
        }
    }
    inside
}
