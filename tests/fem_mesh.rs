//! The FE shell mesh of every example vessel and of a vessel with each head
//! kind: conforming (no free edge but the real boundaries, no two nodes at one
//! point, every part sharing its junction ring with its neighbour), quality
//! (quad corner angles in 45–135° and scaled Jacobian ≥ 0.3 for ≥ 95 % of the
//! elements, no triangle), no inverted element, every node on the mid-surface.

mod common;

use common::examples::{EXAMPLES, example};
use common::fem::vessel;
use vesselcad::design::{Design, resolve};
use vesselcad::fem::quality::quality;
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

/// Asserts the conformity and quality targets of `mesh`.
fn assert_good(what: &str, mesh: &FeMesh) {
    let q = quality(mesh);
    eprintln!("{what}: {q:?}");
    assert_eq!(q.free_edges, 0, "{what}: free edges");
    assert_eq!(q.nonmanifold_edges, 0, "{what}: non-manifold edges");
    assert_eq!(q.coincident_nodes, 0, "{what}: coincident nodes");
    assert_eq!(q.inverted, 0, "{what}: inverted elements");
    assert_eq!(
        q.quads, q.elements,
        "{what}: triangles where none is needed"
    );
    assert!(
        q.quads_in_range as f64 >= 0.95 * q.quads as f64,
        "{what}: {} of {} quads with angles in 45-135",
        q.quads_in_range,
        q.quads
    );
    assert!(
        q.jacobian_ok as f64 >= 0.95 * q.elements as f64,
        "{what}: {} of {} elements with scaled Jacobian >= 0.3",
        q.jacobian_ok,
        q.elements
    );
    assert!(q.min_scaled_jacobian > 0.0, "{what}: {q:?}");
    // Every part shares nodes (its junction ring) with another part.
    let sets: Vec<Vec<usize>> = (0..mesh.parts.len()).map(|k| mesh.part_nodes(k)).collect();
    for (k, set) in sets.iter().enumerate() {
        if sets.len() == 1 {
            break;
        }
        let shared = sets
            .iter()
            .enumerate()
            .filter(|(j, _)| *j != k)
            .any(|(_, other)| set.iter().any(|n| other.binary_search(n).is_ok()));
        assert!(shared, "{what}: part {} shares no node", mesh.parts[k].name);
    }
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
