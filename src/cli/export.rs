//! `vesselcad export <design> -o <file.step|.stp|.igs|.iges> [--vessel TAG ...]`:
//! the exact model as an exchange file (see `vesselcad::exchange`).

use std::path::PathBuf;
use std::process::ExitCode;
use std::time::Instant;

use clap::{Args, ValueEnum};
use vesselcad::design::{DesignError, load};
use vesselcad::exchange::{
    ExchangeError, ExchangeOptions, IgesEntities, StepBlocks, export_iges_as, export_step,
};

use super::output::outln;

/// An exchange format.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum Format {
    /// ISO 10303-21, AP214.
    Step,
    /// IGES 5.3: the B-rep (manifold solid entities), or trimmed surfaces.
    Iges,
}

/// The `export` subcommand's arguments.
#[derive(Args)]
pub struct ExportArgs {
    /// The design file (JSON, vesselcad/1).
    design: PathBuf,
    /// Output file: .step, .stp, .igs or .iges.
    #[arg(short, long)]
    output: PathBuf,
    /// Write only these vessels (repeatable); all by default.
    #[arg(long = "vessel", value_name = "TAG")]
    vessels: Vec<String>,
    /// Format; taken from the output's extension by default.
    #[arg(long, value_enum)]
    format: Option<Format>,
    /// Largest distance between an opening's exact curve and the curve written
    /// for it, mm.
    #[arg(long, default_value_t = ExchangeOptions::DEFAULT.tolerance, allow_negative_numbers = true)]
    tolerance: f64,
    /// Close each nozzle's bore at its gasket face and write each vessel's
    /// closed envelope as a solid (its displacement).
    #[arg(long)]
    solids: bool,
    /// IGES: write loose trimmed surfaces (144) instead of the B-rep's shells
    /// and solids (514/186), for receivers that do not read the B-rep.
    #[arg(long)]
    iges_trimmed: bool,
}

/// The format named by a file's extension.
fn format_of(path: &std::path::Path) -> Option<Format> {
    let extension = path.extension()?.to_str()?.to_ascii_lowercase();
    match extension.as_str() {
        "step" | "stp" => Some(Format::Step),
        "igs" | "iges" => Some(Format::Iges),
        _ => None,
    }
}

/// Runs `vesselcad export`.
pub fn run(args: ExportArgs) -> ExitCode {
    let start = Instant::now();
    let Some(format) = args.format.or_else(|| format_of(&args.output)) else {
        eprintln!(
            "error: {}: cannot tell the format from the extension (.step, .stp, .igs, .iges); give --format",
            args.output.display()
        );
        return ExitCode::from(2);
    };
    let design = match load(&args.design) {
        Ok(d) => d,
        Err(e) => {
            eprintln!("error: {e}");
            return ExitCode::from(if matches!(e, DesignError::Io { .. }) {
                2
            } else {
                1
            });
        }
    };
    let options = ExchangeOptions {
        tolerance: args.tolerance,
        solids: args.solids,
    };
    let name = args
        .output
        .file_name()
        .and_then(|n| n.to_str())
        .unwrap_or("vesselcad")
        .to_string();
    let text = match format {
        Format::Step => export_step(
            &design,
            &args.vessels,
            &options,
            &name,
            &mut StepBlocks::default(),
        ),
        Format::Iges => {
            let entities = if args.iges_trimmed {
                IgesEntities::Trimmed
            } else {
                IgesEntities::Brep
            };
            export_iges_as(&design, &args.vessels, &options, entities, &name)
        }
    };
    let text = match text {
        Ok(text) => text,
        Err(e) => {
            eprintln!("error: {e}");
            return ExitCode::from(match e {
                ExchangeError::Design(_) => 1,
                _ => 2,
            });
        }
    };
    if let Err(e) = std::fs::write(&args.output, &text) {
        eprintln!("error: cannot write {}: {e}", args.output.display());
        return ExitCode::from(2);
    }
    outln!(
        "{}: {} bytes, {:.0} ms",
        args.output.display(),
        text.len(),
        start.elapsed().as_secs_f64() * 1e3
    );
    ExitCode::SUCCESS
}
