//! The FE mesh quality report: per-part figures that add up to the whole
//! mesh's, exact figures on a hand-made mesh, and `vesselcad fem --quality`
//! printing a row per part and the cos(min angle) histogram.

mod common;

use std::process::Command;

use common::examples::example_path;
use glam::DVec3;
use vesselcad::fem::quality::{by_part, quality};
use vesselcad::fem::{Element, ElementKind, FeMesh, FePart};

/// A 2 × 1 rectangle (part A) and a right isosceles triangle of legs 1 (part
/// B) sharing the rectangle's right edge.
fn pair() -> FeMesh {
    let part = |name: &str| FePart {
        name: name.into(),
        id: name.into(),
        thickness: 1.0,
        offset: 0.0,
    };
    FeMesh {
        nodes: vec![
            DVec3::new(0.0, 0.0, 0.0),
            DVec3::new(2.0, 0.0, 0.0),
            DVec3::new(2.0, 1.0, 0.0),
            DVec3::new(0.0, 1.0, 0.0),
            DVec3::new(3.0, 0.0, 0.0),
        ],
        elements: vec![
            Element {
                kind: ElementKind::Quad4,
                nodes: vec![0, 1, 2, 3],
                part: 0,
            },
            Element {
                kind: ElementKind::Tri3,
                nodes: vec![1, 4, 2],
                part: 1,
            },
        ],
        parts: vec![part("A"), part("B")],
        boundary: vec![0, 1, 2, 3, 4],
        ..FeMesh::default()
    }
}

#[test]
fn figures_of_a_hand_made_mesh() {
    let mesh = pair();
    let q = quality(&mesh);
    assert_eq!((q.elements, q.quads), (2, 1));
    assert!((q.max_aspect - 2.0).abs() < 1e-12, "{q:?}");
    assert!((q.min_triangle_angle - 45.0).abs() < 1e-9, "{q:?}");
    // Sizes √2 and √0.5: ratio 2 across the shared edge.
    assert!((q.max_size_ratio - 2.0).abs() < 1e-12, "{q:?}");
    assert_eq!(q.max_size_ratio_elements, (0, 1));
    // cos 90° = 0 (bin 0), cos 45° = 0.707 (bin 7).
    let mut histogram = [0; 10];
    histogram[0] = 1;
    histogram[7] = 1;
    assert_eq!(q.histogram, histogram);
    let parts = by_part(&mesh);
    assert_eq!(parts.len(), 2);
    assert_eq!((parts[0].elements, parts[0].quads), (1, 1));
    assert!((parts[0].max_aspect - 2.0).abs() < 1e-12);
    assert_eq!(parts[0].min_triangle_angle, 180.0);
    assert_eq!((parts[1].elements, parts[1].quads), (1, 0));
    assert!((parts[1].max_aspect - 2f64.sqrt()).abs() < 1e-12);
    // The shared edge's ratio counts for both parts.
    for p in &parts {
        assert!((p.max_size_ratio - 2.0).abs() < 1e-12, "{p:?}");
    }
}

#[test]
fn parts_add_up_to_the_mesh() {
    let design = vesselcad::design::load(example_path("vertical-column")).expect("example");
    let resolved = vesselcad::design::resolve(&design).expect("valid");
    let mesh = vesselcad::fem::build_envelope(
        &design.vessels[0],
        &resolved[0],
        &vesselcad::fem::FemOptions::default(),
    )
    .expect("mesh");
    let q = quality(&mesh);
    let parts = by_part(&mesh);
    assert_eq!(parts.len(), mesh.parts.len());
    let sum = |f: &dyn Fn(&vesselcad::fem::quality::Quality) -> usize| -> usize {
        parts.iter().map(f).sum()
    };
    assert_eq!(sum(&|p| p.elements), q.elements);
    assert_eq!(sum(&|p| p.quads), q.quads);
    assert_eq!(sum(&|p| p.quads_in_range), q.quads_in_range);
    assert_eq!(sum(&|p| p.jacobian_ok), q.jacobian_ok);
    for bin in 0..10 {
        assert_eq!(sum(&|p| p.histogram[bin]), q.histogram[bin], "bin {bin}");
    }
    let worst = |f: &dyn Fn(&vesselcad::fem::quality::Quality) -> f64| {
        parts.iter().map(f).fold(f64::NEG_INFINITY, f64::max)
    };
    assert_eq!(worst(&|p| p.max_size_ratio), q.max_size_ratio);
    assert_eq!(worst(&|p| p.max_aspect), q.max_aspect);
    assert_eq!(worst(&|p| -p.min_scaled_jacobian), -q.min_scaled_jacobian);
}

#[test]
fn the_cli_reports_quality_per_part_with_the_histogram() {
    let dir = tempfile::tempdir().expect("temporary directory");
    let deck = dir.path().join("drum.inp");
    let out = Command::new(env!("CARGO_BIN_EXE_vesselcad"))
        .arg("fem")
        .arg(example_path("horizontal-drum"))
        .args(["--vessel", "V-101", "--quality", "-o"])
        .arg(&deck)
        .output()
        .expect("vesselcad runs");
    let text = String::from_utf8_lossy(&out.stdout);
    eprintln!("{text}{}", String::from_utf8_lossy(&out.stderr));
    assert!(out.status.success());
    for part in ["V-101/S1", "V-101/H1", "V-101/H2", "(all)"] {
        assert!(
            text.lines().any(|l| l.starts_with(part)),
            "no row for {part}"
        );
    }
    // The histogram's ten bins count every element once.
    let elements: usize = text
        .lines()
        .find(|l| l.starts_with("(all)"))
        .and_then(|l| l.split_whitespace().nth(1))
        .and_then(|n| n.parse().ok())
        .expect("element count");
    let bins: Vec<usize> = text
        .lines()
        .skip_while(|l| !l.starts_with("cos(min angle)"))
        .skip(1)
        .take(10)
        .map(|l| {
            l.split_whitespace()
                .nth(1)
                .and_then(|n| n.parse().ok())
                .expect("a bin")
        })
        .collect();
    assert_eq!(bins.len(), 10);
    assert_eq!(bins.iter().sum::<usize>(), elements);
}
