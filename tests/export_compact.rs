//! The compact GLB options: patches that share a mesh share one glTF mesh and
//! draw what they drew on their own; a quantized file (`KHR_mesh_quantization`)
//! still holds the chordal tolerance against the exact surfaces at every point;
//! meshopt compression (`EXT_meshopt_compression`) decodes to the same numbers;
//! names and extras survive every option; the streaming writer writes the same
//! bytes; and the Khronos validator reports no error and no warning on any of
//! them.

mod common;

use std::collections::HashSet;
use std::sync::OnceLock;

use common::examples::example;
use common::glb::{Glb, validate};
use common::triangle::largest_distance;
use glam::DVec3;
use serde_json::Value;
use vesselcad::design::{Design, resolve};
use vesselcad::export::{
    Compression, GlbOptions, Scene, build_scene, patch_name, quantization_budget, stream_glb_with,
    write_glb_with,
};
use vesselcad::mesh::TessellationOptions;
use vesselcad::model::Model;

const TOLERANCE: f64 = 1.0;

/// Every variant of the writer, by name.
fn variants() -> [(&'static str, GlbOptions); 6] {
    let plain = GlbOptions {
        reuse: false,
        ..GlbOptions::default()
    };
    let quantized = GlbOptions {
        quantize: Some(quantization_budget(TOLERANCE)),
        ..GlbOptions::default()
    };
    let meshopt = GlbOptions {
        compress: Compression::Meshopt,
        ..GlbOptions::default()
    };
    [
        ("default", GlbOptions::default()),
        ("no-reuse", plain),
        ("quantized", quantized),
        ("meshopt", meshopt),
        ("compact", GlbOptions::compact(TOLERANCE)),
        ("flat", GlbOptions::compact(TOLERANCE).flat()),
    ]
}

/// The small plant built by the model (which shares meshes between patches) at
/// the meshing tolerance of a quantized file.
fn plant() -> &'static (Design, Scene) {
    static PLANT: OnceLock<(Design, Scene)> = OnceLock::new();
    PLANT.get_or_init(|| {
        let design = example("small-plant");
        let tolerance = GlbOptions::compact(TOLERANCE).meshing_tolerance(TOLERANCE);
        let model = Model::from_design(&design, TessellationOptions::chord(tolerance)).unwrap();
        let scene = model.scene();
        (design, scene)
    })
}

/// The patch nodes of a file, depth first: (vessel, part, patch node index).
fn patch_nodes(glb: &Glb) -> Vec<(String, String, usize)> {
    let mut out = Vec::new();
    for vessel in glb.children(glb.root()) {
        for part in glb.children(vessel) {
            for patch in glb.children(part) {
                let name = |n: usize| glb.node(n)["name"].as_str().unwrap().to_string();
                out.push((name(vessel), name(part), patch));
            }
        }
    }
    out
}

/// What a patch node draws, in its part's frame, mm: each triangle's corners.
fn drawn(glb: &Glb, node: usize) -> Vec<[DVec3; 3]> {
    let mesh = glb.node(node)["mesh"].as_u64().unwrap() as usize;
    let local = glb.local_matrix(node);
    let p = glb.primitive(mesh);
    let points: Vec<DVec3> = p
        .positions
        .iter()
        .map(|&q| local.transform_point3(q) * 1e3)
        .collect();
    p.indices
        .chunks_exact(3)
        .map(|t| [0, 1, 2].map(|k| points[t[k] as usize]))
        .collect()
}

#[test]
fn patches_that_share_a_mesh_share_one_gltf_mesh_and_draw_the_same() {
    let (_, scene) = plant();
    let with = Glb::parse(&write_glb_with(scene, &GlbOptions::default()).unwrap());
    let without = Glb::parse(
        &write_glb_with(
            scene,
            &GlbOptions {
                reuse: false,
                ..GlbOptions::default()
            },
        )
        .unwrap(),
    );
    let nodes = patch_nodes(&with);
    let meshes = with.json["meshes"].as_array().unwrap().len();
    let distinct: HashSet<u64> = nodes
        .iter()
        .map(|&(_, _, n)| with.node(n)["mesh"].as_u64().unwrap())
        .collect();
    println!(
        "{} patch nodes, {meshes} meshes with reuse, {} without",
        nodes.len(),
        without.json["meshes"].as_array().unwrap().len()
    );
    assert_eq!(distinct.len(), meshes, "every mesh is used");
    // The small plant's four vessels repeat flanges, necks and heads: a third
    // of its patches draw a mesh another patch draws.
    assert!(
        10 * meshes < 7 * nodes.len(),
        "{meshes} meshes for {} patches: equal meshes are not shared",
        nodes.len()
    );
    let plain_nodes = patch_nodes(&without);
    assert_eq!(plain_nodes.len(), nodes.len());
    for (a, b) in nodes.iter().zip(&plain_nodes) {
        assert_eq!((&a.0, &a.1), (&b.0, &b.1));
        assert_eq!(with.node(a.2)["name"], without.node(b.2)["name"]);
        assert_eq!(drawn(&with, a.2), drawn(&without, b.2), "{}/{}", a.0, a.1);
    }
}

/// Equal meshes are found by content too: a direct build makes each mesh
/// apart, and its file shares them as the model's does.
#[test]
fn a_direct_build_shares_equal_meshes_like_the_model() {
    let (design, scene) = plant();
    let tolerance = GlbOptions::compact(TOLERANCE).meshing_tolerance(TOLERANCE);
    let direct = build_scene(design, &TessellationOptions::chord(tolerance)).unwrap();
    let options = GlbOptions::default();
    assert!(
        write_glb_with(&direct, &options).unwrap() == write_glb_with(scene, &options).unwrap(),
        "the direct build's file differs from the model's"
    );
}

#[test]
fn quantized_files_hold_the_chordal_tolerance_against_the_exact_surfaces() {
    let design = example("horizontal-drum");
    let resolved = resolve(&design).unwrap();
    let compact = GlbOptions::compact(TOLERANCE);
    let options = TessellationOptions::chord(compact.meshing_tolerance(TOLERANCE));
    let scene = build_scene(&design, &options).unwrap();
    let glb = Glb::parse(&write_glb_with(&scene, &compact).unwrap());
    assert_eq!(glb.json["extensionsRequired"][0], "KHR_mesh_quantization");
    let (mut checked, mut quantized, mut meshes, mut worst) = (0, 0, 0, 0.0f64);
    for (tag, part_id, node) in patch_nodes(&glb) {
        let vessel = resolved.iter().find(|v| v.tag == tag).unwrap();
        let patches = match vessel.parts.iter().find(|p| p.id == part_id) {
            Some(part) => part.geometry.patches().unwrap(),
            None => {
                let nozzle = vessel.nozzles.iter().find(|n| n.mark == part_id).unwrap();
                nozzle.geometry.patches().unwrap()
            }
        };
        let name = glb.node(node)["name"].as_str().unwrap();
        // A nozzle's pad lies on its host's surface, not among its patches.
        let Some(patch) = patches.iter().find(|p| patch_name(p) == name) else {
            continue;
        };
        meshes += 1;
        quantized += usize::from(glb.node(node)["scale"].is_array());
        for triangle in drawn(&glb, node) {
            let d = largest_distance(&patch.analytic, triangle);
            worst = worst.max(d);
            assert!(
                d <= TOLERANCE,
                "{tag}/{part_id}/{name}: {d} mm > {TOLERANCE} mm"
            );
            checked += 1;
        }
    }
    println!(
        "{checked} triangles of {meshes} patch nodes ({quantized} quantized): worst {worst:.4} mm"
    );
    assert!(checked > 1000, "{checked} triangles");
    assert!(quantized == meshes, "{quantized} of {meshes} quantized");
}

/// Names, extras and what every node draws are the same whatever the options
/// (within the quantization bound).
#[test]
fn every_option_keeps_the_tree_names_extras_and_geometry() {
    let (_, scene) = plant();
    let reference = Glb::parse(&write_glb_with(scene, &GlbOptions::default()).unwrap());
    let tree = |glb: &Glb| -> Vec<(Value, Value)> {
        let mut out = Vec::new();
        let mut stack = vec![glb.root()];
        while let Some(n) = stack.pop() {
            out.push((glb.node(n)["name"].clone(), glb.node(n)["extras"].clone()));
            stack.extend(glb.children(n).into_iter().rev());
        }
        out
    };
    let bound = quantization_budget(TOLERANCE) + 1e-3;
    for (name, options) in variants() {
        let glb = Glb::parse(&write_glb_with(scene, &options).unwrap());
        assert!(tree(&glb) == tree(&reference), "{name}: tree differs");
        for ((_, _, a), (_, _, b)) in patch_nodes(&glb).into_iter().zip(patch_nodes(&reference)) {
            let (got, expected) = (drawn(&glb, a), drawn(&reference, b));
            assert_eq!(got.len(), expected.len(), "{name}");
            // Compression reorders triangles: compare each triangle's corners as
            // sets, after sorting the triangles.
            let key = |t: &[DVec3; 3]| {
                let mut c = t.map(|p| p.to_array());
                c.sort_by(|x, y| x.partial_cmp(y).unwrap());
                c
            };
            // (the index codec may also rotate a triangle's corners).
            let sort = |v: Vec<[DVec3; 3]>| {
                let mut keys: Vec<_> = v.iter().map(key).collect();
                keys.sort_by(|x, y| x.partial_cmp(y).unwrap());
                keys
            };
            if options.compress == Compression::None {
                for (g, e) in got.iter().zip(&expected) {
                    for k in 0..3 {
                        assert!(
                            g[k].distance(e[k]) <= bound,
                            "{name}: {} mm",
                            g[k].distance(e[k])
                        );
                    }
                }
            } else if options.quantize.is_none() {
                assert_eq!(sort(got), sort(expected), "{name}");
            }
        }
    }
}

#[test]
fn streaming_writes_the_same_bytes_for_every_option() {
    let (_, scene) = plant();
    for (name, options) in variants() {
        let mut streamed = Vec::new();
        let n = stream_glb_with(scene, &options, &mut streamed, "<memory>".as_ref()).unwrap();
        assert_eq!(n as usize, streamed.len(), "{name}");
        assert!(
            streamed == write_glb_with(scene, &options).unwrap(),
            "{name}: streamed bytes differ"
        );
    }
}

#[test]
fn khronos_validator_finds_no_errors_and_no_warnings_on_any_option() {
    let (_, scene) = plant();
    for (name, options) in variants() {
        let bytes = write_glb_with(scene, &options).unwrap();
        let Some(report) = validate(name, &bytes) else {
            return;
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

/// three.js (the bundle `vesselcad serve` embeds, with its `MeshoptDecoder`)
/// loads every variant in headless Chromium: the same meshes, triangles, named
/// nodes and bounds (within the quantization bound), and the vessels' extras.
#[test]
fn three_js_loads_every_option_in_chromium() {
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR"));
    let driver = root.join("tests/support/node_modules/playwright-core/package.json");
    if !driver.is_file() || !std::path::Path::new("/usr/bin/chromium").exists() {
        let missing = "Chromium or playwright-core is missing: install Debian's chromium and \
                       run npm ci --prefix tests/support";
        assert!(std::env::var_os("CI").is_none(), "{missing}");
        eprintln!("{missing}");
        return;
    }
    let (_, scene) = plant();
    let dir = std::env::temp_dir().join(format!("vesselcad-compact-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let mut files = Vec::new();
    for (name, options) in variants() {
        let file = dir.join(format!("{name}.glb"));
        std::fs::write(&file, write_glb_with(scene, &options).unwrap()).unwrap();
        files.push((name, file));
    }
    let output = std::process::Command::new("node")
        .arg(root.join("tests/support/load-glb-test.js"))
        .arg(root.join("src/server/assets/three-bundle.js"))
        .args(files.iter().map(|(_, f)| f))
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
    let reference = &report["default.glb"];
    for (name, _) in &files {
        let got = &report[format!("{name}.glb")];
        println!(
            "{name}: {}",
            serde_json::json!({
                "meshes": got["meshes"], "triangles": got["triangles"], "vertices": got["vertices"]
            })
        );
        assert_eq!(got["meshes"], count, "{name}: {got}");
        // Without normals three.js shades flat, as the glTF specification asks.
        let flat = if *name == "flat" { count } else { 0 };
        assert_eq!(got["flat"], flat, "{name}: {got}");
        assert_eq!(got["triangles"], triangles, "{name}: {got}");
        assert_eq!(got["names"], reference["names"], "{name}");
        assert_eq!(got["vessel"]["id"], scene.vessels[0].tag.as_str(), "{name}");
        for k in 0..6 {
            let (a, b) = (
                got["box"][k].as_f64().unwrap(),
                reference["box"][k].as_f64().unwrap(),
            );
            assert!(
                (a - b).abs() * 1e3 <= quantization_budget(TOLERANCE),
                "{name}: box {k}: {a} m, {b} m"
            );
        }
    }
}

/// Compressed byte normals go through meshopt's `OCTAHEDRAL` filter and decode
/// (as three.js's decoder does) to unit normals within 2° of the quantized,
/// uncompressed file's at the same positions. Without the filter the example
/// drum's normals took 17.3 KB of its 75.7 KB compact file merged per vessel.
#[test]
fn compressed_normals_are_octahedral_and_decode_within_two_degrees() {
    let (_, scene) = plant();
    let compact = GlbOptions::compact(TOLERANCE);
    let packed = Glb::parse(&write_glb_with(scene, &compact).unwrap());
    let plain = Glb::parse(
        &write_glb_with(
            scene,
            &GlbOptions {
                compress: Compression::None,
                ..compact
            },
        )
        .unwrap(),
    );
    let views = packed.json["bufferViews"].as_array().unwrap();
    let filtered: Vec<&Value> = views
        .iter()
        .map(|v| &v["extensions"]["EXT_meshopt_compression"])
        .filter(|e| e["filter"] == "OCTAHEDRAL")
        .collect();
    assert_eq!(filtered.len(), 1, "one normal view, filtered");
    assert_eq!(filtered[0]["byteStride"], 4);
    let key = |p: DVec3| p.to_array().map(|c| (c * 1e4).round() as i64);
    let mut checked = 0;
    let meshes = packed.json["meshes"].as_array().unwrap().len();
    for mesh in 0..meshes {
        let (got, reference) = (packed.primitive(mesh), plain.primitive(mesh));
        let mut at = std::collections::HashMap::new();
        for (p, n) in reference.positions.iter().zip(&reference.normals) {
            at.entry(key(*p)).or_insert_with(Vec::new).push(*n);
        }
        for (p, n) in got.positions.iter().zip(&got.normals) {
            assert!((n.length() - 1.0).abs() < 0.02, "|n| = {}", n.length());
            let best = at[&key(*p)]
                .iter()
                .map(|r| n.normalize().angle_between(r.normalize()).to_degrees())
                .fold(f64::INFINITY, f64::min);
            assert!(best <= 2.0, "mesh {mesh}: {best}°");
            checked += 1;
        }
    }
    assert!(checked > 10_000, "{checked} normals");
}
