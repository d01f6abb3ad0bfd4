//! The FE shell mesh of the example column and drum at the default size,
//! beside Gmsh meshing the same vessel's STEP export (its surfaces;
//! Frontal-Delaunay recombined into quads by Blossom, second order, one thread) at the same mean element
//! size, in the same run: elements, elements per second, minimum scaled
//! Jacobian and the share of elements under 0.3. Ours is timed as the best of
//! five meshings; Gmsh's mesh time excludes its STEP import.
//!
//! `cargo run --profile test --example fem_gmsh` (Gmsh: `target/occt-venv/bin/pip
//! install gmsh`; set `GMSH_PYTHON` to another interpreter that has it).

use std::process::Command;
use std::time::Instant;

use vesselcad::design::{load, resolve};
use vesselcad::exchange::{ExchangeOptions, StepBlocks, export_step};
use vesselcad::fem::quality::quality;
use vesselcad::fem::{FemOptions, build_envelope};

fn main() {
    let python =
        std::env::var("GMSH_PYTHON").unwrap_or_else(|_| "target/occt-venv/bin/python".into());
    let dir = tempfile::tempdir().expect("temporary directory");
    println!(
        "| Vessel | Mesher | Elements | Time | Elements/s | Min scaled Jacobian | Under 0.3 |"
    );
    println!("|---|---|---|---|---|---|---|");
    for (file, tag) in [
        ("vertical-column.json", "C-201"),
        ("horizontal-drum.json", "V-101"),
    ] {
        let path = format!("examples/designs/{file}");
        let design = load(&path).unwrap_or_else(|e| panic!("{path}: {e}"));
        let resolved = resolve(&design).unwrap_or_else(|e| panic!("{path}: {e:?}"));
        let k = design
            .vessels
            .iter()
            .position(|v| v.tag == tag)
            .expect("vessel");
        let options = FemOptions::default();
        let mut best = f64::INFINITY;
        let mut mesh = None;
        for _ in 0..5 {
            let t = Instant::now();
            let m = build_envelope(&design.vessels[k], &resolved[k], &options)
                .unwrap_or_else(|e| panic!("{tag}: {e}"));
            best = best.min(t.elapsed().as_secs_f64());
            mesh = Some(m);
        }
        let mesh = mesh.expect("meshed");
        let q = quality(&mesh);
        let area: f64 = mesh
            .elements
            .iter()
            .map(|e| {
                let c: Vec<_> = e.nodes[..e.kind.corners()]
                    .iter()
                    .map(|&n| mesh.nodes[n])
                    .collect();
                let mut a = 0.0;
                for i in 1..c.len() - 1 {
                    a += 0.5 * (c[i] - c[0]).cross(c[i + 1] - c[0]).length();
                }
                a
            })
            .sum();
        let size = (area / q.elements as f64).sqrt();
        println!(
            "| {tag} | vesselcad | {} ({} quads) | {:.1} ms | {:.0} k | {:.3} | {} |",
            q.elements,
            q.quads,
            best * 1e3,
            q.elements as f64 / best / 1e3,
            q.min_scaled_jacobian,
            q.elements - q.jacobian_ok
        );
        let step = export_step(
            &design,
            &[tag.to_string()],
            &ExchangeOptions::default(),
            file,
            &mut StepBlocks::default(),
        )
        .unwrap_or_else(|e| panic!("{tag}: STEP: {e}"));
        let step_path = dir.path().join(format!("{tag}.step"));
        std::fs::write(&step_path, step).expect("write STEP");
        let out = Command::new(&python)
            .arg("examples/fem_gmsh.py")
            .arg(&step_path)
            .arg(format!("{size}"))
            .output();
        match out {
            Ok(o) if o.status.success() => {
                let text = String::from_utf8_lossy(&o.stdout);
                let v: serde_json::Value = serde_json::from_str(text.trim())
                    .unwrap_or_else(|e| panic!("gmsh output {text}: {e}"));
                let elements = v["elements"].as_u64().unwrap_or(0);
                let secs = v["mesh_s"].as_f64().unwrap_or(f64::NAN);
                println!(
                    "| {tag} | Gmsh {:.0} mm ({} faces) | {elements} ({} quads) | {:.1} ms (+ {:.0} ms import) | {:.0} k | {:.3} | {} |",
                    size,
                    v["faces"],
                    v["quads"],
                    secs * 1e3,
                    v["import_s"].as_f64().unwrap_or(f64::NAN) * 1e3,
                    elements as f64 / secs / 1e3,
                    v["min_sj"].as_f64().unwrap_or(f64::NAN),
                    v["sj_below_0_3"]
                );
            }
            Ok(o) => println!(
                "| {tag} | Gmsh failed: {} | | | | | |",
                String::from_utf8_lossy(&o.stderr)
                    .lines()
                    .last()
                    .unwrap_or("")
            ),
            Err(e) => println!("| {tag} | Gmsh not run ({python}: {e}) | | | | | |"),
        }
    }
}
