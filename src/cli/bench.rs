//! `vesselcad bench`: the plant-scale figures of this machine in one table.

use std::process::ExitCode;

use clap::Args;
use vesselcad::plant::{BenchConfig, format_markdown, format_table, run_bench};

use super::alloc::live_bytes;
use super::output::out;

/// `vesselcad bench …`.
#[derive(Args)]
pub struct BenchArgs {
    /// Vessels in the generated plant.
    #[arg(long, default_value_t = BenchConfig::default().vessels)]
    vessels: usize,
    /// Plant seed.
    #[arg(long, default_value_t = BenchConfig::default().seed)]
    seed: u64,
    /// Chordal tolerance, mm.
    #[arg(long, default_value_t = BenchConfig::default().tolerance, allow_negative_numbers = true)]
    tolerance: f64,
    /// One-parameter edits measured.
    #[arg(long, default_value_t = BenchConfig::default().edits)]
    edits: usize,
    /// Ticks of 100 edits measured (the tick's p50 is their median).
    #[arg(long, default_value_t = BenchConfig::default().ticks)]
    ticks: usize,
    /// Print the table as Markdown (figure | value | target | met), as BENCHMARKS.md
    /// holds it.
    #[arg(long)]
    markdown: bool,
}

/// Runs `vesselcad bench`.
pub fn run(args: BenchArgs) -> ExitCode {
    if args.vessels == 0 {
        eprintln!("error: --vessels must be at least 1");
        return ExitCode::from(2);
    }
    let config = BenchConfig {
        vessels: args.vessels,
        seed: args.seed,
        tolerance: args.tolerance,
        edits: args.edits,
        ticks: args.ticks,
        ..BenchConfig::default()
    };
    let heap = || Some(live_bytes());
    let mut progress = |what: &str| eprintln!("bench: {what}…");
    match run_bench(&config, &heap, &mut progress, &std::env::temp_dir()) {
        Ok(rows) => {
            if args.markdown {
                out!("{}", format_markdown(&rows));
            } else {
                out!("{}", format_table(&rows));
            }
            ExitCode::SUCCESS
        }
        Err(e) => {
            eprintln!("error: {e}");
            ExitCode::from(2)
        }
    }
}
