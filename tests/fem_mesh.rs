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
            eprintln!("{name} {tag}: notes {:?}", mesh.notes);
            assert_good(&format!("{name} {tag}"), &mesh);
            // Rings with room to grade slowly keep to 1.5 (were 1.80 on the
            // column and 1.61 on the drum); the tank's N4 is cut short by
            // the bottom (1.75).
            if tag == "V-101" {
                // The drum's saddle rings split its courses; its course
                // nozzles are still meshed (they were all left out as "too
                // near its host's end" when only one piece was searched).
                let left: Vec<_> = mesh
                    .notes
                    .iter()
                    .filter(|n| n.contains("left out"))
                    .collect();
                assert!(left.is_empty(), "{name} {tag}: {left:?}");
            }
            if tag == "C-201" {
                // Its skirt is a shell part hanging from the envelope.
                let skirt = mesh.parts.iter().position(|p| p.id == "SK");
                assert!(
                    skirt.is_some_and(|k| mesh.structural.contains(&k)),
                    "{name} {tag}: skirt not meshed: {:?}",
                    mesh.notes
                );
                assert!(
                    common::fem::branch_edges(&mesh) >= 16,
                    "{name} {tag}: the skirt branches off no ring"
                );
                let q = vesselcad::fem::quality::quality(&mesh);
                assert!(
                    q.max_size_ratio <= common::fem::GRADING,
                    "{name} {tag}: {q:?}"
                );
            }
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

/// Distance from (x0, y0), x0 ≥ 0, y0 > 0, to the ellipse of semi-axes a > b
/// (Eberly's root of F(s) = (a·x0/(s + a²))² + (b·y0/(s + b²))² − 1 by bisection).
fn to_ellipse(x0: f64, y0: f64, a: f64, b: f64) -> f64 {
    if x0 <= 1e-12 {
        // On the minor axis the pole is nearest (a > b).
        return (b - y0).abs();
    }
    let f = |s: f64| (a * x0 / (s + a * a)).powi(2) + (b * y0 / (s + b * b)).powi(2) - 1.0;
    let (mut lo, mut hi) = (-b * b + 1e-12 * b * b, a * a.max(x0.hypot(y0)) * 4.0);
    for _ in 0..300 {
        let s = 0.5 * (lo + hi);
        if f(s) > 0.0 { lo = s } else { hi = s }
    }
    let s = 0.5 * (lo + hi);
    let (x, y) = (a * a * x0 / (s + a * a), b * b * y0 / (s + b * b));
    (x0 - x).hypot(y0 - y)
}

/// The ellipsoidal heads' mid-surface (the ellipsoid of semi-axes a − t/2,
/// b − t/2) is within the stated bound of the true mid-surface (the outside
/// offset inwards by t/2): every node's distance from the outside ellipsoid is
/// t/2 within `ellipsoid_mid_surface_error`, and the nodes come within 80 % of
/// the bound (it is sharp, not a loose estimate).
#[test]
fn ellipsoid_mid_surface_within_the_stated_bound() {
    use vesselcad::fem::meridian::ellipsoid_mid_surface_error;
    for (ratio, t) in [(2.0, 10.0), (2.0, 24.0), (3.0, 8.0)] {
        let head = format!(r#""shape": "ellipsoidal", "ratio": {ratio}, "straight_flange": 0"#);
        let design = vessel(&head, 1000.0, 1500.0, t, 500.0);
        let options = FemOptions {
            size: Some(30.0),
            order: 2,
        };
        let (a, b, h) = (500.0, 500.0 / ratio, 0.5 * t);
        let bound = ellipsoid_mid_surface_error(a, b, h).expect("a bound");
        let mut worst = 0.0f64;
        for (_, mesh) in meshes(&design, &options) {
            for (k, part) in mesh.parts.iter().enumerate() {
                if part.id == "S1" {
                    continue;
                }
                for n in mesh.part_nodes(k) {
                    let p = mesh.nodes[n];
                    let y = if p.z > 750.0 { p.z - 1500.0 } else { -p.z };
                    if y <= 0.0 {
                        continue;
                    }
                    let e = (to_ellipse(p.x.hypot(p.y), y, a, b) - h).abs();
                    assert!(
                        e <= bound + 1e-9,
                        "ratio {ratio}, t {t}: node {p} is {e} mm off, bound {bound}"
                    );
                    worst = worst.max(e);
                }
            }
        }
        eprintln!("ratio {ratio}, t {t}: bound {bound:.4} mm, worst node {worst:.4} mm");
        assert!(
            worst >= 0.8 * bound,
            "ratio {ratio}, t {t}: {worst} vs {bound}"
        );
    }
    // A sphere is exact; the 2:1 figure the docs state.
    assert_eq!(ellipsoid_mid_surface_error(500.0, 500.0, 5.0), Some(0.0));
    let e = ellipsoid_mid_surface_error(500.0, 250.0, 5.0).expect("bound");
    assert!((e - 0.29).abs() < 0.01, "{e}");
}

/// The graded rows of a ring or a cap: they start near the first edge's size,
/// end near the last's, and neighbours differ by less than 1.7 in thickness
/// (√area: 1.3 between rows of one width).
#[test]
fn rows_grade_from_both_edges() {
    use vesselcad::fem::grading::layers;
    for (span, first, last, cap) in [
        (300.0, 10.0, 60.0, 80.0),
        (100.0, 5.0, 5.0, 50.0),
        (50.0, 20.0, 40.0, 40.0),
    ] {
        let x = layers(span, first, last, cap);
        let sizes: Vec<f64> = x.windows(2).map(|w| (w[1] - w[0]) * span).collect();
        eprintln!("{span} {first} {last} {cap}: {sizes:.1?}");
        assert!(
            sizes[0] <= first * 1.01 && sizes[0] >= 0.5 * first,
            "{sizes:?}"
        );
        let end = sizes[sizes.len() - 1];
        assert!(end <= last * 1.01 && end >= 0.5 * last, "{sizes:?}");
        for w in sizes.windows(2) {
            assert!(w[0].max(w[1]) / w[0].min(w[1]) < 1.7, "{sizes:?}");
        }
        assert!(sizes.iter().all(|&s| s <= cap * 1.01), "{sizes:?}");
    }
    assert_eq!(layers(10.0, 8.0, 8.0, 8.0), vec![0.0, 1.0]);
}
