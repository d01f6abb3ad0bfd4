//! `vesselcad build --fab` (issue 38 §1 and §3 in the main GLB): fabrication
//! levels and operation ids in the extras of part and nozzle nodes, and every
//! seam of the plan as a line node on the vessel's outside surface within
//! the mesh tolerance; the file passes the Khronos validator, and the default
//! output has neither.

mod common;

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::process::Command;

use common::glb::{Glb, validate};
use glam::DVec3;
use serde_json::Value;
use vesselcad::design::Design;
use vesselcad::fab::welds::WeldKind;
use vesselcad::fab::{ProcessPlan, ShopRules, plan_process};

/// A vertical vessel: ellipsoidal heads, a shell OD 2000 × 7000 (two
/// courses or more), a padded NPS 8 nozzle N1 and a plain NPS 4 nozzle N2.
fn vessel() -> Design {
    let text = r#"{
  "format": "vesselcad/1", "units": "mm",
  "vessels": [{
    "tag": "V-1", "kind": "vertical",
    "placement": { "position": [0, 0, 0], "rotation": 0 },
    "design": { "pressure": 1000, "temperature": 100, "material": "SA-516-70" },
    "parts": [
      { "head": { "id": "H1", "shape": "ellipsoidal", "straight_flange": 50, "thickness": 12 } },
      { "shell": { "id": "S1", "od": 2000, "length": 7000, "thickness": 12 } },
      { "head": { "id": "H2", "shape": "ellipsoidal", "straight_flange": 50, "thickness": 12 } }
    ],
    "nozzles": [
      { "mark": "N1", "size": 8, "rating": 150, "facing": "RF", "host": "S1", "orientation": 90,
        "elevation": 1500, "projection": 1300, "pad": { "od": 420, "thickness": 12 } },
      { "mark": "N2", "size": 4, "rating": 150, "facing": "RF", "host": "S1", "orientation": 200,
        "elevation": 5200, "projection": 1300 }
    ]
  }]
}"#;
    serde_json::from_str(text).unwrap()
}

/// Runs `vesselcad build <design> -o <out> <args>`; the GLB's bytes.
fn build(name: &str, design: &Design, args: &[&str]) -> Vec<u8> {
    let dir = std::env::temp_dir().join(format!("vesselcad-fab-glb-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let input = dir.join(format!("{name}.json"));
    std::fs::write(&input, serde_json::to_string(design).unwrap()).unwrap();
    let out = dir.join(format!("{name}.glb"));
    let run = Command::new(env!("CARGO_BIN_EXE_vesselcad"))
        .arg("build")
        .arg(&input)
        .arg("-o")
        .arg(&out)
        .args(args)
        .output()
        .unwrap();
    assert!(
        run.status.success(),
        "{}",
        String::from_utf8_lossy(&run.stderr)
    );
    let bytes = std::fs::read(&out).unwrap();
    std::fs::remove_file(&input).ok();
    std::fs::remove_file(&out).ok();
    bytes
}

fn plan(design: &Design) -> ProcessPlan {
    plan_process(design, &design.vessels[0].tag, &ShopRules::builtin())
        .unwrap()
        .1
}

/// Every node under vessel `tag`, by name.
fn vessel_nodes(glb: &Glb, tag: &str) -> BTreeMap<String, usize> {
    let vessel = glb
        .children(glb.root())
        .into_iter()
        .find(|&i| glb.node(i)["name"] == tag)
        .unwrap();
    glb.children(vessel)
        .into_iter()
        .map(|i| (glb.node(i)["name"].as_str().unwrap().to_string(), i))
        .collect()
}

fn level(plan: &ProcessPlan, op: &str) -> u64 {
    u64::from(plan.operations.iter().find(|o| o.id == op).unwrap().level)
}

#[test]
fn parts_and_nozzles_carry_their_levels_and_operations() {
    let design = vessel();
    let plan = plan(&design);
    let glb = Glb::parse(&build("levels", &design, &["--fab"]));
    let nodes = vessel_nodes(&glb, "V-1");
    for mark in ["N1", "N2"] {
        let fab = &glb.node(nodes[mark])["extras"]["fab"];
        assert_eq!(
            fab["level"].as_u64(),
            Some(level(&plan, &format!("fit_weld_nozzle:{mark}"))),
            "{mark}: {fab}"
        );
        let ops: Vec<&str> = fab["operations"]
            .as_array()
            .unwrap()
            .iter()
            .map(|o| o.as_str().unwrap())
            .collect();
        assert!(
            ops.contains(&format!("cut_opening:{mark}").as_str()),
            "{ops:?}"
        );
    }
    // The pad's weld is listed with its nozzle, after the nozzle's weld.
    let n1 = &glb.node(nodes["N1"])["extras"]["fab"]["operations"];
    assert!(
        n1.as_array()
            .unwrap()
            .contains(&Value::from("weld_pad:N1/pad"))
    );
    assert!(level(&plan, "weld_pad:N1/pad") > level(&plan, "fit_weld_nozzle:N1"));
    // Every part has a level; a course joins at its first fit-up, after its
    // own long seam and before its nozzles are welded.
    for part in ["H1", "S1", "H2"] {
        let fab = &glb.node(nodes[part])["extras"]["fab"];
        assert!(fab["level"].as_u64().is_some(), "{part}: {fab}");
    }
    let s1 = glb.node(nodes["S1"])["extras"]["fab"]["level"]
        .as_u64()
        .unwrap();
    assert!(s1 > level(&plan, "weld_long_seam:S1"));
    assert!(s1 < level(&plan, "fit_weld_nozzle:N1"));
}

#[test]
fn default_build_has_no_fabrication_data() {
    let glb = Glb::parse(&build("plain", &vessel(), &[]));
    let nodes = vessel_nodes(&glb, "V-1");
    assert!(!nodes.keys().any(|n| n.starts_with("seam ")));
    assert!(glb.node(nodes["N1"])["extras"].get("fab").is_none());
}

/// Seam nodes of `glb` under vessel `tag`: id → (extras, positions in the
/// vessel frame, mm).
fn seams(glb: &Glb, tag: &str) -> BTreeMap<String, (Value, Vec<DVec3>)> {
    let mut out = BTreeMap::new();
    for (name, i) in vessel_nodes(glb, tag) {
        let Some(id) = name.strip_prefix("seam ") else {
            continue;
        };
        let node = glb.node(i);
        assert_eq!(node["extras"]["kind"], "seam");
        assert_eq!(node["extras"]["id"], id);
        let mesh = node["mesh"].as_u64().unwrap() as usize;
        let p = &glb.json["meshes"][mesh]["primitives"][0];
        assert_eq!(p["mode"], 1, "{id}: LINES");
        let points = glb
            .accessor(p["attributes"]["POSITION"].as_u64().unwrap() as usize)
            .into_iter()
            .map(|v| DVec3::new(v[0], v[1], v[2]) * 1e3)
            .collect();
        let before = out.insert(id.to_string(), (node["extras"].clone(), points));
        assert!(before.is_none(), "{id} twice");
    }
    out
}

#[test]
fn every_seam_appears_once_on_the_outside_surface() {
    let design = vessel();
    let plan = plan(&design);
    let tolerance = 0.5;
    let bytes = build("seams", &design, &["--fab", "--tolerance", "0.5"]);
    let glb = Glb::parse(&bytes);
    let seams = seams(&glb, "V-1");
    let expected: Vec<_> = plan
        .welds
        .iter()
        .filter(|w| matches!(w.kind, WeldKind::LongSeam | WeldKind::CircSeam))
        .collect();
    assert!(expected.iter().any(|w| w.kind == WeldKind::LongSeam));
    assert!(
        expected
            .iter()
            .filter(|w| w.kind == WeldKind::CircSeam)
            .count()
            >= 3
    );
    let ids: Vec<&String> = seams.keys().collect();
    let mut want: Vec<&String> = expected.iter().map(|w| &w.id).collect();
    want.sort();
    assert_eq!(ids, want);
    // Every vertex and every chord's midpoint within the tolerance of the
    // outside cylinder (the heads' straight flanges and the shell share OD
    // 2000, thickness 12); positions are f32 metres (1e-4 mm at 7 m).
    for w in &expected {
        let (extras, points) = &seams[&w.id];
        let category = format!("{:?}", w.category.unwrap());
        assert_eq!(extras["category"], category.as_str());
        assert_eq!(
            extras["level"].as_u64(),
            Some(level(&plan, extras["operation"].as_str().unwrap()))
        );
        assert!(points.len() >= 2 && points.len() % 2 == 0);
        let radius = |p: DVec3| p.truncate().length();
        let mut worst: f64 = 0.0;
        for pair in points.chunks(2) {
            for p in [pair[0], pair[1], 0.5 * (pair[0] + pair[1])] {
                worst = worst.max((radius(p) - 1000.0).abs());
            }
            assert!(pair[0].distance(pair[1]) > 1.0);
        }
        assert!(worst <= tolerance, "{}: {worst} mm off", w.id);
        if w.kind == WeldKind::CircSeam {
            let z = points[0].z;
            assert!(points.iter().all(|p| (p.z - z).abs() < 1e-3), "{}", w.id);
            // Not coarser than needed: a closed polygon of at least 8 sides
            // whose vertices are on the circle to f32.
            assert!(points.iter().all(|p| (radius(*p) - 1000.0).abs() < 1e-3));
        }
    }
    if let Some(report) = validate("fab-seams", &bytes) {
        assert_eq!(report["numErrors"], 0, "{report:#}");
    }
}

#[test]
fn the_example_column_gets_its_seams_and_levels() {
    let path: PathBuf =
        Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/designs/vertical-column.json");
    let design = vesselcad::design::load(&path).unwrap();
    let bytes = build("column", &design, &["--fab"]);
    let glb = Glb::parse(&bytes);
    for vessel in &design.vessels {
        let (_, plan) = plan_process(&design, &vessel.tag, &ShopRules::builtin()).unwrap();
        let seams = seams(&glb, &vessel.tag);
        let want = plan
            .welds
            .iter()
            .filter(|w| matches!(w.kind, WeldKind::LongSeam | WeldKind::CircSeam))
            .count();
        assert_eq!(seams.len(), want, "{}", vessel.tag);
        let nodes = vessel_nodes(&glb, &vessel.tag);
        for n in &vessel.nozzles {
            let fab = &glb.node(nodes[&n.mark])["extras"]["fab"];
            assert_eq!(
                fab["level"].as_u64(),
                Some(level(&plan, &format!("fit_weld_nozzle:{}", n.mark))),
                "{}/{}",
                vessel.tag,
                n.mark
            );
        }
    }
    if let Some(report) = validate("fab-column", &bytes) {
        assert_eq!(report["numErrors"], 0, "{report:#}");
    }
}

#[test]
fn seams_refuse_bytes_that_are_not_glb() {
    use vesselcad::fab::seam_glb::add_seams;
    let e = add_seams(b"not a GLB file at all", &[]).unwrap_err();
    assert!(e.to_string().contains("not a binary glTF file"), "{e}");
    let e = add_seams(b"glTF", &[]).unwrap_err();
    assert!(e.to_string().contains("truncated"), "{e}");
}
