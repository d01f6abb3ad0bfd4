//! `vesselcad simulate`: ticks of random valid edits (and level changes) on a
//! plant, printing per-tick latency, work counters and the plant's operating mass.

use std::path::PathBuf;
use std::process::ExitCode;
use std::time::Instant;

use clap::Args;
use vesselcad::design::load;
use vesselcad::mesh::TessellationOptions;
use vesselcad::plant::{Simulation, quantile};

use super::build::build_with_progress;
use super::output::outln;

/// `vesselcad simulate …`.
#[derive(Args)]
pub struct SimulateArgs {
    /// The plant design file.
    design: PathBuf,
    /// Number of ticks.
    #[arg(long, default_value_t = 10)]
    ticks: usize,
    /// Random valid edits per tick (dimension changes, nozzle moves, head swaps).
    #[arg(long, default_value_t = 10)]
    edits_per_tick: usize,
    /// Random seed of the edits.
    #[arg(long, default_value_t = 1)]
    seed: u64,
    /// Also change liquid levels, in one vessel in 20 per tick (at least one).
    #[arg(long)]
    levels: bool,
    /// Chordal tolerance of the meshes, mm.
    #[arg(long, default_value_t = TessellationOptions::DEFAULT.tolerance, allow_negative_numbers = true)]
    tolerance: f64,
}

/// Runs `vesselcad simulate`.
pub fn run(args: SimulateArgs) -> ExitCode {
    let design = match load(&args.design) {
        Ok(d) => d,
        Err(e) => {
            eprintln!("error: {e}");
            return ExitCode::from(1);
        }
    };
    let start = Instant::now();
    let model = match build_with_progress(&design, TessellationOptions::chord(args.tolerance)) {
        Ok(m) => m,
        Err(e) => {
            eprintln!("error: {e}");
            return ExitCode::from(1);
        }
    };
    outln!(
        "{}: {} vessels built in {:.1} s",
        args.design.display(),
        design.vessels.len(),
        start.elapsed().as_secs_f64()
    );
    let mut sim = Simulation::new(model, &design, args.seed);
    let levels = if args.levels {
        (design.vessels.len() / 20).max(1)
    } else {
        0
    };
    outln!(
        "tick  latency ms (update)  edits refused levels  resolved shapes patches meshes triangles operating  operating mass t"
    );
    let mut latencies = Vec::with_capacity(args.ticks);
    for tick in 1..=args.ticks {
        let r = sim.tick(args.edits_per_tick, levels);
        latencies.push(r.latency);
        let c = r.counters;
        outln!(
            "{tick:>4}  {:>10.3} ({:>7.3})  {:>5} {:>7} {:>6}  {:>8} {:>6} {:>7} {:>6} {:>9} {:>9}  {:>16.3}",
            r.latency.as_secs_f64() * 1e3,
            r.update.as_secs_f64() * 1e3,
            r.edits,
            r.refused,
            r.levels,
            c.vessels_resolved,
            c.shapes_rebuilt,
            c.patches_rebuilt,
            c.meshes_rebuilt,
            c.triangles_meshed,
            c.operating_updated,
            sim.total_operating_mass() / 1e3,
        );
        if c.failures > 0 {
            eprintln!(
                "warning: tick {tick}: {} patches or openings failed",
                c.failures
            );
            let errors = &sim.model().errors().0;
            for failure in errors.iter().rev().take(c.failures as usize) {
                eprintln!("  {failure}");
            }
        }
    }
    let p50 = quantile(&mut latencies, 0.5);
    let p99 = quantile(&mut latencies, 0.99);
    outln!(
        "latency per tick: p50 {:.3} ms, p99 {:.3} ms; plant operating mass {:.3} t",
        p50.as_secs_f64() * 1e3,
        p99.as_secs_f64() * 1e3,
        sim.total_operating_mass() / 1e3
    );
    ExitCode::SUCCESS
}
