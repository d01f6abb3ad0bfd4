//! Level-of-detail report: builds the example drum at chordal tolerances 1, 0.1 and
//! 0.01 mm and prints, per tolerance, the total triangle count, the build time, the
//! measured maximum deviation from the exact surfaces over a sample of triangles,
//! and the distribution of minimum triangle angles (the mesher's quality index).
//!
//! ```sh
//! cargo run --release --example lod_report [-- path/to/design.json]
//! ```
//!
//! The deviation of a triangle is the largest distance to its exact patch of its
//! centroid and edge midpoints, each inverted onto the surface with
//! `NurbsSurface::closest_point`; at most [`SAMPLE`] triangles are measured per
//! tolerance, every k-th triangle of every patch (deterministic). Angles are 3D
//! interior angles of every output triangle.

use std::process::ExitCode;
use std::time::Instant;

use glam::DVec3;
use rayon::prelude::*;
use vesselcad::components::{NozzleSpec, PadOf, PartSpec, PatchMesh, PatchOf, PatchSurface};
use vesselcad::design::load;
use vesselcad::mesh::{Mesh, TessellationOptions};
use vesselcad::model::Model;
use vesselcad::nurbs::NurbsSurface;

/// The tolerances reported, mm.
const TOLERANCES: [f64; 3] = [1.0, 0.1, 0.01];
/// Most triangles measured for deviation per tolerance.
const SAMPLE: usize = 40_000;
/// Upper bounds of the minimum-angle bins, degrees (the last bin is open).
const ANGLE_BINS: [f64; 3] = [10.0, 20.0, 30.0];
/// Patches listed with the most triangles under the first angle bin.
const SLIVER_PATCHES: usize = 4;

/// One meshed patch: its owner's id, its name, the exact surface and the mesh.
struct Meshed {
    label: String,
    surface: NurbsSurface,
    mesh: Mesh,
}

/// The meshed patches of the model.
fn meshed(model: &Model) -> Vec<Meshed> {
    let world = model.world();
    let Some(mut query) =
        world.try_query::<(&PatchSurface, &PatchMesh, Option<&PatchOf>, Option<&PadOf>)>()
    else {
        return Vec::new();
    };
    let owner = |e| {
        world
            .get::<PartSpec>(e)
            .map(|p| p.0.id().to_string())
            .or_else(|| world.get::<NozzleSpec>(e).map(|n| n.0.mark.clone()))
            .unwrap_or_else(|| "?".into())
    };
    let mut out: Vec<Meshed> = query
        .iter(world)
        .map(|(surface, mesh, of, pad)| {
            let label = match (of, pad) {
                (Some(of), _) => format!("{}/{}", owner(of.0), surface.0.name),
                (None, Some(pad)) => format!("{}/pad", owner(pad.0)),
                (None, None) => surface.0.name.to_string(),
            };
            let label = if surface.0.index > 0 {
                format!("{label} {}", surface.0.index)
            } else {
                label
            };
            Meshed {
                label,
                surface: surface.0.surface.clone(),
                mesh: mesh.0.unpack(),
            }
        })
        .collect();
    out.sort_by(|a, b| a.label.cmp(&b.label));
    out
}

/// The corners of triangle `t` of a mesh.
fn corners(mesh: &Mesh, t: usize) -> [DVec3; 3] {
    [0, 1, 2].map(|k| mesh.positions[mesh.indices[3 * t + k] as usize])
}

/// Largest distance from the exact surface of a triangle's centroid and edge
/// midpoints (point inversion), mm.
fn deviation(surface: &NurbsSurface, p: [DVec3; 3]) -> f64 {
    [
        (p[0] + p[1] + p[2]) / 3.0,
        0.5 * (p[0] + p[1]),
        0.5 * (p[1] + p[2]),
        0.5 * (p[2] + p[0]),
    ]
    .iter()
    .map(|&q| {
        surface
            .closest_point(q)
            .map_or(f64::INFINITY, |c| c.distance)
    })
    .fold(0.0, f64::max)
}

/// Smallest interior angle of a triangle, degrees.
fn min_angle(p: [DVec3; 3]) -> f64 {
    (0..3)
        .map(|i| (p[(i + 1) % 3] - p[i]).angle_between(p[(i + 2) % 3] - p[i]))
        .fold(f64::INFINITY, f64::min)
        .to_degrees()
}

/// The figures of one tolerance.
struct Report {
    tolerance: f64,
    triangles: usize,
    build_ms: f64,
    measured: usize,
    worst: f64,
    worst_patch: String,
    over: usize,
    bins: [usize; 4],
    smallest_angle: f64,
    /// Patches with the most triangles under 10°: (label, count, patch triangles).
    slivers: Vec<(String, usize, usize)>,
    failures: usize,
}

fn report(design: &vesselcad::design::Design, tolerance: f64) -> Result<Report, String> {
    let start = Instant::now();
    let model = Model::from_design(design, TessellationOptions::chord(tolerance))
        .map_err(|e| e.to_string())?;
    let build_ms = start.elapsed().as_secs_f64() * 1e3;
    let failures = model.errors().0.len();
    for failure in &model.errors().0 {
        eprintln!("  model error at {tolerance} mm, {failure}");
    }
    let patches = meshed(&model);
    let triangles: usize = patches.iter().map(|p| p.mesh.triangle_count()).sum();
    let stride = triangles.div_ceil(SAMPLE).max(1);
    let jobs: Vec<(usize, usize)> = patches
        .iter()
        .enumerate()
        .flat_map(|(k, p)| {
            (0..p.mesh.triangle_count())
                .step_by(stride)
                .map(move |t| (k, t))
        })
        .collect();
    let deviations: Vec<(usize, f64)> = jobs
        .par_iter()
        .map(|&(k, t)| {
            (
                k,
                deviation(&patches[k].surface, corners(&patches[k].mesh, t)),
            )
        })
        .collect();
    let (worst_k, worst) = deviations
        .iter()
        .copied()
        .fold((0, 0.0f64), |a, b| if b.1 > a.1 { b } else { a });
    let over = deviations.iter().filter(|d| d.1 > tolerance).count();
    let mut bins = [0usize; 4];
    let mut smallest_angle = f64::INFINITY;
    let mut slivers = Vec::new();
    for p in &patches {
        let mut under = 0;
        for t in 0..p.mesh.triangle_count() {
            let a = min_angle(corners(&p.mesh, t));
            smallest_angle = smallest_angle.min(a);
            let bin = ANGLE_BINS.iter().take_while(|&&b| a >= b).count();
            bins[bin] += 1;
            under += usize::from(bin == 0);
        }
        slivers.push((p.label.clone(), under, p.mesh.triangle_count()));
    }
    slivers.sort_by_key(|s| std::cmp::Reverse(s.1));
    slivers.truncate(SLIVER_PATCHES);
    Ok(Report {
        tolerance,
        triangles,
        build_ms,
        measured: jobs.len(),
        worst,
        worst_patch: patches
            .get(worst_k)
            .map_or(String::new(), |p| p.label.clone()),
        over,
        bins,
        smallest_angle,
        slivers,
        failures,
    })
}

fn main() -> ExitCode {
    let path = std::env::args().nth(1).unwrap_or_else(|| {
        concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/examples/designs/horizontal-drum.json"
        )
        .into()
    });
    let design = match load(&path) {
        Ok(d) => d,
        Err(e) => {
            eprintln!("error: {path}: {e}");
            return ExitCode::from(2);
        }
    };
    println!("level of detail: {path}");
    println!(
        "{:>9} {:>10} {:>10} {:>9} {:>10} {:>9} {:<24} {:>8} {:>8} {:>8} {:>8} {:>8} {:>8}",
        "tol mm",
        "triangles",
        "build ms",
        "measured",
        "max dev",
        "dev/tol",
        "worst patch",
        "over",
        "<10°",
        "10-20°",
        "20-30°",
        ">=30°",
        "min °"
    );
    let mut failed = false;
    for tolerance in TOLERANCES {
        match report(&design, tolerance) {
            Ok(r) => {
                let share = |n: usize| 100.0 * n as f64 / r.triangles.max(1) as f64;
                println!(
                    "{:>9} {:>10} {:>10.1} {:>9} {:>10.5} {:>9.3} {:<24} {:>8} {:>7.2}% {:>7.2}% {:>7.2}% {:>7.2}% {:>8.4}",
                    r.tolerance,
                    r.triangles,
                    r.build_ms,
                    r.measured,
                    r.worst,
                    r.worst / r.tolerance,
                    r.worst_patch,
                    r.over,
                    share(r.bins[0]),
                    share(r.bins[1]),
                    share(r.bins[2]),
                    share(r.bins[3]),
                    r.smallest_angle
                );
                let slivers: Vec<String> = r
                    .slivers
                    .iter()
                    .filter(|s| s.1 > 0)
                    .map(|(label, n, of)| format!("{label} {n}/{of}"))
                    .collect();
                println!("{:>9} most triangles < 10°: {}", "", slivers.join(", "));
                if r.failures > 0 {
                    println!("{:>9} {} model error(s), see stderr", "", r.failures);
                    failed = true;
                }
            }
            Err(e) => {
                eprintln!("error at {tolerance} mm: {e}");
                failed = true;
            }
        }
    }
    println!(
        "measured: triangles sampled (every k-th); over: sampled triangles above the tolerance"
    );
    if failed {
        ExitCode::FAILURE
    } else {
        ExitCode::SUCCESS
    }
}
