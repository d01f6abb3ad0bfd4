//! The constrained-Delaunay patch mesher: chordal bound, valid triangles, kept loop
//! vertices, holes, periodic regions, poles on either side, typed errors,
//! determinism and triangle counts.
//!
//! Boundary loops are built the way the Tessellate stage will: each side of the
//! patch's parameter rectangle is sampled uniformly along its isocurve with just
//! enough points for the chord deviation to be within the tolerance, and a side
//! that collapses to a pole gets only its corners. Every mesh is checked by
//! [`check`]: for every triangle, S at the parametric centroid is within the
//! tolerance of the triangle's plane, and the triangle faces along the exact
//! normals at its vertices; for an evenly strided sample of triangles (all of them
//! in small meshes) the closest surface points to the 3D centroid and edge
//! midpoints, found by point inversion, are within the tolerance; every loop vertex
//! is in the output.

mod common;
mod mesh_cdt_support;

use std::time::Instant;

use glam::DVec2;
use mesh_cdt_support::*;
use vesselcad::mesh::cdt::{CdtError, Region, UvLoop, mesh_region, mesh_region_with_uvs};
use vesselcad::nurbs::NurbsSurface;
use vesselcad::parts::Shell;
use vesselcad::parts::heads::{Head, HeadKind};

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

/// The same suite through the analytic entry point the pipeline uses, so the
/// structured path's screen is held to the same checks.
#[test]
fn every_patch_is_within_the_tolerance_through_the_analytic_entry_point() {
    for tol in [5.0, 1.0, 0.1] {
        let mut paths = std::collections::BTreeMap::new();
        for (what, patch) in all_patches() {
            let stats = mesh_and_check_analytic(&patch, tol, &what);
            *paths.entry(format!("{:?}", stats.path)).or_insert(0) += 1;
        }
        println!("all patches at {tol} mm through the analytic entry point: {paths:?}");
        // The screen is exercised: the structured paths mesh patches here.
        assert!(paths.get("Sector").is_some_and(|&n| n > 0), "{paths:?}");
    }
}

#[test]
fn a_head_at_a_hundredth_of_a_millimetre() {
    let head = Head::new(500.0, HeadKind::asme_fd(500.0)).with_straight_flange(20.0);
    for p in head.patches().unwrap() {
        mesh_and_check(&p, 0.01, "ASME F&D OD 500");
    }
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

/// A clockwise polygon in (u, v) round `centre` on a course of OD `od` and
/// length `length`: radius `radius(angle)` mm, sampled finely enough for `tol`.
fn opening(
    centre: DVec2,
    od: f64,
    length: f64,
    tol: f64,
    radius: impl Fn(f64) -> f64,
) -> Vec<DVec2> {
    let (su, sv) = (std::f64::consts::PI * od, length);
    let largest = (0..64).map(|k| radius(k as f64 / 10.0)).fold(0.0, f64::max);
    let n = (std::f64::consts::TAU / (2.0 * (1.0 - tol / largest).acos())).ceil() as usize * 2;
    (0..n)
        .map(|k| {
            let a = -std::f64::consts::TAU * k as f64 / n as f64;
            let r = radius(a);
            centre + DVec2::new(r * a.cos() / su, r * a.sin() / sv)
        })
        .collect()
}

/// A whole course (its rings structure kept) with openings of every kind the
/// cavities meet: a lone round one, two stacked close enough to share a cavity, a
/// kidney-shaped one (not convex), a long slot, and one beside the seam; at 1 and
/// 0.1 mm, with and without a stretch limit (which gives the course rows). Each
/// mesh is checked in full: chordal bound by point inversion, valid triangles
/// facing along the normals, every loop vertex kept, nothing inside an opening,
/// and exactly one boundary loop per opening besides the two end rings.
#[test]
fn openings_in_a_whole_course_are_meshed_in_their_cavities() {
    let (od, length) = (2400.0, 6000.0);
    let shell = Shell {
        outside_diameter: od,
        length,
    };
    let patch = &shell.patches().unwrap()[0];
    let s = &patch.surface;
    for tol in [1.0, 0.1] {
        let round = |r: f64| move |_: f64| r;
        let holes = [
            opening(DVec2::new(0.3, 0.5), od, length, tol, round(300.0)),
            opening(DVec2::new(0.55, 0.3), od, length, tol, round(60.0)),
            opening(DVec2::new(0.555, 0.33), od, length, tol, round(50.0)),
            opening(DVec2::new(0.75, 0.7), od, length, tol, |a: f64| {
                150.0 + 90.0 * (2.0 * a).cos()
            }),
            opening(DVec2::new(0.9, 0.2), od, length, tol, |a: f64| {
                // A slot: long round the course, short along it.
                let (c, s) = (a.cos(), a.sin());
                1.0 / ((c / 200.0).powi(2) + (s / 40.0).powi(2)).sqrt()
            }),
        ];
        let seam = opening(DVec2::new(0.02, 0.5), od, length, tol, round(80.0));
        for with_seam in [false, true] {
            for stretch in [None, Some(3.0)] {
                let mut region = full_region(s, tol);
                for hole in holes.iter().chain(with_seam.then_some(&seam)) {
                    region = region.with_hole(UvLoop::new(hole.clone()));
                }
                let what = format!(
                    "course with openings at {tol} mm, seam {with_seam}, stretch {stretch:?}"
                );
                let options = options(tol).with_max_stretch(stretch);
                let out = mesh_region_with_uvs(s, &region, &options).unwrap();
                check(s, &region, &out, tol, &what);
                for (t, tri) in out.mesh.indices.chunks(3).enumerate() {
                    // A triangle on the seam has welded vertices at u = 0: unwrap.
                    let mut uvs = [0, 1, 2].map(|i| out.uvs[tri[i] as usize]);
                    if uvs.iter().any(|p| p.x > 0.5) {
                        for p in &mut uvs {
                            p.x += if p.x < 0.25 { 1.0 } else { 0.0 };
                        }
                    }
                    let c = (uvs[0] + uvs[1] + uvs[2]) / 3.0;
                    for (h, hole) in region.holes.iter().enumerate() {
                        assert!(
                            !in_polygon(c, &hole.uv),
                            "{what}: triangle {t} {uvs:?} lies in hole {h}"
                        );
                    }
                }
                assert_eq!(boundary_loops(&out.mesh), 2 + region.holes.len(), "{what}");
                let again = mesh_region_with_uvs(s, &region, &options).unwrap();
                assert_eq!(again, out, "{what}: not deterministic");
                println!("{what}: {:?}", out.stats);
            }
        }
    }
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
    // Either hole may be the one named: both cross the other.
    let result = mesh_region(s, &overlapping, &options(0.5));
    assert!(
        matches!(
            result,
            Err(CdtError::ConstraintFailed {
                loop_index: 1 | 2,
                ..
            })
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

/// A patch over the vertex budget is refused with the option's value as the
/// user set it (not the budget left after the loop vertices), the option's
/// name, and at least how many vertices the patch needed (issue 31).
#[test]
fn the_budget_error_names_the_option_its_value_and_what_the_patch_needs() {
    let head = Head::new(2000.0, HeadKind::Hemispherical);
    let crown = &head.patches().unwrap()[0].surface;
    let region = full_region(crown, 1.0);
    for max_vertices in [1_000, 20_000] {
        let result = mesh_region(
            crown,
            &region,
            &options(0.01).with_max_vertices(max_vertices),
        );
        let Err(
            e @ CdtError::BudgetExceeded {
                max_vertices: named,
                needed,
            },
        ) = &result
        else {
            panic!("{result:?}");
        };
        assert_eq!(*named, max_vertices, "{e}");
        assert!(*needed > max_vertices, "{e}");
        let message = e.to_string();
        assert!(
            message.contains(&format!("max_vertices = {max_vertices}"))
                && message.contains("--max-vertices")
                && message.contains(&format!("at least {needed} vertices")),
            "{message}"
        );
    }
}

/// A hole inside another hole (two openings one inside the other): the region
/// would lie on both sides of the outer hole's loop, so it is refused instead of
/// meshed over that hole.
#[test]
fn a_hole_inside_a_hole_is_a_typed_error() {
    let shell = Shell {
        outside_diameter: 1000.0,
        length: 500.0,
    };
    let s = &shell.patches().unwrap()[0].surface;
    let diamond = |centre: DVec2, half: f64| {
        UvLoop::new(vec![
            centre - DVec2::new(half, 0.0),
            centre + DVec2::new(0.0, half),
            centre + DVec2::new(half, 0.0),
            centre - DVec2::new(0.0, half),
        ])
    };
    let nested = Region::new(box_loop(s, DVec2::new(0.3, 0.0), DVec2::new(0.7, 1.0), 0.5))
        .with_hole(diamond(DVec2::new(0.5, 0.5), 0.15))
        .with_hole(diamond(DVec2::new(0.5, 0.5), 0.03));
    let result = mesh_region(s, &nested, &options(0.5));
    assert!(
        matches!(result, Err(CdtError::NestedLoop { loop_index: 1 })),
        "{result:?}"
    );
}

#[test]
fn interior_edges_respect_the_maximum_length() {
    let shell = Shell {
        outside_diameter: 1000.0,
        length: 800.0,
    };
    let s = &shell.patches().unwrap()[0].surface;
    let opts = options(1.0).with_max_edge_length(Some(60.0));
    let region = full_region(s, 1.0);
    let out = mesh_region_with_uvs(s, &region, &opts).unwrap();
    check(s, &region, &out, 1.0, "shell with edges ≤ 60 mm");
    // Interior edges away from the loops (whose straight sides are single
    // 800 mm segments, which the mesher may not split).
    let on_loop = |k: u32| {
        let p = out.mesh.positions[k as usize];
        region
            .outer
            .uv
            .iter()
            .any(|&uv| (surface_at(s, uv) - p).length() < 1e-9)
    };
    let uses = edge_uses(&out.mesh);
    for &(a, b) in uses.keys() {
        if uses.contains_key(&(b, a)) && !on_loop(a) && !on_loop(b) {
            let length = (out.mesh.positions[a as usize] - out.mesh.positions[b as usize]).length();
            assert!(
                length <= 60.0 + 1e-9,
                "interior edge {a}–{b} is {length} mm long"
            );
        }
    }
}

#[test]
fn a_pole_on_a_u_side_is_meshed_like_one_on_a_v_side() {
    let tol = 0.1;
    let head = Head::new(2000.0, HeadKind::Hemispherical);
    let crown = head.patches().unwrap().remove(0).surface;
    // u along the meridian, v around the axis: the pole is the side u = u1, the
    // seam is v = v0 / v1, and the normal points inwards.
    let transposed = crown.transposed();
    let region = full_region(&transposed, tol);
    let out = mesh_region_with_uvs(&transposed, &region, &options(tol)).unwrap();
    check(&transposed, &region, &out, tol, "transposed crown");
    let (_, original) = mesh_region(&crown, &full_region(&crown, tol), &options(tol)).unwrap();
    let ratio = out.stats.triangles as f64 / original.triangles as f64;
    assert!(
        (ratio - 1.0).abs() < 0.02,
        "{} vs {} triangles",
        out.stats.triangles,
        original.triangles
    );
}

/// A nozzle's neck as the Tessellate stage meshes it: its bottom side is the loop
/// where the host cuts it (its v rising and falling round the turn), its top the
/// ring at the hub. Small and large nozzles on a small and a large course, at 1
/// and 0.1 mm, radial and off the axis: each mesh is checked in full, keeps
/// every loop vertex, has the two loops as its only boundary, and adds no vertex
/// inside (the neck is straight along its generators: the loop and the ring are
/// zipped directly).
#[test]
fn a_neck_is_meshed_between_the_loop_its_host_cuts_and_its_top_ring() {
    use glam::{DAffine3, DMat3, DVec3};
    use vesselcad::mesh::{cut_opening, patch_region};
    use vesselcad::parts::tables::{FlangeClass, Nps, PipeSchedule};
    use vesselcad::parts::{Facing, FlangeType, Nozzle};

    for (od, size, offset) in [
        (1200.0, 2.0, 0.0),
        (1200.0, 16.0, 0.0),
        (3000.0, 8.0, 600.0),
    ] {
        let host = Shell {
            outside_diameter: od,
            length: 3000.0,
        }
        .patches()
        .unwrap()
        .remove(0);
        let nozzle = Nozzle {
            nps: Nps::try_new(size).unwrap(),
            schedule: PipeSchedule::Std,
            class: FlangeClass::C150,
            flange: FlangeType::WeldNeck,
            facing: Facing::RaisedFace,
            projection: od / 2.0 + 400.0,
        };
        let neck = nozzle.patches().unwrap().remove(0);
        // Radial along +X at mid-height, moved sideways by `offset` (a hillside
        // nozzle, whose loop is lopsided).
        let frame = DAffine3::from_mat3_translation(
            DMat3::from_cols(DVec3::Z, -DVec3::Y, DVec3::X),
            DVec3::new(0.0, offset, 1500.0),
        );
        for tol in [1.0, 0.1] {
            let what = format!("neck of {size}\" on OD {od}, offset {offset}, at {tol} mm");
            let cut = cut_opening(&neck, None, &frame, &DAffine3::IDENTITY, &[&host], tol)
                .unwrap_or_else(|e| panic!("{what}: {e}"));
            let region = patch_region(&neck.surface, &options(tol), &[], Some(&cut.neck)).unwrap();
            let out = mesh_region_with_uvs(&neck.surface, &region, &options(tol)).unwrap();
            check(&neck.surface, &region, &out, tol, &what);
            assert_eq!(boundary_loops(&out.mesh), 2, "{what}");
            // The seam's two copies weld: one vertex per distinct loop vertex.
            let distinct = region.outer.uv.len() - 2;
            assert!(
                out.mesh.positions.len() <= distinct,
                "{what}: interior vertices"
            );
            assert_eq!(
                out.stats.refinement_insertions, 0,
                "{what}: {:?}",
                out.stats
            );
            println!("{what}: {:?}", out.stats);
        }
    }
}

/// A whole surface of revolution without openings is meshed a quarter turn at a
/// time: the mesh of every patch of every head shape, laid out as the model lays
/// it out, at 1 and 0.1 mm, passes the full check and is its own image under a
/// quarter turn about the axis (every vertex turned by 90° is a vertex).
#[test]
fn a_whole_head_is_its_first_quarter_turned_round() {
    for kind in head_kinds(2400.0) {
        let head = Head::new(2400.0, kind).with_straight_flange(40.0);
        for patch in head.patches().unwrap() {
            for tol in [1.0, 0.1] {
                let what = format!("{kind:?} {} at {tol} mm", patch.name);
                let s = &patch.surface;
                // Laid out as the Tessellate stage lays it out: circle edges in
                // multiples of eight segments.
                let region = vesselcad::mesh::patch_region(s, &options(tol), &[], None).unwrap();
                let out = mesh_region_with_uvs(s, &region, &options(tol)).unwrap();
                check(s, &region, &out, tol, &what);
                let cell = 1e-6;
                let key = |p: glam::DVec3| (p / cell).round().as_i64vec3().to_array();
                let mut at: std::collections::HashMap<[i64; 3], Vec<glam::DVec3>> =
                    Default::default();
                for &p in &out.mesh.positions {
                    at.entry(key(p)).or_default().push(p);
                }
                let found = |q: glam::DVec3| {
                    let k = key(q);
                    (-1..=1).any(|dx| {
                        (-1..=1).any(|dy| {
                            (-1..=1).any(|dz| {
                                at.get(&[k[0] + dx, k[1] + dy, k[2] + dz])
                                    .is_some_and(|l| l.iter().any(|&p| (p - q).length() <= 1e-7))
                            })
                        })
                    })
                };
                for &p in &out.mesh.positions {
                    let turned = glam::DVec3::new(-p.y, p.x, p.z);
                    assert!(found(turned), "{what}: {p} turned is not a vertex");
                }
            }
        }
    }
}
