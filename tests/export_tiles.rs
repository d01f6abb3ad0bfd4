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
