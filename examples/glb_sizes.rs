//! The GLB writer's figures for each option: file size, glTF meshes, patch
//! nodes (draw calls) and write speed (bytes of output per second, before
//! compression for the compressed variant's reference).
//!
//! `cargo run --profile test --example glb_sizes -- [DESIGN.json | --plant N] [TOLERANCE [SHARE]]`
//! (the example plant's horizontal drum by default, at 1 mm; `--plant N` a
//! generated plant of N vessels). Each variant is written a few times and the
//! fastest run counts. Meshes are made to the tolerance less the quantization
//! budget, as `vesselcad build --quantize` makes them (SHARE: that share of
//! the tolerance as the quantization budget instead, to compare splits).
//! `GLB_SIZES_ROWS=part,vessel` runs only the rows whose names contain one of
//! those words. The last rows are the
//! compact file (reuse + quantization + meshopt) of the scene merged per part,
//! vessel and plant (`--granularity`; merging is not timed), the part merge
//! with instancing, and the compact file without normals (`--normals flat`) per
//! patch, part and vessel. An instanced node is one draw call; vertices written
//! are the `POSITION` counts of the glTF meshes.

use std::time::Instant;

use vesselcad::design::load;
use vesselcad::export::{
    Compression, GlbOptions, Granularity, merge_scene, quantization_budget, write_glb_with,
};
use vesselcad::mesh::TessellationOptions;
use vesselcad::model::Model;
use vesselcad::plant::generate_plant;

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let (design, rest) = match args.first().map(String::as_str) {
        Some("--plant") => {
            let n: usize = args[1].parse().expect("a vessel count");
            (generate_plant(n, 1).expect("a plant"), &args[2..])
        }
        Some(path) => (
            load(std::path::Path::new(path)).expect("a design"),
            &args[1..],
        ),
        None => {
            let path = concat!(
                env!("CARGO_MANIFEST_DIR"),
                "/examples/designs/horizontal-drum.json"
            );
            (
                load(std::path::Path::new(path)).expect("the example"),
                &args[..],
            )
        }
    };
    let tolerance: f64 = rest
        .first()
        .map_or(1.0, |t| t.parse().expect("a tolerance"));
    // An optional share of the tolerance for quantization, to compare splits.
    let budget = rest.get(1).map_or(quantization_budget(tolerance), |s| {
        tolerance * s.parse::<f64>().expect("a share")
    });
    let meshing = tolerance - budget;
    let model = Model::from_design(&design, TessellationOptions::chord(meshing)).expect("builds");
    let scene = model.scene();
    let patches: usize = scene
        .vessels
        .iter()
        .flat_map(|v| &v.nodes)
        .map(|n| {
            n.patches
                .iter()
                .filter(|p| p.mesh.triangle_count() > 0)
                .count()
        })
        .sum();
    println!(
        "{} vessel(s), {patches} patches, meshed at {meshing} mm for {tolerance} mm",
        scene.vessels.len()
    );
    println!(
        "| variant | bytes | JSON bytes | glTF meshes | draw calls | vertices written | write MB/s | views |"
    );
    println!("|---|---|---|---|---|---|---|---|");
    let q = Some(budget);
    let compact = GlbOptions {
        quantize: q,
        ..GlbOptions::compact(tolerance)
    };
    let variants = [
        (
            "f32, one mesh per patch",
            false,
            None,
            Compression::None,
            false,
        ),
        ("f32, reuse (default)", true, None, Compression::None, false),
        ("reuse + instancing", true, None, Compression::None, true),
        ("reuse + quantization", true, q, Compression::None, false),
        ("reuse + meshopt", true, None, Compression::Meshopt, false),
        (
            "reuse + quantization + meshopt",
            true,
            q,
            Compression::Meshopt,
            false,
        ),
        ("compact + instancing", true, q, Compression::Meshopt, true),
    ];
    let merged = [
        ("compact, --granularity part", Granularity::Part),
        ("compact, --granularity vessel", Granularity::Vessel),
        ("compact, --granularity plant", Granularity::Plant),
    ]
    .map(|(name, g)| (name, merge_scene(&scene, g)));
    let rows = variants
        .iter()
        .map(|&(name, reuse, quantize, compress, instancing)| {
            let options = GlbOptions {
                reuse,
                quantize,
                compress,
                instancing,
                ..GlbOptions::default()
            };
            (name, &scene, options)
        })
        .chain(merged.iter().map(|(name, s)| (*name, s, compact)))
        .chain([
            (
                "compact + instancing, --granularity part",
                &merged[0].1,
                compact.instanced(),
            ),
            ("compact, --normals flat", &scene, compact.flat()),
            (
                "compact, --normals flat, --granularity part",
                &merged[0].1,
                compact.flat(),
            ),
            (
                "compact, --normals flat, --granularity vessel",
                &merged[1].1,
                compact.flat(),
            ),
        ]);
    // `GLB_SIZES_ROWS=a,b`: only the rows whose names contain one of these.
    let only: Vec<String> = std::env::var("GLB_SIZES_ROWS")
        .map(|v| v.split(',').map(str::to_string).collect())
        .unwrap_or_default();
    let rows = rows
        .filter(|(name, _, _)| only.is_empty() || only.iter().any(|o| name.contains(o.as_str())));
    for (name, scene, options) in rows {
        let mut best = f64::INFINITY;
        let mut bytes = Vec::new();
        for _ in 0..3 {
            let start = Instant::now();
            bytes = write_glb_with(scene, &options).expect("writes");
            best = best.min(start.elapsed().as_secs_f64());
        }
        let json_len = u32::from_le_bytes(bytes[12..16].try_into().unwrap()) as usize;
        let json: serde_json::Value = serde_json::from_slice(&bytes[20..20 + json_len]).unwrap();
        let meshes = json["meshes"].as_array().map_or(0, Vec::len);
        let draws = json["nodes"]
            .as_array()
            .map_or(0, |n| n.iter().filter(|n| n["mesh"].is_u64()).count());
        let vertices: u64 = json["meshes"].as_array().map_or(0, |m| {
            m.iter()
                .flat_map(|m| m["primitives"].as_array().into_iter().flatten())
                .filter_map(|p| p["attributes"]["POSITION"].as_u64())
                .filter_map(|a| json["accessors"][a as usize]["count"].as_u64())
                .sum()
        });
        // Each view's bytes in the file (encoded, when compressed), by what
        // it holds: `P` positions, `N` normals, `I` indices, `X` instances.
        let views: Vec<String> = json["bufferViews"]
            .as_array()
            .into_iter()
            .flatten()
            .map(|v| {
                let what = match (v["target"].as_u64(), v["byteStride"].as_u64()) {
                    (Some(34963), _) => "I",
                    (_, Some(8)) => "P",
                    (_, Some(4)) => "N",
                    (Some(34962), Some(12)) => "P/N",
                    _ => "X",
                };
                let length = v["extensions"]["EXT_meshopt_compression"]["byteLength"]
                    .as_u64()
                    .or(v["byteLength"].as_u64())
                    .unwrap_or(0);
                format!("{what} {length}")
            })
            .collect();
        println!(
            "| {name} | {} | {json_len} | {meshes} | {draws} | {vertices} | {:.0} | {} |",
            bytes.len(),
            bytes.len() as f64 / best / 1e6,
            views.join(", ")
        );
    }
}
