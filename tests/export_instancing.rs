//! `EXT_mesh_gpu_instancing`: with instancing on, the patches that share a
//! glTF mesh are drawn by one instanced node (one draw call) and every patch is
//! drawn where the plain file draws it, by the same triangles; the instanced
//! node's extras name each instance; the streaming writer writes the same bytes;
//! the Khronos validator reports no error and no warning; three.js r187 loads
//! it in headless Chromium as `InstancedMesh`es drawing the same triangles.

mod common;

use std::collections::BTreeMap;
use std::sync::OnceLock;

use common::examples::example;
use common::glb::{Glb, validate};
use glam::{DMat4, DQuat, DVec3};
use serde_json::Value;
use vesselcad::export::{GlbOptions, Scene, quantization_budget, stream_glb_with, write_glb_with};
use vesselcad::mesh::TessellationOptions;
use vesselcad::model::Model;

const TOLERANCE: f64 = 1.0;

/// The small plant built by the model at the meshing tolerance of a quantized
/// file.
fn plant() -> &'static Scene {
    static PLANT: OnceLock<Scene> = OnceLock::new();
    PLANT.get_or_init(|| {
        let tolerance = GlbOptions::compact(TOLERANCE).meshing_tolerance(TOLERANCE);
        let model = Model::from_design(
            &example("small-plant"),
            TessellationOptions::chord(tolerance),
        )
        .unwrap();
        model.scene()
    })
}

/// The plain and the instanced options of each variant, by name.
fn variants() -> [(&'static str, GlbOptions); 3] {
    let quantized = GlbOptions {
        quantize: Some(quantization_budget(TOLERANCE)),
        ..GlbOptions::default()
    };
    [
        ("default", GlbOptions::default()),
        ("quantized", quantized),
        ("compact", GlbOptions::compact(TOLERANCE)),
    ]
}

/// Each triangle a file draws, by patch id (`tag/part/patch`), in the plant's
/// frame (the root's rotation included), mm; and the draw calls (nodes with a
/// mesh).
fn drawn(glb: &Glb) -> (BTreeMap<String, Vec<[DVec3; 3]>>, usize) {
    let mut out: BTreeMap<String, Vec<[DVec3; 3]>> = BTreeMap::new();
    let mut draws = 0;
    let mut stack = vec![(glb.root(), DMat4::IDENTITY, Vec::<String>::new())];
    while let Some((n, parent, path)) = stack.pop() {
        let node = glb.node(n);
        let world = parent * glb.local_matrix(n);
        let name = node["name"].as_str().unwrap_or_default().to_string();
        let mut path = path.clone();
        if n != glb.root() {
            path.push(name);
        }
        if let Some(mesh) = node["mesh"].as_u64() {
            draws += 1;
            let p = glb.primitive(mesh as usize);
            let triangles = |m: DMat4| -> Vec<[DVec3; 3]> {
                let points: Vec<DVec3> = p
                    .positions
                    .iter()
                    .map(|&q| m.transform_point3(q) * 1e3)
                    .collect();
                p.indices
                    .chunks_exact(3)
                    .map(|t| [0, 1, 2].map(|k| points[t[k] as usize]))
                    .collect()
            };
            let ext = &node["extensions"]["EXT_mesh_gpu_instancing"]["attributes"];
            if ext.is_object() {
                let attribute = |key: &str| -> Option<Vec<Vec<f64>>> {
                    ext[key].as_u64().map(|a| glb.accessor(a as usize))
                };
                let t = attribute("TRANSLATION").unwrap();
                let r = attribute("ROTATION");
                let s = attribute("SCALE");
                let ids = node["extras"]["ids"].as_array().unwrap();
                assert_eq!(node["extras"]["kind"], "instances");
                assert_eq!(ids.len(), t.len(), "an id per instance");
                assert!(
                    ids.len() > 1,
                    "an instanced node draws its mesh twice or more"
                );
                for (k, id) in ids.iter().enumerate() {
                    let rotation = r.as_ref().map_or(DQuat::IDENTITY, |r| {
                        DQuat::from_xyzw(r[k][0], r[k][1], r[k][2], r[k][3])
                    });
                    let scale = s
                        .as_ref()
                        .map_or(DVec3::ONE, |s| DVec3::new(s[k][0], s[k][1], s[k][2]));
                    let instance = DMat4::from_scale_rotation_translation(
                        scale,
                        rotation,
                        DVec3::new(t[k][0], t[k][1], t[k][2]),
                    );
                    let id = id.as_str().unwrap().to_string();
                    assert!(
                        out.insert(id.clone(), triangles(world * instance))
                            .is_none(),
                        "{id} drawn twice"
                    );
                }
            } else {
                let id = path.join("/");
                assert!(
                    out.insert(id.clone(), triangles(world)).is_none(),
                    "{id} drawn twice"
                );
            }
        }
        for child in glb.children(n).into_iter().rev() {
            stack.push((child, world, path.clone()));
        }
    }
    (out, draws)
}

#[test]
fn instanced_files_draw_every_patch_where_plain_files_do_with_fewer_draw_calls() {
    let scene = plant();
    for (name, plain) in variants() {
        let plain_glb = Glb::parse(&write_glb_with(scene, &plain).unwrap());
        let instanced = plain.instanced();
        let glb = Glb::parse(&write_glb_with(scene, &instanced).unwrap());
        assert!(
            glb.json["extensionsRequired"]
                .as_array()
                .unwrap()
                .iter()
                .any(|e| e == "EXT_mesh_gpu_instancing"),
            "{name}: {}",
            glb.json["extensionsRequired"]
        );
        let (expected, plain_draws) = drawn(&plain_glb);
        let (got, draws) = drawn(&glb);
        let meshes = glb.json["meshes"].as_array().unwrap().len();
        println!(
            "{name}: {} patches, {plain_draws} draw calls plain, {draws} instanced ({meshes} meshes)",
            expected.len()
        );
        assert_eq!(plain_draws, expected.len());
        assert_eq!(draws, meshes, "{name}: one draw call per glTF mesh");
        assert!(
            3 * draws < 2 * plain_draws,
            "{name}: {draws} draw calls instanced, {plain_draws} plain"
        );
        assert_eq!(
            got.keys().collect::<Vec<_>>(),
            expected.keys().collect::<Vec<_>>(),
            "{name}: the same patches"
        );
        // One f32 translation instead of three (vessel, part, dequantization)
        // and one rotation instead of three: the roundings differ by a few µm.
        let mut worst = 0.0f64;
        for (id, triangles) in &expected {
            assert_eq!(got[id].len(), triangles.len(), "{name}: {id}");
            for (a, b) in got[id].iter().zip(triangles) {
                for k in 0..3 {
                    worst = worst.max(a[k].distance(b[k]));
                }
            }
        }
        println!("{name}: worst distance from the plain file {worst:.5} mm");
        assert!(worst <= 0.01, "{name}: {worst} mm from the plain file");
        // The parts' nodes and extras stay.
        let parts = |glb: &Glb| -> Vec<Value> {
            glb.children(glb.root())
                .into_iter()
                .flat_map(|v| glb.children(v))
                .map(|p| glb.node(p)["extras"].clone())
                .filter(|e| !e.is_null())
                .collect()
        };
        assert!(
            parts(&glb) == parts(&plain_glb),
            "{name}: part extras differ"
        );
    }
}

#[test]
fn instanced_files_stream_the_same_bytes_and_validate() {
    let scene = plant();
    for (name, options) in variants() {
        let options = options.instanced();
        let bytes = write_glb_with(scene, &options).unwrap();
        let mut streamed = Vec::new();
        stream_glb_with(scene, &options, &mut streamed, "<memory>".as_ref()).unwrap();
        assert!(streamed == bytes, "{name}: streamed bytes differ");
        let Some(report) = validate(&format!("instanced-{name}"), &bytes) else {
            continue;
        };
        println!(
            "{name}: {} bytes, {} errors, {} warnings, {} infos: {}",
            bytes.len(),
            report["numErrors"],
            report["numWarnings"],
            report["numInfos"],
            report["messages"]
        );
        assert_eq!(report["numErrors"], 0, "{name}: {report:#}");
        assert_eq!(report["numWarnings"], 0, "{name}: {report:#}");
    }
}

/// three.js r187's `GLTFLoader` (the bundle `vesselcad serve` embeds) supports
/// the extension: it makes an `InstancedMesh` per instanced node, drawing every
/// patch's triangles in one draw call per mesh.
#[test]
fn three_js_draws_instanced_files_in_chromium() {
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR"));
    let driver = root.join("tests/support/node_modules/playwright-core/package.json");
    if !driver.is_file() || !std::path::Path::new("/usr/bin/chromium").exists() {
        let missing = "Chromium or playwright-core is missing: install Debian's chromium and \
                       run npm ci --prefix tests/support";
        assert!(std::env::var_os("CI").is_none(), "{missing}");
        eprintln!("{missing}");
        return;
    }
    let scene = plant();
    let dir = std::env::temp_dir().join(format!("vesselcad-instancing-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let mut files = Vec::new();
    for (name, options) in variants() {
        for (suffix, options) in [("plain", options), ("instanced", options.instanced())] {
            let file = dir.join(format!("{name}-{suffix}.glb"));
            let bytes = write_glb_with(scene, &options).unwrap();
            let glb = Glb::parse(&bytes);
            std::fs::write(&file, bytes).unwrap();
            files.push((format!("{name}-{suffix}.glb"), file, drawn(&glb).1));
        }
    }
    let output = std::process::Command::new("node")
        .arg(root.join("tests/support/load-glb-test.js"))
        .arg(root.join("src/server/assets/three-bundle.js"))
        .args(files.iter().map(|(_, f, _)| f))
        .output()
        .unwrap();
    std::fs::remove_dir_all(&dir).unwrap();
    let stdout = String::from_utf8_lossy(&output.stdout);
    assert!(
        output.status.success(),
        "load-glb-test.js failed: {stdout}\n{}",
        String::from_utf8_lossy(&output.stderr)
    );
    let report: Value = serde_json::from_str(&stdout).unwrap();
    let patches = scene
        .vessels
        .iter()
        .flat_map(|v| &v.nodes)
        .flat_map(|n| &n.patches)
        .filter(|p| p.mesh.triangle_count() > 0);
    let (count, triangles) = patches.fold((0, 0), |(c, t), p| (c + 1, t + p.mesh.triangle_count()));
    for pair in files.chunks(2) {
        let (plain, instanced) = (&report[&pair[0].0], &report[&pair[1].0]);
        println!("{}: {plain}\n{}: {instanced}", pair[0].0, pair[1].0);
        for (got, (name, _, draws)) in [(plain, &pair[0]), (instanced, &pair[1])] {
            assert_eq!(got["meshes"], *draws, "{name}: draw calls");
            assert_eq!(got["drawn"], count, "{name}: patches drawn");
            assert_eq!(got["triangles"], triangles, "{name}");
        }
        assert!(instanced["meshes"].as_u64() < plain["meshes"].as_u64());
        for k in 0..6 {
            let (a, b) = (
                instanced["box"][k].as_f64().unwrap(),
                plain["box"][k].as_f64().unwrap(),
            );
            assert!(
                (a - b).abs() * 1e3 <= 0.01,
                "{}: box {k}: {a} m, {b} m",
                pair[1].0
            );
        }
        assert_eq!(instanced["vessel"]["id"], scene.vessels[0].tag.as_str());
    }
}
