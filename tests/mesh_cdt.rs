//! The constrained-Delaunay patch mesher: chordal bound, valid triangles, kept loop
//! vertices, holes, periodic regions and triangle counts.
//!
//! Boundary loops are built the way the Tessellate stage will: each side of the
//! patch's parameter rectangle is sampled uniformly along its isocurve with just
//! enough points for the chord deviation to be within the tolerance, and a side
//! that collapses to a pole gets only its corners.

use std::collections::HashMap;
use std::time::Instant;

use glam::{DVec2, DVec3, DVec4};
use rayon::prelude::*;
use vesselcad::mesh::cdt::{
    CdtError, MeshStats, Region, RegionMesh, UvLoop, mesh_region, mesh_region_with_uvs, wrap_u,
};
use vesselcad::mesh::{Mesh, TessellationOptions};
use vesselcad::nurbs::NurbsSurface;
use vesselcad::parts::heads::{Head, HeadKind};
use vesselcad::parts::tables::{FlangeClass, Nps, PipeSchedule};
use vesselcad::parts::{Facing, FlangeType, Nozzle, Patch, Shell};

/// Slack on the inversion-based checks: the closest point of the triangle's 3D
/// centroid (or edge midpoint) is not exactly the surface point at the parametric
/// centroid the mesher measures, so its distance differs to second order.
const INVERSION_SLACK: f64 = 1.05;
/// Samples per segment when measuring a side's chord deviation.
const SIDE_SAMPLES: usize = 8;

fn options(tolerance: f64) -> TessellationOptions {
    TessellationOptions::chord(tolerance)
}

/// Largest distance from the side's curve to its chords with `n` uniform segments.
fn side_deviation(s: &NurbsSurface, a: DVec2, b: DVec2, n: usize) -> f64 {
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
fn side(s: &NurbsSurface, a: DVec2, b: DVec2, tol: f64) -> Vec<DVec2> {
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
fn box_loop(s: &NurbsSurface, lo: DVec2, hi: DVec2, tol: f64) -> UvLoop {
    let c = [lo, DVec2::new(hi.x, lo.y), hi, DVec2::new(lo.x, hi.y)];
    let mut uv = Vec::new();
    for k in 0..4 {
        uv.extend(side(s, c[k], c[(k + 1) % 4], tol));
    }
    UvLoop::new(uv)
}

/// The whole patch with sampled sides.
fn full_region(s: &NurbsSurface, tol: f64) -> Region {
    let ((u0, u1), (v0, v1)) = s.domain();
    Region::new(box_loop(s, DVec2::new(u0, v0), DVec2::new(u1, v1), tol))
}

fn surface_at(s: &NurbsSurface, uv: DVec2) -> DVec3 {
    s.point(wrap_u(s, uv.x), uv.y)
}

/// Parameters of a triangle's corners for measuring: u unwrapped next to the
/// first regular corner, and a pole corner given the mean u of the other two.
fn corner_uvs(s: &NurbsSurface, out: &RegionMesh, tri: [usize; 3], poles: &[DVec3]) -> [DVec2; 3] {
    let ((u0, u1), _) = s.domain();
    let period = u1 - u0;
    let closed = (wrap_u(s, u0 + 0.25 * period) - (u0 + 0.25 * period)).abs() < 1e-12
        && wrap_u(s, u1 + 0.25 * period) < u1;
    let is_pole = |k: usize| {
        poles
            .iter()
            .any(|p| (out.mesh.positions[k] - *p).length() < 1e-9)
    };
    let mut uv = tri.map(|k| out.uvs[k]);
    let reference = (0..3).find(|&i| !is_pole(tri[i])).map(|i| uv[i].x);
    if let (true, Some(r)) = (closed, reference) {
        for p in &mut uv {
            p.x += ((r - p.x) / period).round() * period;
        }
    }
    for i in 0..3 {
        if is_pole(tri[i]) {
            let others: Vec<f64> = (0..3).filter(|&j| j != i).map(|j| uv[j].x).collect();
            uv[i].x = 0.5 * (others[0] + others[1]);
        }
    }
    uv
}

/// Points where a whole side of the domain collapses.
fn pole_points(s: &NurbsSurface) -> Vec<DVec3> {
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
            let p = at(0.0);
            (0..=8)
                .all(|k| (at(k as f64 / 8.0) - p).length() < 1e-9)
                .then_some(p)
        })
        .collect()
}

/// Most triangles of one mesh whose centroid and edge midpoints are checked by
/// point inversion (evenly strided; the plane check covers every triangle).
const INVERSION_CHECKS: usize = 1500;

/// Asserts the chordal bound, valid triangles and kept loop vertices; returns the
/// largest deviation found at a parametric centroid.
fn check(s: &NurbsSurface, region: &Region, out: &RegionMesh, tol: f64, what: &str) -> f64 {
    let m = &out.mesh;
    let poles = pole_points(s);
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
            let uv = corner_uvs(s, out, tri, &poles);
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
    for l in region.loops() {
        for &uv in &l.uv {
            let x = surface_at(s, uv);
            assert!(
                m.positions.iter().any(|&p| (p - x).length() < 1e-9),
                "{what}: loop vertex {uv} is missing"
            );
        }
    }
    worst
}

/// Meshes the whole patch at `tol` and checks it; returns the stats.
fn mesh_and_check(patch: &Patch, tol: f64, what: &str) -> MeshStats {
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

fn head_kinds(od: f64) -> Vec<HeadKind> {
    vec![
        HeadKind::Hemispherical,
        HeadKind::TWO_TO_ONE,
        HeadKind::asme_fd(od),
        HeadKind::eighty_ten(od),
        HeadKind::Toriconical {
            half_angle: 30.0,
            knuckle_radius: 0.1 * od,
        },
        HeadKind::Conical {
            half_angle: 30.0,
            small_diameter: 0.0,
        },
        HeadKind::Conical {
            half_angle: 45.0,
            small_diameter: 0.25 * od,
        },
        HeadKind::Flat {
            knuckle_radius: 0.0,
        },
        HeadKind::Flat {
            knuckle_radius: 0.05 * od,
        },
    ]
}

fn nozzles() -> Vec<Nozzle> {
    let nps = Nps::try_new(4.0).unwrap();
    [
        (FlangeType::WeldNeck, Facing::RaisedFace),
        (FlangeType::SlipOn, Facing::FlatFace),
        (FlangeType::Blind, Facing::RingJoint),
    ]
    .into_iter()
    .map(|(flange, facing)| {
        let n = Nozzle {
            nps,
            schedule: PipeSchedule::Std,
            class: FlangeClass::C300,
            flange,
            facing,
            projection: 0.0,
        };
        Nozzle {
            projection: n.flange_length().unwrap() + Nozzle::MIN_NECK_LENGTH + 100.0,
            ..n
        }
    })
    .collect()
}

/// Every patch of the test parts: a shell course, every head kind, nozzles.
fn all_patches() -> Vec<(String, Patch)> {
    let od = 2400.0;
    let mut out = Vec::new();
    let shell = Shell {
        outside_diameter: od,
        length: 3000.0,
    };
    for p in shell.patches().unwrap() {
        out.push(("shell".to_string(), p));
    }
    for kind in head_kinds(od) {
        let head = Head::new(od, kind).with_straight_flange(50.0);
        for p in head.patches().unwrap() {
            out.push((format!("{} head", kind.name()), p));
        }
    }
    for (k, n) in nozzles().into_iter().enumerate() {
        for p in n.patches().unwrap() {
            out.push((format!("nozzle {k}"), p));
        }
    }
    out
}

#[test]
fn every_patch_is_within_the_tolerance() {
    for tol in [1.0, 0.1] {
        let start = Instant::now();
        let mut triangles = 0;
        let mut smallest = f64::INFINITY;
        for (what, patch) in all_patches() {
            let stats = mesh_and_check(&patch, tol, &what);
            triangles += stats.triangles;
            smallest = smallest.min(stats.min_angle_deg);
        }
        println!(
            "all patches at {tol} mm: {triangles} triangles, min angle {smallest:.1}°, {:?}",
            start.elapsed()
        );
    }
}

#[test]
fn a_head_at_a_hundredth_of_a_millimetre() {
    let head = Head::new(500.0, HeadKind::asme_fd(500.0)).with_straight_flange(20.0);
    for p in head.patches().unwrap() {
        mesh_and_check(&p, 0.01, "ASME F&D OD 500");
    }
}

/// The directed edges of a mesh, each with how often it occurs.
fn edge_uses(m: &Mesh) -> HashMap<(u32, u32), usize> {
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
fn boundary_loops(m: &Mesh) -> usize {
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
    let mut seen = std::collections::HashSet::new();
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
fn in_polygon(p: DVec2, poly: &[DVec2]) -> bool {
    let mut inside = false;
    for k in 0..poly.len() {
        let (a, b) = (poly[k], poly[(k + 1) % poly.len()]);
        if (a.y > p.y) != (b.y > p.y) && p.x < a.x + (p.y - a.y) * (b.x - a.x) / (b.y - a.y) {
            inside = !inside;
        }
    }
    inside
}

#[test]
fn a_hole_stays_empty_and_its_vertices_are_kept() {
    let tol = 0.1;
    let shell = Shell {
        outside_diameter: 2400.0,
        length: 3000.0,
    };
    let patch = &shell.patches().unwrap()[0];
    let s = &patch.surface;
    let outer = box_loop(s, DVec2::new(0.1, 0.0), DVec2::new(0.4, 1.0), tol);
    // A circle of radius 300 mm on the cylinder, clockwise in (u, v).
    let (radius, centre) = (300.0, DVec2::new(0.25, 0.5));
    let (su, sv) = (std::f64::consts::PI * 2400.0, 3000.0);
    let n = (std::f64::consts::TAU / (2.0 * (1.0 - tol / radius).acos())).ceil() as usize * 2;
    let hole: Vec<DVec2> = (0..n)
        .map(|k| {
            let a = -std::f64::consts::TAU * k as f64 / n as f64;
            centre + DVec2::new(radius * a.cos() / su, radius * a.sin() / sv)
        })
        .collect();
    let region = Region::new(outer).with_hole(UvLoop::new(hole.clone()));
    let out = mesh_region_with_uvs(s, &region, &options(tol)).unwrap();
    check(s, &region, &out, tol, "shell with a hole");
    for (t, tri) in out.mesh.indices.chunks(3).enumerate() {
        let c = tri.iter().map(|&k| out.uvs[k as usize]).sum::<DVec2>() / 3.0;
        assert!(!in_polygon(c, &hole), "triangle {t} lies in the hole");
    }
    assert_eq!(boundary_loops(&out.mesh), 2);
    println!("shell with a hole: {:?}", out.stats);
}

#[test]
fn a_region_across_the_seam_evaluates_at_wrapped_u() {
    let tol = 0.5;
    let shell = Shell {
        outside_diameter: 2400.0,
        length: 1000.0,
    };
    let patch = &shell.patches().unwrap()[0];
    let s = &patch.surface;
    let region = Region::new(box_loop(s, DVec2::new(0.3, 0.0), DVec2::new(1.3, 1.0), tol));
    let out = mesh_region_with_uvs(s, &region, &options(tol)).unwrap();
    check(s, &region, &out, tol, "shell cut at u = 0.3");
    assert!(
        out.uvs.iter().any(|uv| uv.x > 1.0),
        "no vertex beyond u = 1"
    );
    for (uv, p) in out.uvs.iter().zip(&out.mesh.positions) {
        let exact = s.point((uv.x - 0.0).rem_euclid(1.0), uv.y);
        assert!(
            (exact - *p).length() < 1e-9,
            "vertex at {uv}: {p} is not S({uv}) = {exact}"
        );
    }
    // The seam at u = 0.3 closes: only the two end circles stay open.
    assert_eq!(boundary_loops(&out.mesh), 2);
}

/// The mirror image of a head patch in z = 0, with u reversed so that the normal
/// still points outward.
fn mirrored(s: &NurbsSurface) -> NurbsSurface {
    let (nu, nv) = (s.u_count(), s.v_count());
    let mut points = Vec::with_capacity(nu * nv);
    for i in (0..nu).rev() {
        for j in 0..nv {
            let p = s.homogeneous_point_at(i, j);
            points.push(DVec4::new(p.x, p.y, -p.z, p.w));
        }
    }
    NurbsSurface::try_new(s.u_knots().reversed(), s.v_knots().clone(), points).unwrap()
}

#[test]
fn triangle_counts_at_a_tenth_of_a_millimetre() {
    let tol = 0.1;
    let count = |surfaces: Vec<NurbsSurface>| {
        let start = Instant::now();
        let mut triangles = 0;
        for s in &surfaces {
            let region = full_region(s, tol);
            let (mesh, stats) = mesh_region(s, &region, &options(tol)).unwrap();
            assert_eq!(stats.triangles, mesh.triangle_count());
            triangles += stats.triangles;
        }
        (triangles, start.elapsed())
    };
    let fd = Head::new(2400.0, HeadKind::asme_fd(2400.0));
    let (n, time) = count(
        fd.patches()
            .unwrap()
            .into_iter()
            .map(|p| p.surface)
            .collect(),
    );
    println!("ASME F&D OD 2400 at {tol} mm: {n} triangles in {time:?}");
    let hemi: Vec<NurbsSurface> = Head::new(2000.0, HeadKind::Hemispherical)
        .patches()
        .unwrap()
        .into_iter()
        .map(|p| p.surface)
        .collect();
    let mut sphere = hemi.clone();
    sphere.extend(hemi.iter().map(mirrored));
    let (n, time) = count(sphere);
    // Equilateral triangles of side √(6 R δ) on a sphere: 4πR² / (√3/4 · 6Rδ).
    let ideal = 4.0 * std::f64::consts::PI * 1000.0 / (3f64.sqrt() / 4.0 * 6.0 * tol);
    println!(
        "sphere R 1000 at {tol} mm: {n} triangles ({:.2} × the ideal {ideal:.0}) in {time:?}",
        n as f64 / ideal
    );
    assert!((n as f64) <= 1.3 * ideal);
}

#[test]
fn meshing_is_deterministic() {
    let head = Head::new(2400.0, HeadKind::TWO_TO_ONE);
    for p in head.patches().unwrap() {
        let region = full_region(&p.surface, 0.5);
        let a = mesh_region(&p.surface, &region, &options(0.5)).unwrap();
        let b = mesh_region(&p.surface, &region, &options(0.5)).unwrap();
        assert_eq!(a, b);
    }
}

#[test]
fn bad_input_is_a_typed_error() {
    let shell = Shell {
        outside_diameter: 1000.0,
        length: 500.0,
    };
    let s = &shell.patches().unwrap()[0].surface;
    let region = full_region(s, 0.5);
    assert!(matches!(
        mesh_region(s, &region, &options(0.0)),
        Err(CdtError::Options(_))
    ));
    let mut reversed = region.clone();
    reversed.outer.uv.reverse();
    assert!(matches!(
        mesh_region(s, &reversed, &options(0.5)),
        Err(CdtError::InvalidLoop { loop_index: 0, .. })
    ));
    // A hole that crosses the outer loop.
    let crossing = UvLoop::new(vec![
        DVec2::new(0.4, 0.5),
        DVec2::new(0.5, 1.5),
        DVec2::new(0.6, 0.5),
    ]);
    let bad = region.clone().with_hole(crossing);
    assert!(mesh_region(s, &bad, &options(0.5)).is_err());
    // Two holes that cross each other (both clockwise).
    let overlapping = Region::new(box_loop(s, DVec2::new(0.3, 0.0), DVec2::new(0.7, 1.0), 0.5))
        .with_hole(UvLoop::new(vec![
            DVec2::new(0.4, 0.5),
            DVec2::new(0.5, 0.8),
            DVec2::new(0.6, 0.5),
            DVec2::new(0.5, 0.2),
        ]))
        .with_hole(UvLoop::new(vec![
            DVec2::new(0.45, 0.3),
            DVec2::new(0.5, 0.9),
            DVec2::new(0.55, 0.3),
        ]));
    let result = mesh_region(s, &overlapping, &options(0.5));
    assert!(
        matches!(
            result,
            Err(CdtError::ConstraintFailed { loop_index: 2, .. })
        ),
        "{result:?}"
    );
    let head = Head::new(2000.0, HeadKind::Hemispherical);
    let crown = &head.patches().unwrap()[0].surface;
    assert!(matches!(
        mesh_region(crown, &full_region(crown, 1.0), &options(1e-6)),
        Err(CdtError::BudgetExceeded { .. })
    ));
}
