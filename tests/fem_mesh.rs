//! The FE shell mesh of every example vessel and of a vessel with each head
//! kind: conforming (no free edge but the real boundaries, no two nodes at one
//! point, every part sharing its junction ring with its neighbour), quality
//! (quad corner angles in 45–135° and scaled Jacobian ≥ 0.3 for ≥ 95 % of the
//! elements, no triangle), no inverted element, every node on the mid-surface.

mod common;

use common::examples::{EXAMPLES, example};
use common::fem::{assert_good, vessel};
use vesselcad::design::{Design, resolve};
use vesselcad::fem::{FeMesh, FemOptions, build_envelope};

/// Meshes every vessel of `design` at the default size.
fn meshes(design: &Design, options: &FemOptions) -> Vec<(String, FeMesh)> {
    let resolved = resolve(design).expect("valid design");
    design
        .vessels
        .iter()
        .zip(&resolved)
        .map(|(v, r)| {
            let mesh =
                build_envelope(v, r, options).unwrap_or_else(|e| panic!("vessel {}: {e}", v.tag));
            (v.tag.clone(), mesh)
        })
        .collect()
}

#[test]
fn example_designs_mesh_conforming_and_well_shaped() {
    for name in EXAMPLES {
        for (tag, mesh) in meshes(&example(name), &FemOptions::default()) {
            assert_good(&format!("{name} {tag}"), &mesh);
        }
    }
}

#[test]
fn every_head_kind_meshes_conforming_and_well_shaped() {
    let heads = [
        r#""shape": "hemispherical""#,
        r#""shape": "ellipsoidal""#,
        r#""shape": "ellipsoidal", "ratio": 3"#,
        r#""shape": "torispherical""#,
        r#""shape": "toriconical", "half_angle": 30"#,
        r#""shape": "conical", "half_angle": 30"#,
        r#""shape": "flat""#,
        r#""shape": "flat", "knuckle_radius": 100"#,
    ];
    for head in heads {
        for order in [1, 2] {
            let design = vessel(head, 1000.0, 1500.0, 8.0, 500.0);
            let options = FemOptions {
                size: Some(60.0),
                order,
            };
            for (tag, mesh) in meshes(&design, &options) {
                assert_good(&format!("{head} order {order} {tag}"), &mesh);
            }
        }
    }
}

/// Corner and mid-side nodes of a course lie on its mid-surface (radius R − t/2).
#[test]
fn nodes_lie_on_the_mid_surface() {
    let design = vessel(r#""shape": "hemispherical""#, 1000.0, 1500.0, 8.0, 500.0);
    for (_, mesh) in meshes(&design, &FemOptions::default()) {
        for (k, part) in mesh.parts.iter().enumerate() {
            for n in mesh.part_nodes(k) {
                let p = mesh.nodes[n];
                let d = if part.id == "S1" {
                    (p.x.hypot(p.y) - 496.0).abs()
                } else {
                    // Hemispheres about the tangent lines z = 0 and z = 1500.
                    let c = if p.z < 750.0 { 0.0 } else { 1500.0 };
                    (glam::DVec3::new(p.x, p.y, p.z - c).length() - 496.0).abs()
                };
                assert!(d < 1e-6, "{}: node {n} at {p} is {d} mm off", part.name);
            }
        }
    }
}
