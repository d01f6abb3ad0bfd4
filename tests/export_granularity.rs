//! `--granularity`: patch meshes merged per part, vessel or plant. A merged file
//! draws the same triangles, holds the chordal tolerance against the exact
//! surfaces at every point (quantized and compressed too), keeps the names and
//! extras of the nodes that remain, has one draw call per merged node and
//! material, passes the Khronos validator with no error and no warning, and
//! loads in three.js in headless Chromium.

mod common;

use std::sync::OnceLock;

use common::examples::example;
use common::glb::{Glb, validate};
use common::triangle::largest_distance;
use glam::{DAffine3, DMat4, DVec3};
use serde_json::Value;
use vesselcad::design::{Design, resolve};
use vesselcad::export::{GlbOptions, Granularity, Scene, build_scene, merge_scene, write_glb_with};
use vesselcad::mesh::TessellationOptions;
use vesselcad::model::Model;

const TOLERANCE: f64 = 1.0;
const MERGED: [(&str, Granularity); 3] = [
    ("part", Granularity::Part),
    ("vessel", Granularity::Vessel),
    ("plant", Granularity::Plant),
];

/// The small plant built by the model at a quantized file's meshing tolerance.
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

/// Every mesh node of a file with its world matrix (glTF frame, metres).
fn mesh_nodes(glb: &Glb) -> Vec<(usize, DMat4)> {
    let mut out = Vec::new();
    let mut stack = vec![(glb.root(), DMat4::IDENTITY)];
    while let Some((n, parent)) = stack.pop() {
        let world = parent * glb.local_matrix(n);
        if glb.node(n)["mesh"].is_u64() {
            out.push((n, world));
        }
        stack.extend(glb.children(n).into_iter().map(|c| (c, world)));
    }
    out
}

/// Every triangle a file draws, in the plant frame, mm.
fn drawn(glb: &Glb) -> Vec<[DVec3; 3]> {
    // glTF (x, y, z) → plant (x, −z, y), m → mm: undoes the root's rotation.
    let back = DMat4::from_cols_array(&[
        1.0, 0.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, -1.0, 0.0, 0.0, 0.0, 0.0, 0.0, 1.0,
    ]) * 1e3;
    let mut out = Vec::new();
    for (node, world) in mesh_nodes(glb) {
        let p = glb.primitive(glb.node(node)["mesh"].as_u64().unwrap() as usize);
        let to_plant = back * world;
        let points: Vec<DVec3> = p
            .positions
            .iter()
            .map(|&q| to_plant.transform_point3(q))
            .collect();
        out.extend(
            p.indices
                .chunks_exact(3)
                .map(|t| [0, 1, 2].map(|k| points[t[k] as usize])),
        );
    }
    out
}

/// Names and extras of the vessel and part nodes, depth first, for a file
/// with vessel (and part) nodes.
fn tree(glb: &Glb, depth: usize) -> Vec<(Value, Value)> {
    let mut out = Vec::new();
    let mut level = glb.children(glb.root());
    for _ in 0..depth {
        let mut next = Vec::new();
        for n in level {
            out.push((glb.node(n)["name"].clone(), glb.node(n)["extras"].clone()));
            next.extend(glb.children(n));
        }
        level = next;
    }
    out
}

#[test]
fn merged_files_draw_the_same_triangles_with_fewer_draw_calls_and_keep_ids() {
    let (_, scene) = plant();
    let reference = Glb::parse(&write_glb_with(scene, &GlbOptions::default()).unwrap());
    let expected = drawn(&reference);
    let patches = mesh_nodes(&reference).len();
    for (name, granularity) in MERGED {
        let merged = merge_scene(scene, granularity);
        let glb = Glb::parse(&write_glb_with(&merged, &GlbOptions::default()).unwrap());
        let got = drawn(&glb);
        let calls = mesh_nodes(&glb).len();
        println!("{name}: {calls} draw calls for {patches} patches");
        assert_eq!(got.len(), expected.len(), "{name}: triangles");
        let limit = match granularity {
            Granularity::Part => scene.vessels.iter().map(|v| v.nodes.len()).sum(),
            Granularity::Vessel => 3 * scene.vessels.len(),
            _ => 3,
        };
        assert!(calls <= limit, "{name}: {calls} draw calls > {limit}");
        // Same triangles: every merged triangle's corners lie on a reference
        // triangle's corners, compared through a grid of 0.01 mm.
        let key = |p: DVec3| (p * 100.0).round().as_i64vec3().to_array();
        let corners: std::collections::HashSet<[i64; 3]> =
            expected.iter().flatten().map(|&p| key(p)).collect();
        let near = |p: DVec3| {
            (-1..=1).any(|dx| {
                (-1..=1).any(|dy| {
                    (-1..=1).any(|dz| {
                        let k = key(p);
                        corners.contains(&[k[0] + dx, k[1] + dy, k[2] + dz])
                    })
                })
            })
        };
        let strays = got.iter().flatten().filter(|&&p| !near(p)).count();
        assert_eq!(strays, 0, "{name}: corners not in the reference");
        match granularity {
            Granularity::Part => assert!(tree(&glb, 2) == tree(&reference, 2), "{name}: ids"),
            Granularity::Vessel => {
                assert!(tree(&glb, 1) == tree(&reference, 1), "{name}: ids");
                for part in glb.children(glb.children(glb.root())[0]) {
                    assert_eq!(glb.node(part)["extras"]["kind"], "merged", "{name}");
                    assert!(
                        !glb.node(part)["extras"]["ids"]
                            .as_array()
                            .unwrap()
                            .is_empty()
                    );
                }
            }
            _ => {
                let vessel = glb.children(glb.root())[0];
                let tags: Vec<Value> = scene
                    .vessels
                    .iter()
                    .map(|v| v.tag.as_str().into())
                    .collect();
                assert_eq!(glb.node(vessel)["extras"]["vessels"], Value::from(tags));
            }
        }
    }
}

/// Merged, quantized and compressed meshes hold the tolerance against the
/// exact surfaces: every triangle of the drum's merged meshes is within it of
/// one of the vessel's patches.
#[test]
fn merged_compact_files_hold_the_chordal_tolerance_against_the_exact_surfaces() {
    let design = example("horizontal-drum");
    let resolved = resolve(&design).unwrap();
    let compact = GlbOptions::compact(TOLERANCE);
    let scene = build_scene(
        &design,
        &TessellationOptions::chord(compact.meshing_tolerance(TOLERANCE)),
    )
    .unwrap();
    let vessel = &scene.vessels[0];
    let exact = &resolved[0];
    // Every patch of the vessel with its part's frame (part → plant).
    let mut surfaces = Vec::new();
    for node in &vessel.nodes {
        let patches = match exact.parts.iter().find(|p| p.id == node.id) {
            Some(part) => part.geometry.patches().unwrap(),
            None => {
                let nozzle = exact.nozzles.iter().find(|n| n.mark == node.id).unwrap();
                nozzle.geometry.patches().unwrap()
            }
        };
        let to_local: DAffine3 = (vessel.frame * node.frame).inverse();
        for patch in patches {
            surfaces.push((patch.analytic, to_local));
        }
    }
    for (name, granularity) in MERGED {
        let merged = merge_scene(&scene, granularity);
        let glb = Glb::parse(&write_glb_with(&merged, &compact).unwrap());
        let (mut worst, mut last) = (0.0f64, 0);
        let triangles = drawn(&glb);
        for t in &triangles {
            let distance = |k: usize| {
                let (analytic, to_local) = &surfaces[k];
                largest_distance(analytic, t.map(|p| to_local.transform_point3(p)))
            };
            let mut d = distance(last);
            if d > TOLERANCE
                && let Some((k, dk)) = (0..surfaces.len())
                    .map(|k| (k, distance(k)))
                    .min_by(|a, b| a.1.total_cmp(&b.1))
            {
                (last, d) = (k, dk);
            }
            worst = worst.max(d);
            assert!(d <= TOLERANCE, "{name}: {d} mm > {TOLERANCE} mm");
        }
        println!("{name}: {} triangles, worst {worst:.4} mm", triangles.len());
        assert!(triangles.len() > 1000);
    }
}

/// A compact file writes a vertex once: the vertices merged patches share
/// along their boundaries (and a periodic patch's seam) are welded, so no mesh
/// of a merged compact file holds two vertices with the same position and
/// normal, and each writes fewer vertices than its patches hold. Triangles keep
/// their count (checked above and in Chromium).
#[test]
fn merged_compact_files_write_each_shared_vertex_once() {
    let (_, scene) = plant();
    for (name, granularity) in MERGED {
        let merged = merge_scene(scene, granularity);
        let glb = Glb::parse(&write_glb_with(&merged, &GlbOptions::compact(TOLERANCE)).unwrap());
        let held: usize = merged
            .vessels
            .iter()
            .flat_map(|v| &v.nodes)
            .flat_map(|n| &n.patches)
            .map(|p| p.mesh.vertex_count())
            .sum();
        let mut written = 0;
        for mesh in 0..glb.json["meshes"].as_array().unwrap().len() {
            let p = glb.primitive(mesh);
            let mut seen = std::collections::HashSet::new();
            let twice = p
                .positions
                .iter()
                .zip(&p.normals)
                .filter(|(q, n)| {
                    !seen.insert((
                        q.to_array().map(f64::to_bits),
                        n.to_array().map(f64::to_bits),
                    ))
                })
                .count();
            assert_eq!(
                twice, 0,
                "{name}: mesh {mesh} writes {twice} vertices twice"
            );
            written += p.positions.len();
        }
        println!("{name}: {written} vertices written of {held} held");
        assert!(
            written < held,
            "{name}: {written} vertices written of {held}"
        );
    }
}

#[test]
fn khronos_validator_finds_no_errors_and_no_warnings_on_merged_files() {
    let (_, scene) = plant();
    for (name, granularity) in MERGED {
        let merged = merge_scene(scene, granularity);
        for (variant, options) in [
            ("default", GlbOptions::default()),
            ("compact", GlbOptions::compact(TOLERANCE)),
        ] {
            let bytes = write_glb_with(&merged, &options).unwrap();
            let Some(report) = validate(&format!("{name}-{variant}"), &bytes) else {
                return;
            };
            println!(
                "{name} {variant}: {} bytes, {} errors, {} warnings, {} infos",
                bytes.len(),
                report["numErrors"],
                report["numWarnings"],
                report["numInfos"]
            );
            assert_eq!(report["numErrors"], 0, "{name} {variant}: {report:#}");
            assert_eq!(report["numWarnings"], 0, "{name} {variant}: {report:#}");
        }
    }
}

/// three.js loads every merged file (compact) in headless Chromium: one mesh
/// per merged node, every triangle.
#[test]
fn three_js_loads_merged_files_in_chromium() {
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
    let dir = std::env::temp_dir().join(format!("vesselcad-granularity-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let mut files = Vec::new();
    for (name, granularity) in MERGED {
        let merged = merge_scene(scene, granularity);
        let bytes = write_glb_with(&merged, &GlbOptions::compact(TOLERANCE)).unwrap();
        let calls = mesh_nodes(&Glb::parse(&bytes)).len();
        let file = dir.join(format!("{name}.glb"));
        std::fs::write(&file, bytes).unwrap();
        files.push((name, file, calls));
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
    let triangles: usize = scene
        .vessels
        .iter()
        .flat_map(|v| &v.nodes)
        .flat_map(|n| &n.patches)
        .map(|p| p.mesh.triangle_count())
        .sum();
    for (name, _, calls) in &files {
        let got = &report[format!("{name}.glb")];
        println!("{name}: {got}");
        assert_eq!(got["meshes"], *calls, "{name}: {got}");
        assert_eq!(got["triangles"], triangles, "{name}: {got}");
    }
}
