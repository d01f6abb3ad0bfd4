//! `vesselcad build --tiles`: one GLB per vessel and a 3D Tiles 1.1
//! `tileset.json`. The tileset parses, names every vessel's file, which exists
//! and passes the Khronos validator with no error and no warning, and each
//! tile's box (plant frame, metres) holds every vertex its file draws.

mod common;

use common::examples::example;
use common::glb::{Glb, validate};
use glam::{DMat4, DVec3};
use serde_json::Value;
use vesselcad::export::{GlbOptions, TILESET, write_tiles};
use vesselcad::mesh::TessellationOptions;
use vesselcad::model::Model;

const TOLERANCE: f64 = 1.0;

/// Every vertex a file draws, in the tileset's frame (glTF Y-up → Z-up), m.
fn vertices(glb: &Glb) -> Vec<DVec3> {
    let y_up_to_z_up = DMat4::from_cols_array(&[
        1.0, 0.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, -1.0, 0.0, 0.0, 0.0, 0.0, 0.0, 1.0,
    ]);
    let mut out = Vec::new();
    let mut stack = vec![(glb.root(), y_up_to_z_up)];
    while let Some((n, parent)) = stack.pop() {
        let world = parent * glb.local_matrix(n);
        if let Some(mesh) = glb.node(n)["mesh"].as_u64() {
            let p = glb.primitive(mesh as usize);
            out.extend(p.positions.iter().map(|&q| world.transform_point3(q)));
        }
        stack.extend(glb.children(n).into_iter().map(|c| (c, world)));
    }
    out
}

/// Whether `p` lies in a 3D Tiles box (centre, three half-axes), within `slack`.
fn in_box(b: &[f64], p: DVec3, slack: f64) -> bool {
    let c = DVec3::new(b[0], b[1], b[2]);
    let d = p - c;
    (0..3).all(|k| {
        let axis = DVec3::new(b[3 + 3 * k], b[4 + 3 * k], b[5 + 3 * k]);
        let h = axis.length();
        (d.dot(axis) / h).abs() <= h + slack
    })
}

#[test]
fn tileset_names_every_vessel_file_and_its_boxes_hold_the_vertices() {
    let design = example("small-plant");
    let options = GlbOptions::compact(TOLERANCE);
    let model = Model::from_design(
        &design,
        TessellationOptions::chord(options.meshing_tolerance(TOLERANCE)),
    )
    .unwrap();
    let scene = model.scene();
    let dir = std::env::temp_dir().join(format!("vesselcad-tiles-{}", std::process::id()));
    let files = write_tiles(&scene, &options, TOLERANCE, &dir).unwrap();
    assert_eq!(files.len(), scene.vessels.len() + 1);
    let tileset: Value =
        serde_json::from_slice(&std::fs::read(dir.join(TILESET)).unwrap()).unwrap();
    assert_eq!(tileset["asset"]["version"], "1.1");
    let root = &tileset["root"];
    let root_box: Vec<f64> = serde_json::from_value(root["boundingVolume"]["box"].clone()).unwrap();
    assert_eq!(root_box.len(), 12);
    let children = root["children"].as_array().unwrap();
    assert_eq!(children.len(), scene.vessels.len());
    assert!(root["geometricError"].as_f64().unwrap() > 0.0);
    // Quantization moves a vertex by at most its budget; f32 adds a little.
    let slack = 1e-3 * (options.quantize.unwrap() + 0.01);
    for (tile, vessel) in children.iter().zip(&scene.vessels) {
        assert_eq!(tile["extras"]["tag"], vessel.tag.as_str());
        assert_eq!(tile["geometricError"].as_f64(), Some(TOLERANCE * 1e-3));
        let uri = tile["content"]["uri"].as_str().unwrap();
        let bytes = std::fs::read(dir.join(uri)).unwrap_or_else(|e| panic!("{uri}: {e}"));
        if let Some(report) = validate(uri, &bytes) {
            assert_eq!(report["numErrors"], 0, "{uri}: {report:#}");
            assert_eq!(report["numWarnings"], 0, "{uri}: {report:#}");
        }
        let glb = Glb::parse(&bytes);
        let b: Vec<f64> = serde_json::from_value(tile["boundingVolume"]["box"].clone()).unwrap();
        let points = vertices(&glb);
        assert!(points.len() > 100, "{uri}: {} vertices", points.len());
        for p in &points {
            assert!(in_box(&b, *p, slack), "{uri}: {p} outside {b:?}");
            assert!(in_box(&root_box, *p, slack), "{uri}: {p} outside the root");
        }
        // The box is tight: some vertex touches each face.
        let c = DVec3::new(b[0], b[1], b[2]);
        let h = DVec3::new(b[3], b[7], b[11]);
        let (lo, hi) = points
            .iter()
            .fold((DVec3::INFINITY, DVec3::NEG_INFINITY), |(l, u), &p| {
                (l.min(p), u.max(p))
            });
        assert!(
            ((c - h) - lo).abs().max_element() <= slack,
            "{uri}: low corner"
        );
        assert!(
            ((c + h) - hi).abs().max_element() <= slack,
            "{uri}: high corner"
        );
        println!(
            "{uri}: {} bytes, {} vertices, box {b:?}",
            bytes.len(),
            points.len()
        );
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

/// Levels of detail, coarse to fine, mm.
const LEVELS: [f64; 3] = [5.0, 1.0, 0.25];

/// The triangles a GLB draws: every primitive of every node's mesh.
fn triangles(glb: &Glb) -> usize {
    let mut n = 0;
    let mut stack = vec![glb.root()];
    while let Some(i) = stack.pop() {
        if let Some(mesh) = glb.node(i)["mesh"].as_u64() {
            for p in glb.json["meshes"][mesh as usize]["primitives"]
                .as_array()
                .unwrap()
            {
                let indices = p["indices"].as_u64().unwrap() as usize;
                n += glb.json["accessors"][indices]["count"].as_u64().unwrap() as usize / 3;
            }
        }
        stack.extend(glb.children(i));
    }
    n
}

/// The 3D Tiles screen-space error rule with tiles.js's viewport (1000 px high,
/// 50° field of view) and bound (1 px): the first level whose tolerance looks
/// at most 1 px from `distance` m, else the finest.
fn expected_level(distance: f64) -> usize {
    let k = 1000.0 / (2.0 * (25f64).to_radians().tan());
    LEVELS
        .iter()
        .position(|t| t * 1e-3 * k / distance.max(1e-9) <= 1.0)
        .unwrap_or(LEVELS.len() - 1)
}

/// Distance from `p` to an axis-aligned 3D Tiles box.
fn box_distance(b: &[f64], p: DVec3) -> f64 {
    let c = DVec3::new(b[0], b[1], b[2]);
    let h = DVec3::new(b[3], b[7], b[11]);
    ((p - c).abs() - h).max(DVec3::ZERO).length()
}

#[test]
fn levels_of_detail_chain_coarse_to_fine_and_the_viewer_picks_by_distance() {
    let design = example("small-plant");
    let dir = std::env::temp_dir().join(format!("vesselcad-lod-{}", std::process::id()));
    let mut writer = vesselcad::export::TilesWriter::new(&dir, &LEVELS).unwrap();
    while let Some(t) = writer.next_tolerance() {
        let options = GlbOptions::compact(t);
        let model = Model::from_design(
            &design,
            TessellationOptions::chord(options.meshing_tolerance(t)),
        )
        .unwrap();
        writer.add_level(&model.scene(), &options).unwrap();
    }
    let files = writer.finish().unwrap();
    assert_eq!(files.len(), 4 * LEVELS.len() + 1);
    let tileset: Value =
        serde_json::from_slice(&std::fs::read(dir.join(TILESET)).unwrap()).unwrap();
    let root = &tileset["root"];
    let root_box: Vec<f64> = serde_json::from_value(root["boundingVolume"]["box"].clone()).unwrap();
    let children = root["children"].as_array().unwrap();
    assert_eq!(children.len(), 4);
    let mut boxes = Vec::new();
    let mut drawn = std::collections::HashMap::new();
    for vessel in children {
        let tag = vessel["extras"]["tag"].as_str().unwrap().to_string();
        let b: Vec<f64> = serde_json::from_value(vessel["boundingVolume"]["box"].clone()).unwrap();
        let mut tile = vessel;
        let mut last_triangles = 0;
        for (level, &t) in LEVELS.iter().enumerate() {
            assert_eq!(
                tile["geometricError"].as_f64(),
                Some(t * 1e-3),
                "{tag} {level}"
            );
            assert_eq!(
                tile["extras"]["tolerance"].as_f64(),
                Some(t),
                "{tag} {level}"
            );
            let tile_box: Vec<f64> =
                serde_json::from_value(tile["boundingVolume"]["box"].clone()).unwrap();
            assert_eq!(tile_box, b, "{tag} {level}: a child's box is its parent's");
            let uri = tile["content"]["uri"].as_str().unwrap();
            assert_eq!(uri, format!("{tag}.lod{level}.glb"));
            let bytes = std::fs::read(dir.join(uri)).unwrap();
            if let Some(report) = validate(uri, &bytes) {
                assert_eq!(report["numErrors"], 0, "{uri}: {report:#}");
                assert_eq!(report["numWarnings"], 0, "{uri}: {report:#}");
            }
            let glb = Glb::parse(&bytes);
            let slack = 1e-3 * (0.25 * t + 0.01);
            for p in vertices(&glb) {
                assert!(in_box(&b, p, slack), "{uri}: {p} outside {b:?}");
                assert!(in_box(&root_box, p, slack), "{uri}: {p} outside the root");
            }
            // Each level is the mesher's at its own tolerance: finer, more triangles.
            let n = triangles(&glb);
            assert!(
                n > last_triangles,
                "{uri}: {n} triangles, coarser level {last_triangles}"
            );
            last_triangles = n;
            drawn.insert(uri.to_string(), n);
            println!("{uri}: {} bytes, {n} triangles", bytes.len());
            if level + 1 < LEVELS.len() {
                assert_eq!(tile["refine"], "REPLACE", "{uri}");
                let next = tile["children"].as_array().unwrap();
                assert_eq!(next.len(), 1, "{uri}");
                tile = &next[0];
            } else {
                assert!(
                    tile.get("children").is_none(),
                    "{uri}: the finest is a leaf"
                );
            }
        }
        boxes.push((tag, b));
    }

    // The viewer (tiles.js in headless Chromium): far, every vessel at the
    // coarsest level and nothing finer fetched; half a metre off the first
    // vessel, it at the finest and each other at the level its distance asks.
    let (near_tag, near_box) = &boxes[0];
    let near = DVec3::new(near_box[0] + near_box[3] + 0.5, near_box[1], near_box[2]);
    let centre = DVec3::new(root_box[0], root_box[1], root_box[2]);
    let far = centre + DVec3::new(0.0, -2000.0, 500.0);
    let cameras = serde_json::json!([
        { "eye": far.to_array(), "target": centre.to_array() },
        { "eye": near.to_array(), "target": [near_box[0], near_box[1], near_box[2]] },
    ]);
    let Some(report) = show_tiles(&dir, &cameras) else {
        std::fs::remove_dir_all(&dir).unwrap();
        return;
    };
    for (view, eye) in [far, near].iter().enumerate() {
        let shown = report[view]["shown"].as_array().unwrap();
        assert_eq!(shown.len(), boxes.len(), "view {view}: {shown:#?}");
        for (tag, b) in &boxes {
            let level = expected_level(box_distance(b, *eye));
            let tile = shown
                .iter()
                .find(|s| s["tag"] == tag.as_str())
                .unwrap_or_else(|| panic!("view {view}: {tag} not drawn"));
            let uri = format!("{tag}.lod{level}.glb");
            assert!(
                tile["uri"].as_str().unwrap().ends_with(&uri),
                "view {view}: {tag} drawn from {} (distance {:.2} m: {uri})",
                tile["uri"],
                box_distance(b, *eye)
            );
            assert_eq!(
                tile["triangles"].as_u64(),
                Some(drawn[&uri] as u64),
                "{uri}"
            );
        }
        if view == 0 {
            let fetched = report[0]["fetched"].as_array().unwrap();
            assert!(
                fetched
                    .iter()
                    .all(|f| !f.as_str().unwrap().contains(".lod1")
                        && !f.as_str().unwrap().contains(".lod2")),
                "far: finer levels fetched: {fetched:?}"
            );
        }
    }
    assert_eq!(
        expected_level(box_distance(near_box, near)),
        LEVELS.len() - 1,
        "{near_tag}"
    );
    std::fs::remove_dir_all(&dir).unwrap();
}

/// Runs tests/support/tiles-lod-test.js on the tileset in `dir`; `None` when
/// Node or Chromium is missing (after failing under CI).
fn show_tiles(dir: &std::path::Path, cameras: &Value) -> Option<Value> {
    use std::process::Command;
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR"));
    let support = root.join("tests/support");
    let ready = support
        .join("node_modules/playwright-core/package.json")
        .is_file()
        && std::path::Path::new("/usr/bin/chromium").is_file();
    if !ready {
        assert!(
            std::env::var_os("CI").is_none(),
            "playwright-core or chromium missing"
        );
        eprintln!("playwright-core or chromium missing: the viewer is not tried");
        return None;
    }
    let file = dir.join("cameras.json");
    std::fs::write(&file, serde_json::to_vec(cameras).unwrap()).unwrap();
    let output = Command::new("node")
        .arg(support.join("tiles-lod-test.js"))
        .arg(root.join("src/server/assets/three-bundle.js"))
        .arg(root.join("src/server/assets/tiles.js"))
        .arg(dir)
        .arg(&file)
        .output()
        .unwrap();
    let stdout = String::from_utf8_lossy(&output.stdout);
    assert!(
        output.status.success(),
        "tiles-lod-test.js failed: {stdout}\n{}",
        String::from_utf8_lossy(&output.stderr)
    );
    Some(serde_json::from_str(&stdout).unwrap())
}
