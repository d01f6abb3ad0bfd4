//! Times the mesher on the issue-4 bench cases without curvo: `fd` (ASME F&D
//! head OD 2400), `sphere` (R 1000), `shell` (2400×6000 course with six nozzles), at
//! 0.1 mm or `TOL`; best of `reps`. For profiling (callgrind, perf) of one case.
//!
//! Meshes inside the rayon pool, as the bench and the Tessellate stage do;
//! `STATS=1` prints each mesh's statistics.
//!
//! `cargo run --release --example mesh_profile -- [fd|sphere|shell|both] [reps]`
use std::time::Instant;
use vesselcad::mesh::cdt::mesh_region_on;
use vesselcad::mesh::{TessellationOptions, patch_region};
use vesselcad::parts::heads::{Head, HeadKind};

fn main() {
    let which = std::env::args().nth(1).unwrap_or_else(|| "both".into());
    let reps: usize = std::env::args()
        .nth(2)
        .and_then(|s| s.parse().ok())
        .unwrap_or(20);
    let options = TessellationOptions {
        tolerance: std::env::var("TOL")
            .ok()
            .and_then(|s| s.parse().ok())
            .unwrap_or(0.1),
        ..TessellationOptions::default()
    };
    let od = 2400.0;
    let fd = Head::new(od, HeadKind::asme_fd(od)).patches().unwrap();
    let hemi = Head::new(2000.0, HeadKind::Hemispherical)
        .patches()
        .unwrap();
    let mut pieces = Vec::new();
    if which == "fd" || which == "both" {
        pieces.extend(fd.iter());
    }
    if which == "sphere" || which == "both" {
        pieces.push(&hemi[0]);
        pieces.push(&hemi[0]);
    }
    let mut regions: Vec<_> = pieces
        .iter()
        .map(|p| patch_region(&p.surface, &options, &[], None).unwrap())
        .collect();
    let shell_holder;
    if which == "shell" {
        let design = vesselcad::design::parse(SHELL).unwrap();
        let model = vesselcad::model::Model::from_design(&design, options).unwrap();
        let world = model.world();
        let mut query = world
            .try_query::<(
                &vesselcad::components::PatchSurface,
                &vesselcad::components::PatchRegion,
            )>()
            .unwrap();
        let (patch, region) = query
            .iter(world)
            .find(|(s, _)| s.0.name == "shell")
            .map(|(s, r)| (s.0.clone(), r.region.clone().unwrap()))
            .unwrap();
        shell_holder = patch;
        pieces.push(&shell_holder);
        regions.push((*region).clone());
        println!(
            "holes {} loop vertices {}",
            regions[0].holes.len(),
            regions[0].vertex_count()
        );
    }
    // Meshed inside the pool, as the model's Tessellate stage and the mesher bench
    // do: the mesher's own parallel loops then run on the worker, not handed over
    // from the main thread.
    let pool = rayon::ThreadPoolBuilder::new().build().unwrap();
    let (best, tris) = pool.install(|| time(&pieces, &regions, &options, reps));
    report(&which, tris, best);
}

/// Best time of `reps` meshings of every piece, and the triangle count.
fn time(
    pieces: &[&vesselcad::parts::Patch],
    regions: &[vesselcad::mesh::cdt::Region],
    options: &TessellationOptions,
    reps: usize,
) -> (f64, usize) {
    let mut best = f64::MAX;
    let mut tris = 0;
    let stats = std::env::var("STATS").is_ok();
    for _ in 0..reps {
        let t = Instant::now();
        tris = 0;
        for (p, r) in pieces.iter().zip(regions) {
            let (m, s) = mesh_region_on(&p.surface, &p.analytic, r, options).unwrap();
            tris += m.indices.len() / 3;
            if stats {
                eprintln!("{s:?}");
            }
            std::hint::black_box(s);
        }
        best = best.min(t.elapsed().as_secs_f64());
    }
    (best, tris)
}

fn report(which: &str, tris: usize, best: f64) {
    println!(
        "{which}: {tris} tris, best {:.2} ms, {:.2} Mtri/s",
        best * 1e3,
        tris as f64 / best / 1e6
    );
}

const SHELL: &str = r#"{
  "format": "vesselcad/1",
  "units": "mm",
  "vessels": [{
    "tag": "B-1",
    "kind": "vertical",
    "parts": [{ "shell": { "id": "S1", "od": 2400, "length": 6000 } }],
    "nozzles": [
      { "mark": "M1", "size": 24, "rating": 150, "host": "S1", "orientation": 30, "elevation": 3000, "projection": 1600 },
      { "mark": "N1", "size": 8, "rating": 150, "host": "S1", "orientation": 100, "elevation": 1200, "projection": 1600 },
      { "mark": "N2", "size": 6, "rating": 150, "host": "S1", "orientation": 150, "elevation": 4800, "projection": 1600 },
      { "mark": "N3", "size": 4, "rating": 300, "host": "S1", "orientation": 200, "elevation": 2200, "projection": 1600 },
      { "mark": "N4", "size": 3, "rating": 150, "host": "S1", "orientation": 260, "elevation": 3900, "projection": 1600 },
      { "mark": "N5", "size": 2, "rating": 150, "host": "S1", "orientation": 320, "elevation": 800, "projection": 1600 }
    ]
  }]
}"#;
