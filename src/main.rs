//! The `vesselcad` command line: build a design into a GLB, check a design, or
//! report its figures. Each command lives in its own file under `src/cli/`; this
//! file only names them.
//!
//! Exit status: 0 on success; 1 when the design is invalid (every problem is
//! listed on stderr); 2 when a file cannot be read or written or the command line
//! is wrong. A reader of standard output that goes away early (`| head -1`) ends
//! a command quietly with 0.

use std::process::ExitCode;

use clap::{Parser, Subcommand};

mod cli;

#[derive(Parser)]
#[command(
    name = "vesselcad",
    version,
    about = "Parametric process vessels as exact NURBS"
)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Build a design and write it as binary glTF (Y-up, metres).
    Build(cli::build::BuildArgs),
    /// Check a design: exit 0 when valid, 1 with every problem listed otherwise.
    Check(cli::check::CheckArgs),
    /// The code calculation report (ASME VIII-1): text, JSON, HTML or PDF.
    Calc(cli::calc::CalcArgs),
    /// Serve a live redesign session: viewer page, JSON Patch edits, journal,
    /// glTF deltas over WebSocket (see `vesselcad::server`).
    Serve(cli::serve::ServeArgs),
    /// Draw one vessel's sheet (views, dimensions, tables) as SVG and optionally DXF.
    Drawing(cli::drawing::DrawingArgs),
    /// Report each vessel's parts, nozzles, lengths, OD, volume and area.
    Info(cli::info::InfoArgs),
    /// Plant tools: `plant generate --vessels N --seed S -o plant.json`.
    Plant(cli::plant::PlantArgs),
    /// Simulate ticks of random edits and level changes on a plant.
    Simulate(cli::simulate::SimulateArgs),
    /// Measure the plant-scale figures on this machine, beside their targets.
    Bench(cli::bench::BenchArgs),
    /// Write the exact model as STEP (AP214): sewn B-spline faces, shells,
    /// nozzle connection points.
    Export(cli::export::ExportArgs),
    /// Plan one vessel's fabrication: flat patterns, seams, plate DXFs,
    /// nesting; traveler, BOM, weld map (CSV, JSON, GLB, SVG).
    Fab(cli::fab::FabArgs),
    /// Write one vessel's shell finite-element model (CalculiX .inp, Gmsh .msh,
    /// VTU) and optionally solve it with ccx.
    Fem(cli::fem::FemArgs),
    /// The design store: import, list, log, show, diff, tag, checkout, export,
    /// search (SQLite file or PostgreSQL URL).
    Store(cli::store::StoreArgs),
    /// Scans against the design: `scan simulate` draws a synthetic scan with
    /// known defects; `scan fit` registers a scan, fits it part by part and
    /// reports the code checks (HTML, JSON, a coloured GLB).
    Scan(cli::scan::ScanArgs),
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    // A command that runs to completion keeps its freed memory for reuse; a
    // server gives it back (see `vesselcad::allocator`).
    if !matches!(cli.command, Command::Serve(_)) {
        vesselcad::allocator::hold_freed_memory();
    }
    match cli.command {
        Command::Build(args) => cli::build::run(args),
        Command::Check(args) => cli::check::run(args),
        Command::Serve(args) => cli::serve::run(args),
        Command::Drawing(args) => cli::drawing::run(args),
        Command::Info(args) => cli::info::run(args),
        Command::Calc(args) => cli::calc::run(args),
        Command::Plant(args) => cli::plant::run(args),
        Command::Simulate(args) => cli::simulate::run(args),
        Command::Bench(args) => cli::bench::run(args),
        Command::Export(args) => cli::export::run(args),
        Command::Fab(args) => cli::fab::run(args),
        Command::Fem(args) => cli::fem::run(args),
        Command::Store(args) => cli::store::run(args),
        Command::Scan(args) => cli::scan::run(args),
    }
}
