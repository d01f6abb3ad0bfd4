//! The FE mesh rebuilt after an edit through a `FemCache`, beside a mesh from
//! scratch, in one run: the example column after its nozzle N2 (on course S2)
//! turns, the drum after its nozzle N5 (on its one course) moves, and either
//! after a pressure edit (no piece meshed). Best of 7 of each, alternating, with
//! the pieces meshed and reused.
//!
//! `cargo run --profile test --example fem_incremental`

use std::time::{Duration, Instant};

use vesselcad::design::{Design, load, resolve};
use vesselcad::fem::{FeMesh, FemCache, FemOptions, build_envelope, build_envelope_cached};

const REPEATS: usize = 7;

fn design(name: &str) -> Design {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("examples/designs")
        .join(format!("{name}.json"));
    load(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()))
}

fn mesh(design: &Design, cache: Option<&mut FemCache>) -> FeMesh {
    let resolved = resolve(design).expect("valid design");
    let (v, r) = (&design.vessels[0], &resolved[0]);
    let options = FemOptions::default();
    match cache {
        Some(c) => build_envelope_cached(v, r, &options, c),
        None => build_envelope(v, r, &options),
    }
    .expect("mesh")
}

/// Turns nozzle `mark` by `by` degrees (or moves it `by` mm along the axis on
/// a horizontal vessel, whose nozzles stand at an elevation along it).
fn nudge(design: &mut Design, mark: &str, by: f64, along: bool) {
    let n = design.vessels[0]
        .nozzles
        .iter_mut()
        .find(|n| n.mark == mark)
        .expect("nozzle");
    if along {
        n.elevation = n.elevation.map(|e| e + by);
    } else {
        n.orientation += by;
    }
}

fn main() {
    println!("| Vessel | Edit | Scratch | Incremental | Pieces meshed / reused |");
    println!("|---|---|---|---|---|");
    for (name, mark, by, along) in [
        ("vertical-column", "N2", 20.0, false),
        ("horizontal-drum", "N5", 100.0, true),
    ] {
        let mut d = design(name);
        let tag = d.vessels[0].tag.clone();
        let mut cache = FemCache::new();
        mesh(&d, Some(&mut cache));
        let (mut scratch, mut moved, mut loads) = (Duration::MAX, Duration::MAX, Duration::MAX);
        let (mut moved_counts, mut load_counts) = ((0, 0), (0, 0));
        for rep in 0..REPEATS {
            let sign = if rep % 2 == 0 { 1.0 } else { -1.0 };
            nudge(&mut d, mark, sign * by, along);
            let t = Instant::now();
            let inc = mesh(&d, Some(&mut cache));
            moved = moved.min(t.elapsed());
            let c = cache.counters();
            moved_counts = (c.meshed, c.reused);
            let t = Instant::now();
            let full = mesh(&d, None);
            scratch = scratch.min(t.elapsed());
            assert_eq!(inc, full, "{tag}: incremental = scratch");
            let p = d.vessels[0].design.pressure.unwrap_or(1.0);
            d.vessels[0].design.pressure = Some(p * 1.01);
            let t = Instant::now();
            mesh(&d, Some(&mut cache));
            loads = loads.min(t.elapsed());
            let c = cache.counters();
            load_counts = (c.meshed, c.reused);
        }
        let ms = |d: Duration| d.as_secs_f64() * 1e3;
        println!(
            "| {tag} | {mark} moved | {:.1} ms | {:.1} ms | {} / {} |",
            ms(scratch),
            ms(moved),
            moved_counts.0,
            moved_counts.1
        );
        println!(
            "| {tag} | pressure | {:.1} ms | {:.1} ms | {} / {} |",
            ms(scratch),
            ms(loads),
            load_counts.0,
            load_counts.1
        );
    }
}
