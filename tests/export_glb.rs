//! GLB export of every example design at a 1 mm chordal tolerance: the node tree
//! and its names, `extras`, the Z-up → Y-up root rotation, positions in metres,
//! unit normals, deterministic bytes, and the Khronos glTF validator (npm
//! `gltf-validator`, installed with `npm ci --prefix tests/support`).

use std::path::{Path, PathBuf};
use std::process::Command;
use std::sync::OnceLock;

use glam::{DMat4, DVec3};
use gltf::Gltf;
use serde_json::Value;
use vesselcad::design::{Design, load, resolve};
use vesselcad::export::{PLANT_NODE, PLANT_ROTATION, build_scene, write_glb};
use vesselcad::mesh::TessellationOptions;

const TOLERANCE_MM: f64 = 1.0;
const MISSING_VALIDATOR: &str =
    "gltf-validator is not installed: run npm ci --prefix tests/support";

/// One example design and its GLB.
struct Example {
    name: String,
    design: Design,
    glb: Vec<u8>,
}

/// Every example design, built and written once for all tests.
fn examples() -> &'static [Example] {
    static EXAMPLES: OnceLock<Vec<Example>> = OnceLock::new();
    EXAMPLES.get_or_init(|| {
        let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/designs");
        let mut paths: Vec<PathBuf> = std::fs::read_dir(&dir)
            .unwrap()
            .map(|e| e.unwrap().path())
            .filter(|p| p.extension().is_some_and(|e| e == "json"))
            .collect();
        paths.sort();
        assert!(!paths.is_empty(), "no example designs in {}", dir.display());
        paths
            .into_iter()
            .map(|path| {
                let design = load(&path).unwrap();
                let glb = glb_of(&design);
                let name = path.file_stem().unwrap().to_string_lossy().into_owned();
                Example { name, design, glb }
            })
            .collect()
    })
}

fn glb_of(design: &Design) -> Vec<u8> {
    let scene = build_scene(design, &TessellationOptions::chord(TOLERANCE_MM)).unwrap();
    write_glb(&scene).unwrap()
}

fn example(name: &str) -> &'static Example {
    examples().iter().find(|e| e.name == name).unwrap()
}

fn extras(node: &gltf::Node) -> Value {
    let raw = node.extras().as_ref().expect("node has extras");
    serde_json::from_str(raw.get()).unwrap()
}

fn local_matrix(node: &gltf::Node) -> DMat4 {
    let cols = node.transform().matrix();
    DMat4::from_cols_array_2d(&cols.map(|c| c.map(f64::from)))
}

#[test]
fn node_tree_is_plant_vessels_parts_patches_with_names_and_extras() {
    for example in examples() {
        let gltf = Gltf::from_slice(&example.glb).unwrap();
        let scene = gltf.default_scene().unwrap();
        let roots: Vec<_> = scene.nodes().collect();
        assert_eq!(roots.len(), 1, "{}", example.name);
        let plant = &roots[0];
        assert_eq!(plant.name(), Some(PLANT_NODE));
        let vessels: Vec<_> = plant.children().collect();
        let tags: Vec<_> = example
            .design
            .vessels
            .iter()
            .map(|v| v.tag.as_str())
            .collect();
        let names: Vec<_> = vessels.iter().map(|n| n.name().unwrap()).collect();
        assert_eq!(names, tags, "{}", example.name);
        for (node, vessel) in vessels.iter().zip(&example.design.vessels) {
            let x = extras(node);
            assert_eq!(x["id"], vessel.tag.as_str());
            assert!(x["kind"].is_string(), "{}: vessel kind", vessel.tag);
            assert!(x["resolved"]["tangent_length"].as_f64().unwrap() > 0.0);
            let children: Vec<_> = node.children().collect();
            let expected: Vec<(&str, &str)> = vessel
                .parts
                .iter()
                .map(|p| (p.id(), p.kind()))
                .chain(vessel.nozzles.iter().map(|n| (n.mark.as_str(), "nozzle")))
                .collect();
            assert_eq!(children.len(), expected.len(), "{}", vessel.tag);
            for (child, (id, kind)) in children.iter().zip(expected) {
                assert_eq!(child.name(), Some(id), "{}", vessel.tag);
                let x = extras(child);
                assert_eq!(x["kind"], kind, "{}/{id}", vessel.tag);
                assert_eq!(x["id"], id, "{}/{id}", vessel.tag);
                assert!(x["parameters"].is_object(), "{}/{id}", vessel.tag);
                let patches: Vec<_> = child.children().collect();
                assert!(!patches.is_empty(), "{}/{id} has no patches", vessel.tag);
                for patch in patches {
                    assert!(!patch.name().unwrap().is_empty());
                    assert!(
                        patch.mesh().is_some(),
                        "{}/{id}: patch without mesh",
                        vessel.tag
                    );
                    assert_eq!(patch.children().count(), 0);
                }
            }
        }
    }
}

#[test]
fn root_rotation_turns_plant_z_up_into_gltf_y_up() {
    let gltf = Gltf::from_slice(&examples()[0].glb).unwrap();
    let plant = gltf.default_scene().unwrap().nodes().next().unwrap();
    let (translation, rotation, scale) = plant.transform().decomposed();
    assert_eq!(rotation, PLANT_ROTATION);
    assert_eq!(translation, [0.0; 3]);
    assert_eq!(scale, [1.0; 3]);
    let m = local_matrix(&plant);
    let up = m.transform_vector3(DVec3::Z);
    let north = m.transform_vector3(DVec3::Y);
    let east = m.transform_vector3(DVec3::X);
    assert!((up - DVec3::Y).length() < 1e-7, "{up}");
    assert!((north - DVec3::NEG_Z).length() < 1e-7, "{north}");
    assert!((east - DVec3::X).length() < 1e-7, "{east}");
}

/// World-space (glTF, m) bounds of every vertex under the node `path`
/// (`[vessel tag, part id]`) of an example.
fn world_bounds(example: &Example, path: [&str; 2]) -> (DVec3, DVec3) {
    let gltf = Gltf::from_slice(&example.glb).unwrap();
    let blob = gltf.blob.as_deref().unwrap();
    let plant = gltf.default_scene().unwrap().nodes().next().unwrap();
    let vessel = plant
        .children()
        .find(|n| n.name() == Some(path[0]))
        .unwrap();
    let part = vessel
        .children()
        .find(|n| n.name() == Some(path[1]))
        .unwrap();
    let to_part = local_matrix(&plant) * local_matrix(&vessel) * local_matrix(&part);
    let mut lo = DVec3::splat(f64::INFINITY);
    let mut hi = DVec3::splat(f64::NEG_INFINITY);
    for patch in part.children() {
        let to_world = to_part * local_matrix(&patch);
        for primitive in patch.mesh().unwrap().primitives() {
            let reader = primitive.reader(|_| Some(blob));
            for p in reader.read_positions().unwrap() {
                let w = to_world.transform_point3(DVec3::from(p.map(f64::from)));
                lo = lo.min(w);
                hi = hi.max(w);
            }
        }
    }
    (lo, hi)
}

fn assert_close(what: &str, got: DVec3, expected: DVec3, tolerance: f64) {
    assert!(
        (got - expected).abs().max_element() <= tolerance,
        "{what}: got {got}, expected {expected}"
    );
}

/// Chordal error and f32 rounding, m: vertices lie on the surface, so a bound
/// falls short of the exact one by at most about the tolerance.
const BOUNDS_SLACK_M: f64 = 2.0 * TOLERANCE_MM / 1000.0;

#[test]
fn drum_shell_bounds_are_its_dimensions_in_metres_y_up() {
    // V-101: horizontal, axis bearing 90° (east = glTF +X), datum at 2000 mm up;
    // S1 is OD 2400 × 7200.
    let example = example("horizontal-drum");
    let resolved = resolve(&example.design).unwrap();
    let s1 = resolved[0].parts.iter().find(|p| p.id == "S1").unwrap();
    let (start, end) = (s1.span.0 / 1000.0, s1.span.1 / 1000.0);
    assert!((end - start - 7.2).abs() < 1e-9);
    let (lo, hi) = world_bounds(example, ["V-101", "S1"]);
    assert_close("S1 min", lo, DVec3::new(start, 0.8, -1.2), BOUNDS_SLACK_M);
    assert_close("S1 max", hi, DVec3::new(end, 3.2, 1.2), BOUNDS_SLACK_M);
}

#[test]
fn column_shell_bounds_are_its_dimensions_in_metres_y_up() {
    // C-201: vertical at 20 m east; S1 is OD 2000 × 12000 above the datum.
    let example = example("vertical-column");
    let resolved = resolve(&example.design).unwrap();
    let s1 = resolved[0].parts.iter().find(|p| p.id == "S1").unwrap();
    let (start, end) = (s1.span.0 / 1000.0, s1.span.1 / 1000.0);
    assert!((end - start - 12.0).abs() < 1e-9);
    let (lo, hi) = world_bounds(example, ["C-201", "S1"]);
    assert_close("S1 min", lo, DVec3::new(19.0, start, -1.0), BOUNDS_SLACK_M);
    assert_close("S1 max", hi, DVec3::new(21.0, end, 1.0), BOUNDS_SLACK_M);
}

#[test]
fn normals_are_unit_and_positions_within_accessor_bounds() {
    for example in examples() {
        let gltf = Gltf::from_slice(&example.glb).unwrap();
        let blob = gltf.blob.as_deref().unwrap();
        assert!(gltf.meshes().count() > 0, "{}", example.name);
        for mesh in gltf.meshes() {
            for primitive in mesh.primitives() {
                let reader = primitive.reader(|_| Some(blob));
                let bounds = primitive.bounding_box();
                let positions: Vec<[f32; 3]> = reader.read_positions().unwrap().collect();
                let normals: Vec<[f32; 3]> = reader.read_normals().unwrap().collect();
                assert_eq!(positions.len(), normals.len());
                for &n in &normals {
                    let length = glam::Vec3::from(n).length();
                    assert!(
                        (length - 1.0).abs() < 1e-6,
                        "{:?}: |n| = {length}",
                        mesh.name()
                    );
                }
                let (lo, hi) = (glam::Vec3::from(bounds.min), glam::Vec3::from(bounds.max));
                for &p in &positions {
                    let p = glam::Vec3::from(p);
                    assert!(
                        p.cmpge(lo).all() && p.cmple(hi).all(),
                        "{p} outside {lo}..{hi}"
                    );
                }
                let indices: Vec<u32> = reader.read_indices().unwrap().into_u32().collect();
                assert!(!indices.is_empty() && indices.len().is_multiple_of(3));
                assert_front_faces_outward(&positions, &normals, &indices, mesh.name());
            }
        }
    }
}

/// Materials are single-sided: every counter-clockwise triangle must face the
/// way its vertex normals point.
fn assert_front_faces_outward(
    positions: &[[f32; 3]],
    normals: &[[f32; 3]],
    indices: &[u32],
    mesh: Option<&str>,
) {
    let vec = |a: [f32; 3]| glam::Vec3::from(a);
    for triangle in indices.chunks_exact(3) {
        let [a, b, c] = [0, 1, 2].map(|k| triangle[k] as usize);
        let face =
            (vec(positions[b]) - vec(positions[a])).cross(vec(positions[c]) - vec(positions[a]));
        let normal = vec(normals[a]) + vec(normals[b]) + vec(normals[c]);
        assert!(
            face.dot(normal) >= 0.0,
            "{mesh:?}: triangle {triangle:?} faces inward"
        );
    }
}

/// Supports are sheets (a skirt and its base ring, a saddle's web and plates,
/// base plates): seen from both sides, so their material is double-sided, or
/// back-face culling hides one side. The vessel and nozzles, seen from outside,
/// stay single-sided.
#[test]
fn support_sheets_are_double_sided() {
    let mut supports = 0;
    for name in ["horizontal-drum", "vertical-column"] {
        let example = example(name);
        let gltf = Gltf::from_slice(&example.glb).unwrap();
        for vessel in gltf
            .default_scene()
            .unwrap()
            .nodes()
            .flat_map(|n| n.children())
        {
            for part in vessel.children() {
                let kind = extras(&part)["kind"].as_str().unwrap().to_string();
                let support = matches!(kind.as_str(), "skirt" | "saddle" | "legs" | "lugs");
                for patch in part.children() {
                    for primitive in patch.mesh().unwrap().primitives() {
                        let material = primitive.material();
                        assert_eq!(
                            material.double_sided(),
                            support,
                            "{name}/{}/{}: {kind} material {:?}",
                            part.name().unwrap(),
                            patch.name().unwrap(),
                            material.name()
                        );
                        supports += usize::from(support);
                    }
                }
            }
        }
    }
    assert!(supports > 0, "no support in the examples");
}

#[test]
fn glb_container_is_well_formed() {
    for example in examples() {
        let glb = &example.glb;
        assert_eq!(&glb[0..4], b"glTF");
        assert_eq!(u32::from_le_bytes(glb[4..8].try_into().unwrap()), 2);
        assert_eq!(
            u32::from_le_bytes(glb[8..12].try_into().unwrap()) as usize,
            glb.len()
        );
        let json_len = u32::from_le_bytes(glb[12..16].try_into().unwrap()) as usize;
        assert_eq!(&glb[16..20], b"JSON");
        assert_eq!(json_len % 4, 0);
        let bin = 20 + json_len;
        assert_eq!(&glb[bin + 4..bin + 8], b"BIN\0");
        let json: Value = serde_json::from_slice(&glb[20..bin]).unwrap();
        let generator = json["asset"]["generator"].as_str().unwrap();
        assert_eq!(
            generator,
            format!("vesselcad {}", env!("CARGO_PKG_VERSION"))
        );
    }
}

#[test]
fn two_builds_give_identical_bytes() {
    for example in examples() {
        assert!(
            glb_of(&example.design) == example.glb,
            "{}: bytes differ",
            example.name
        );
    }
}

/// Runs the Khronos validator on an example's GLB; `None` when it is not installed
/// (after failing under CI).
fn validate(example: &Example) -> Option<Value> {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let module = root.join("tests/support/node_modules/gltf-validator/package.json");
    let node = Command::new("node").arg("--version").output();
    if !module.is_file() || !node.is_ok_and(|o| o.status.success()) {
        if std::env::var_os("CI").is_some() {
            panic!("{MISSING_VALIDATOR}");
        }
        eprintln!("{MISSING_VALIDATOR}");
        return None;
    }
    let file = std::env::temp_dir().join(format!(
        "vesselcad-export-glb-{}-{}.glb",
        example.name,
        std::process::id()
    ));
    std::fs::write(&file, &example.glb).unwrap();
    let output = Command::new("node")
        .arg(root.join("tests/support/validate-gltf.js"))
        .arg(&file)
        .output()
        .unwrap();
    std::fs::remove_file(&file).unwrap();
    let stdout = String::from_utf8_lossy(&output.stdout);
    let report: Value = serde_json::from_str(&stdout).unwrap_or_else(|e| {
        panic!(
            "{}: validator output is not JSON ({e}): {stdout}\n{}",
            example.name,
            String::from_utf8_lossy(&output.stderr)
        )
    });
    Some(report)
}

#[test]
fn khronos_validator_finds_no_errors() {
    for example in examples() {
        let Some(report) = validate(example) else {
            return;
        };
        eprintln!(
            "{} ({} bytes): {} errors, {} warnings, {} infos, {} hints; messages: {}",
            example.name,
            example.glb.len(),
            report["numErrors"],
            report["numWarnings"],
            report["numInfos"],
            report["numHints"],
            report["messages"]
        );
        assert_eq!(report["numErrors"], 0, "{}: {report:#}", example.name);
    }
}
