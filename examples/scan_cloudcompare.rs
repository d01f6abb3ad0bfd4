//! The distance step side by side with CloudCompare's cloud-to-mesh distance
//! (`C2M_DIST`): the same simulated scan of the test drum
//! (`tests/common/scan.rs`, noise 1 mm, plant frame) against the drum's design
//! mesh as `vesselcad` exports it (a GLB at the given chordal tolerance, read
//! back and written as a PLY mesh for CloudCompare, which reads no glTF),
//! beside vesselcad's own deviation step (point inversion on the exact patches:
//! `Envelope::project_all`, the scan moved into the vessel frame first) on one
//! and two threads. Prints the times and how far the two distances agree
//! (they should within the mesh's tolerance where both measure to the same
//! surface; the mesh has the nozzles' openings cut, the exact patches do not).
//!
//! Needs Debian's `cloudcompare` (the `CloudCompare` binary) and `/usr/bin/time`;
//! runs it headless (`QT_QPA_PLATFORM=offscreen`, `-SILENT`).
//!
//! `cargo run --profile test --example scan_cloudcompare -- [density] [tolerance] [runs]`
//! (defaults 4000 points/m², 0.1 mm, 2 runs of each; the best run counts).
//! Files go to `target/scan-cloudcompare/`.
use std::io::Write;
use std::path::{Path, PathBuf};
use std::process::Command;

use glam::{DMat4, DVec3};
use vesselcad::design::parse;
use vesselcad::export::{build_scene, write_glb};
use vesselcad::mesh::TessellationOptions;
use vesselcad::scan::{Envelope, Targets};

#[path = "../tests/common/scan.rs"]
#[expect(dead_code, reason = "the example uses the drum only")]
mod designs;
#[path = "support/scan_run.rs"]
mod run;

/// The GLB's triangles in the plant frame, mm: every node's mesh under its
/// nodes' transforms, glTF's Y-up metres turned back into Z-up millimetres.
fn triangles(glb: &[u8]) -> (Vec<DVec3>, Vec<[u32; 3]>) {
    let gltf = gltf::Gltf::from_slice(glb).expect("a GLB");
    let blob = gltf.blob.as_deref().expect("a BIN chunk");
    let mut positions = Vec::new();
    let mut faces = Vec::new();
    let mut stack: Vec<(gltf::Node, DMat4)> = gltf
        .default_scene()
        .expect("a scene")
        .nodes()
        .map(|n| (n, DMat4::IDENTITY))
        .collect();
    while let Some((node, parent)) = stack.pop() {
        let local = node.transform().matrix().map(|c| c.map(f64::from));
        let world = parent * DMat4::from_cols_array_2d(&local);
        if let Some(mesh) = node.mesh() {
            for primitive in mesh.primitives() {
                let reader = primitive.reader(|_| Some(blob));
                let base = positions.len() as u32;
                positions.extend(reader.read_positions().expect("positions").map(|p| {
                    let g = world.transform_point3(DVec3::from(p.map(f64::from)));
                    DVec3::new(g.x, -g.z, g.y) * 1e3
                }));
                let indices: Vec<u32> =
                    reader.read_indices().expect("indices").into_u32().collect();
                faces.extend(
                    indices
                        .chunks_exact(3)
                        .map(|t| [base + t[0], base + t[1], base + t[2]]),
                );
            }
        }
        stack.extend(node.children().map(|c| (c, world)));
    }
    (positions, faces)
}

/// A binary little-endian PLY of `points` and, if any, triangle `faces`.
fn write_ply(path: &Path, points: &[DVec3], faces: &[[u32; 3]]) {
    let mut out = Vec::with_capacity(12 * points.len() + 13 * faces.len() + 256);
    write!(
        out,
        "ply\nformat binary_little_endian 1.0\nelement vertex {}\n\
         property float x\nproperty float y\nproperty float z\n",
        points.len()
    )
    .expect("header");
    if !faces.is_empty() {
        write!(
            out,
            "element face {}\nproperty list uchar int vertex_indices\n",
            faces.len()
        )
        .expect("header");
    }
    out.extend_from_slice(b"end_header\n");
    for p in points {
        for c in p.as_vec3().to_array() {
            out.extend_from_slice(&c.to_le_bytes());
        }
    }
    for f in faces {
        out.push(3);
        for i in f {
            out.extend_from_slice(&(*i as i32).to_le_bytes());
        }
    }
    std::fs::write(path, out).expect("writes the PLY");
}

/// One CloudCompare run: (its C2M times from its log — the octree's
/// approximate pass and the distances — process wall, process CPU).
struct CloudCompareRun {
    approx: f64,
    distances: f64,
    wall: f64,
    cpu: f64,
}

fn cloudcompare(dir: &Path, threads: usize, distances: bool, out: &Path) -> CloudCompareRun {
    let time = dir.join("time.txt");
    let mut command = Command::new("/usr/bin/time");
    command
        .env("QT_QPA_PLATFORM", "offscreen")
        .args(["-f", "%e %U %S", "-o"])
        .arg(&time)
        .args([
            "CloudCompare",
            "-SILENT",
            "-NO_TIMESTAMP",
            "-AUTO_SAVE",
            "OFF",
        ])
        .args(["-O", "cloud.ply", "-O", "mesh.ply"])
        .current_dir(dir);
    if distances {
        command
            .args(["-C2M_DIST", "-MAX_TCOUNT"])
            .arg(threads.to_string())
            .args(["-C_EXPORT_FMT", "ASC", "-SAVE_CLOUDS", "FILE"])
            .arg(out);
    }
    let output = command.output().expect("runs CloudCompare");
    let log = String::from_utf8_lossy(&output.stdout);
    assert!(
        output.status.success(),
        "CloudCompare failed ({}): {log}{}",
        output.status,
        String::from_utf8_lossy(&output.stderr)
    );
    let seconds = |tag: &str| {
        log.lines()
            .find_map(|l| l.split_once(tag))
            .and_then(|(_, rest)| rest.trim().trim_end_matches(" s.").parse::<f64>().ok())
            .unwrap_or(f64::NAN)
    };
    let times: Vec<f64> = std::fs::read_to_string(&time)
        .expect("/usr/bin/time's output")
        .split_whitespace()
        .filter_map(|s| s.parse().ok())
        .collect();
    if distances {
        assert!(!seconds("[ComputeDistances] Time:").is_nan(), "{log}");
    }
    CloudCompareRun {
        approx: seconds("[computeApproxDistances] Time:"),
        distances: seconds("[ComputeDistances] Time:"),
        wall: times[0],
        cpu: times[1] + times[2],
    }
}

fn percentile(sorted: &[f64], q: f64) -> f64 {
    sorted[((sorted.len() - 1) as f64 * q).round() as usize]
}

fn main() {
    let mut args = std::env::args().skip(1);
    let density: f64 = args.next().and_then(|s| s.parse().ok()).unwrap_or(4000.0);
    let tolerance: f64 = args.next().and_then(|s| s.parse().ok()).unwrap_or(0.1);
    let runs: usize = args.next().and_then(|s| s.parse().ok()).unwrap_or(2);
    let dir = PathBuf::from(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/target/scan-cloudcompare"
    ));
    std::fs::create_dir_all(&dir).expect("the output directory");

    let design = parse(designs::DRUM).expect("the test drum parses");
    let env = Envelope::of_design(&design, "V-1").expect("the test drum builds");
    let scan = run::points(&env, density);
    let glb =
        write_glb(&build_scene(&design, &TessellationOptions::chord(tolerance)).expect("meshes"))
            .expect("writes the GLB");
    std::fs::write(dir.join("design.glb"), &glb).expect("writes the GLB");
    let (vertices, faces) = triangles(&glb);
    write_ply(&dir.join("mesh.ply"), &vertices, &faces);
    write_ply(&dir.join("cloud.ply"), &scan, &[]);
    println!(
        "{} points; design mesh at {tolerance} mm: {} triangles, {} vertices ({} GLB bytes)",
        scan.len(),
        faces.len(),
        vertices.len(),
        glb.len()
    );

    // vesselcad: into the vessel frame, then point inversion on the exact patches.
    let margin = env.default_margin();
    let to_vessel = env.frame.inverse();
    let ours = |threads: usize| {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .expect("a pool");
        let mut best = (f64::INFINITY, f64::INFINITY, Vec::new());
        for _ in 0..runs {
            let (feet, wall, cpu) = run::timed(|| {
                pool.install(|| {
                    use rayon::prelude::*;
                    let local: Vec<DVec3> = scan
                        .par_iter()
                        .map(|&p| to_vessel.transform_point3(p))
                        .collect();
                    env.project_all(&local, Targets::WithNozzles, margin)
                })
            });
            if wall < best.0 {
                best = (wall, cpu, feet);
            }
        }
        best
    };
    println!("| step | threads | wall s | CPU s | points per CPU second |\n|---|---|---|---|---|");
    let mut feet = Vec::new();
    for threads in [1, 2] {
        let (wall, cpu, f) = ours(threads);
        println!(
            "| vesselcad deviation (exact patches) | {threads} | {wall:.3} | {cpu:.2} | {:.2} M |",
            scan.len() as f64 / cpu.max(0.01) / 1e6
        );
        feet = f;
    }
    let out = dir.join("c2m.asc");
    let load = (0..runs)
        .map(|_| cloudcompare(&dir, 1, false, &out))
        .min_by(|a, b| a.wall.total_cmp(&b.wall))
        .expect("a run");
    println!(
        "| CloudCompare, load both files only | — | {:.2} | {:.2} | — |",
        load.wall, load.cpu
    );
    for threads in [1, 2] {
        let cc = (0..runs)
            .map(|_| cloudcompare(&dir, threads, true, &out))
            .min_by(|a, b| a.wall.total_cmp(&b.wall))
            .expect("a run");
        println!(
            "| CloudCompare C2M_DIST: octree pass {:.2} s + distances {:.2} s (its log); process | {threads} | {:.2} | {:.2} | {:.2} M (C2M log time) |",
            cc.approx,
            cc.distances,
            cc.wall,
            cc.cpu,
            scan.len() as f64 / (cc.approx + cc.distances).max(0.01) / 1e6
        );
    }

    // Agreement, point by point (CloudCompare keeps the cloud's order).
    let text = std::fs::read_to_string(&out).expect("CloudCompare's distances");
    let theirs: Vec<f64> = text
        .lines()
        .filter_map(|l| l.split_whitespace().nth(3)?.parse().ok())
        .collect();
    assert_eq!(theirs.len(), scan.len(), "one distance per point");
    let mut differences: Vec<f64> = feet
        .iter()
        .zip(&theirs)
        .filter_map(|(f, d)| {
            let f = f.as_ref().filter(|f| f.inside)?;
            Some((f.deviation - d).abs())
        })
        .collect();
    differences.sort_by(f64::total_cmp);
    let within = differences
        .iter()
        .filter(|&&d| d <= tolerance + 1e-3)
        .count();
    println!(
        "agreement on {} points with an inside foot: |ours − CloudCompare| median {:.4} mm, \
         99 % {:.4} mm, max {:.1} mm; {:.3} % within the mesh's {tolerance} mm",
        differences.len(),
        percentile(&differences, 0.5),
        percentile(&differences, 0.99),
        differences.last().copied().unwrap_or(0.0),
        100.0 * within as f64 / differences.len().max(1) as f64
    );
}
