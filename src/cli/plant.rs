//! `vesselcad plant generate`: write a generated plant as a design file.

use std::path::PathBuf;
use std::process::ExitCode;

use clap::{Args, Subcommand};
use vesselcad::design::save;
use vesselcad::plant::generate_plant;

use super::output::outln;

/// `vesselcad plant …`.
#[derive(Args)]
pub struct PlantArgs {
    #[command(subcommand)]
    command: PlantCommand,
}

#[derive(Subcommand)]
enum PlantCommand {
    /// Generate a valid, realistic plant of N vessels (deterministic for a seed).
    Generate {
        /// Number of vessels.
        #[arg(long)]
        vessels: usize,
        /// Random seed.
        #[arg(long, default_value_t = 1)]
        seed: u64,
        /// Output design file (JSON).
        #[arg(short, long)]
        output: PathBuf,
    },
}

/// Runs `vesselcad plant …`.
pub fn run(args: PlantArgs) -> ExitCode {
    match args.command {
        PlantCommand::Generate {
            vessels,
            seed,
            output,
        } => {
            let design = match generate_plant(vessels, seed) {
                Ok(d) => d,
                Err(e) => {
                    eprintln!("error: {e}");
                    return ExitCode::from(2);
                }
            };
            if let Err(e) = save(&design, &output) {
                eprintln!("error: {e}");
                return ExitCode::from(2);
            }
            let nozzles: usize = design.vessels.iter().map(|v| v.nozzles.len()).sum();
            let parts: usize = design.vessels.iter().map(|v| v.parts.len()).sum();
            outln!(
                "{}: {} vessels, {parts} parts, {nozzles} nozzles (seed {seed})",
                output.display(),
                design.vessels.len()
            );
            ExitCode::SUCCESS
        }
    }
}
