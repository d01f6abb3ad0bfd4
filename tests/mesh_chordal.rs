//! The chordal bound holds on every point of every triangle, not only where the
//! mesher probes: each triangle is sampled at 45 barycentric points (the 8th
//! subdivision of its sides) and the largest distance to the exact (analytic)
//! surface is then climbed to its local maximum. Every head kind (hemisphere,
//! ellipsoids, torispherical crowns and knuckles, toriconical and flat-head
//! knuckles, cones) at 5, 1, 0.1 and 0.01 mm, and every patch of the example
//! designs (boots, pads and nozzles on heads included) at 1 mm. Triangle counts
//! are printed, against the count of an ideal mesh (see [`ideal`]).

mod common;

use common::triangle::largest_distance;
use glam::DVec3;
use vesselcad::components::{PatchMesh, PatchSurface};
use vesselcad::design::load;
use vesselcad::mesh::cdt::mesh_patch_region;
use vesselcad::mesh::{TessellationOptions, patch_region};
use vesselcad::model::Model;
use vesselcad::parts::heads::{Head, HeadKind};
use vesselcad::parts::{Analytic, Patch};

/// The worst triangle of a mesh against `analytic` (as a share of the
/// tolerance) and the share of triangles over the tolerance.
struct Verdict {
    worst: f64,
    over: usize,
    triangles: usize,
}

fn check(analytic: &Analytic, positions: &[DVec3], indices: &[u32], tolerance: f64) -> Verdict {
    let mut verdict = Verdict {
        worst: 0.0,
        over: 0,
        triangles: 0,
    };
    for t in indices.chunks_exact(3) {
        let p = [t[0], t[1], t[2]].map(|i| positions[i as usize]);
        let d = largest_distance(analytic, p) / tolerance;
        verdict.worst = verdict.worst.max(d);
        verdict.over += usize::from(d > 1.0);
        verdict.triangles += 1;
    }
    verdict
}

/// An ideal mesh's triangle count for a patch of area `area` whose largest
/// principal curvature is `kappa` everywhere (a lower estimate on a patch
/// whose curvature varies): equilateral triangles whose circumradius R just
/// meets the tolerance, R²κ/2 = t, each of area (3√3/4) R².
fn ideal(area: f64, kappa: f64, tolerance: f64) -> f64 {
    let r2 = 2.0 * tolerance / kappa;
    area / (0.75 * 3f64.sqrt() * r2)
}

/// Every head kind, with the head diameter used at each tolerance (smaller for
/// the finest, to keep the test's triangle count reasonable).
fn heads(tolerance: f64) -> Vec<(String, Head)> {
    let od = if tolerance >= 1.0 {
        2400.0
    } else if tolerance >= 0.1 {
        1000.0
    } else {
        240.0
    };
    let kinds = [
        HeadKind::Hemispherical,
        HeadKind::TWO_TO_ONE,
        HeadKind::Ellipsoidal { ratio: 3.0 },
        HeadKind::asme_fd(od),
        HeadKind::eighty_ten(od),
        HeadKind::Toriconical {
            half_angle: 30.0,
            knuckle_radius: 0.1 * od,
        },
        HeadKind::Conical {
            half_angle: 45.0,
            small_diameter: 0.0,
        },
        HeadKind::Flat {
            knuckle_radius: 0.05 * od,
        },
    ];
    kinds
        .into_iter()
        .map(|kind| (format!("{} {od}", kind.name()), Head::new(od, kind)))
        .collect()
}

fn mesh_whole(patch: &Patch, options: &TessellationOptions) -> (Vec<DVec3>, Vec<u32>) {
    let region = patch_region(&patch.surface, options, &[], None).expect("a region");
    let out = mesh_patch_region(patch, &region, options).expect("meshed");
    (out.mesh.positions, out.mesh.indices)
}

#[test]
fn every_head_kind_holds_the_bound_on_every_point_of_every_triangle() {
    let mut failures = Vec::new();
    for tolerance in [5.0, 1.0, 0.1, 0.01] {
        let options = TessellationOptions::chord(tolerance);
        for (name, head) in heads(tolerance) {
            for patch in head.patches().expect("a head") {
                let (positions, indices) = mesh_whole(&patch, &options);
                let v = check(&patch.analytic, &positions, &indices, tolerance);
                println!(
                    "{tolerance} mm {name} {}: {} triangles, worst {:.4}×, {} over",
                    patch.name, v.triangles, v.worst, v.over
                );
                if v.worst > 1.0 + 1e-9 {
                    failures.push(format!(
                        "{tolerance} mm {name} {}: {:.5}× ({} of {} triangles)",
                        patch.name, v.worst, v.over, v.triangles
                    ));
                }
            }
        }
    }
    assert!(failures.is_empty(), "{failures:#?}");
}

/// Triangle counts stay near an ideal mesh's on a patch of constant
/// curvature: a hemisphere's against equilateral triangles that just meet the
/// tolerance (a lower bound no mesh reaches). The metric-sized lattice gave
/// 1.22–1.43× of it; the sphere's own rows, sized by the whole-triangle bound
/// (`structured::sphere`), stay within 1.3× (issue 30). Guards against a
/// layout or a bound that over-refines.
#[test]
fn hemisphere_triangle_counts_stay_within_the_ideal_budget() {
    for tolerance in [5.0, 1.0, 0.1] {
        let options = TessellationOptions::chord(tolerance);
        let od = 2400.0;
        let head = Head::new(od, HeadKind::Hemispherical);
        let patch = head
            .patches()
            .expect("a head")
            .into_iter()
            .find(|p| matches!(p.analytic, Analytic::Sphere { .. }))
            .expect("a crown");
        let (_, indices) = mesh_whole(&patch, &options);
        let r = od / 2.0;
        let area = 2.0 * std::f64::consts::PI * r * r;
        let count = indices.len() / 3;
        let ratio = count as f64 / ideal(area, 1.0 / r, tolerance);
        println!("hemisphere at {tolerance} mm: {count} triangles, {ratio:.3}× ideal");
        assert!(ratio <= 1.3, "{count} triangles: {ratio:.3}× ideal");
    }
}

/// Every patch of the example designs, and of the conical roof whose opening
/// near the apex made refinement run away (issue 30 §1: spade's fan from the
/// pole's two corners held triangles turned over on the cone).
#[test]
fn every_patch_of_the_examples_holds_the_bound_on_every_point() {
    let tolerance = 1.0;
    let mut failures = Vec::new();
    for name in [
        "examples/designs/horizontal-drum.json",
        "examples/designs/vertical-column.json",
        "examples/designs/storage-tank.json",
        "examples/designs/small-plant.json",
        "tests/repros/tank-N3-orientation-25.37.json",
    ] {
        let design = load(format!("{}/{name}", env!("CARGO_MANIFEST_DIR"))).unwrap();
        let mut model = Model::from_design(&design, TessellationOptions::chord(tolerance)).unwrap();
        assert!(model.errors().0.is_empty(), "{name}: {:?}", model.errors());
        let mut query = model.query::<(&PatchSurface, &PatchMesh)>();
        let world = model.world();
        let (mut triangles, mut worst) = (0, 0.0f64);
        for (surface, mesh) in query.iter(world) {
            let m = mesh.0.unpack();
            let v = check(&surface.0.analytic, &m.positions, &m.indices, tolerance);
            triangles += v.triangles;
            worst = worst.max(v.worst);
            if v.worst > 1.0 + 1e-9 {
                failures.push(format!(
                    "{name}/{}: {:.5}× ({} of {} triangles)",
                    surface.0.name, v.worst, v.over, v.triangles
                ));
            }
        }
        println!("{name}: {triangles} triangles, worst {worst:.4}× at {tolerance} mm");
    }
    assert!(failures.is_empty(), "{failures:#?}");
}
