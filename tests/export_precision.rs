//! The chordal tolerance holds in the file: a 50 m storage tank at 0.1 mm,
//! written as GLB (`f32` metres) and read back, every triangle of its course,
//! bottom and roof within the tolerance of the exact surface at every point
//! (45 barycentric samples per triangle, then a climb to the local maximum).
//! The `f32` rounding of 25 m coordinates (about 0.001 mm each) used to take
//! the triangles that meet the tolerance in `f64` past it.

mod common;

use common::triangle::largest_distance;
use glam::DVec3;
use gltf::Gltf;
use vesselcad::design::{parse, resolve};
use vesselcad::export::{build_scene, patch_name, write_glb};
use vesselcad::mesh::TessellationOptions;

const TOLERANCE: f64 = 0.1;

const TANK: &str = r#"{
  "format": "vesselcad/1",
  "units": "mm",
  "vessels": [
    {
      "tag": "TK-50",
      "kind": "tank",
      "placement": { "position": [0, 0, 0], "rotation": 0 },
      "design": { "pressure": 2, "temperature": 40, "corrosion_allowance": 1.5, "material": "A283-C" },
      "parts": [
        { "head": { "id": "BTM", "shape": "flat", "thickness": 12 } },
        { "shell": { "id": "S1", "od": 50000, "length": 2400, "thickness": 30 } },
        { "head": { "id": "ROOF", "shape": "conical", "half_angle": 80, "thickness": 8 } }
      ],
      "nozzles": []
    }
  ]
}"#;

#[test]
fn a_50_m_tank_holds_the_tolerance_in_f32() {
    let design = parse(TANK).expect("the tank design");
    let resolved = resolve(&design).expect("resolves");
    let glb =
        write_glb(&build_scene(&design, &TessellationOptions::chord(TOLERANCE)).expect("builds"))
            .expect("writes");
    let gltf = Gltf::from_slice(&glb).expect("a GLB");
    let blob = gltf.blob.as_deref().expect("a BIN chunk");
    let vessel = gltf
        .default_scene()
        .unwrap()
        .nodes()
        .flat_map(|plant| plant.children())
        .next()
        .expect("the tank");
    let mut checked = 0;
    for (node, part) in vessel.children().zip(&resolved[0].parts) {
        assert_eq!(node.name(), Some(part.id.as_str()));
        let patches = part.geometry.patches().expect("patches");
        for patch_node in node.children() {
            let patch = patches
                .iter()
                .find(|p| Some(patch_name(p).as_str()) == patch_node.name())
                .expect("the node's patch");
            let mesh = patch_node.mesh().expect("a mesh");
            for primitive in mesh.primitives() {
                let reader = primitive.reader(|_| Some(blob));
                // The file's own numbers: f32 metres, widened exactly.
                let positions: Vec<DVec3> = reader
                    .read_positions()
                    .unwrap()
                    .map(|p| DVec3::from(p.map(f64::from)) * 1e3)
                    .collect();
                let indices: Vec<u32> = reader.read_indices().unwrap().into_u32().collect();
                let (mut worst, mut over) = (0.0f64, 0);
                for t in indices.chunks_exact(3) {
                    let p = [t[0], t[1], t[2]].map(|i| positions[i as usize]);
                    let d = largest_distance(&patch.analytic, p);
                    worst = worst.max(d);
                    over += usize::from(d > TOLERANCE);
                }
                println!(
                    "{}/{}: {} triangles, worst {:.5} mm, {over} over {TOLERANCE} mm",
                    part.id,
                    patch.name,
                    indices.len() / 3,
                    worst
                );
                assert!(
                    worst <= TOLERANCE,
                    "{}/{}: {worst} mm > {TOLERANCE} mm ({over} triangles)",
                    part.id,
                    patch.name
                );
                checked += indices.len() / 3;
            }
        }
    }
    assert!(checked > 1000, "{checked} triangles");
}
