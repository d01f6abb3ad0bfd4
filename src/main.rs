//! The `vesselcad` command line: build a design into a GLB, check a design, or
//! report its figures.
//!
//! Exit status: 0 on success; 1 when the design is invalid (every problem is
//! listed on stderr); 2 when a file cannot be read or written or the command line
//! is wrong.

mod drawing_command;

use std::path::PathBuf;
use std::process::ExitCode;
use std::time::Instant;

use clap::{Parser, Subcommand};
use vesselcad::design::{DesignError, load};
use vesselcad::export::{stream_glb, stream_glb_to};
use vesselcad::mesh::TessellationOptions;
use vesselcad::model::ModelError;
use vesselcad::report::report;
use vesselcad::server::cli::{ServeArgs, serve_command};

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
    Build {
        /// The design file (JSON, vesselcad/1).
        design: PathBuf,
        /// Output GLB file (`.glb`), or `-` for standard output.
        #[arg(short, long)]
        output: PathBuf,
        /// Chordal tolerance of the meshes, mm.
        #[arg(long, default_value_t = TessellationOptions::DEFAULT.tolerance, allow_negative_numbers = true)]
        tolerance: f64,
        /// Largest ratio between a triangle's sizes in two directions (≥ 1; e.g. 3
        /// for analysis-quality triangles). No limit by default.
        #[arg(long, allow_negative_numbers = true)]
        max_stretch: Option<f64>,
    },
    /// Check a design: exit 0 when valid, 1 with every problem listed otherwise.
    Check {
        /// The design file.
        design: PathBuf,
        /// Print the result as JSON (`vesselcad-check/1`) on standard output.
        #[arg(long)]
        json: bool,
        /// Also exit 1 when a part or nozzle is thinner than the code requires.
        #[arg(long)]
        strict: bool,
    },
    /// The code calculation report (ASME VIII-1): text, JSON, HTML or PDF.
    Calc(cli::calc::CalcArgs),
    /// Serve a live redesign session: viewer page, JSON Patch edits, journal,
    /// glTF deltas over WebSocket (see `vesselcad::server`).
    Serve(ServeArgs),
    /// Draw one vessel's sheet (views, dimensions, tables) as SVG and optionally DXF.
    Drawing(drawing_command::DrawingArgs),
    /// Report each vessel's parts, nozzles, lengths, OD, volume and area.
    Info {
        /// The design file.
        design: PathBuf,
        /// Print JSON instead of text.
        #[arg(long)]
        json: bool,
        /// Also build the model and report its counts and measured memory per
        /// vessel.
        #[arg(long)]
        memory: bool,
        /// Chordal tolerance of the meshes for `--memory`, mm.
        #[arg(long, default_value_t = 1.0, allow_negative_numbers = true)]
        tolerance: f64,
    },
    /// Plant tools: `plant generate --vessels N --seed S -o plant.json`.
    Plant(cli::plant::PlantArgs),
    /// Simulate ticks of random edits and level changes on a plant.
    Simulate(cli::simulate::SimulateArgs),
    /// Measure the plant-scale figures on this machine, beside their targets.
    Bench(cli::bench::BenchArgs),
    /// Write the exact model as STEP (AP214): sewn B-spline faces, shells,
    /// nozzle connection points.
    Export(cli::export::ExportArgs),
}

/// Prints a design error and returns the exit code for it.
fn fail(error: &DesignError) -> ExitCode {
    eprintln!("error: {error}");
    match error {
        DesignError::Io { .. } => ExitCode::from(2),
        _ => ExitCode::from(1),
    }
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    // A command that runs to completion keeps its freed memory for reuse; a
    // server gives it back (see `vesselcad::allocator`).
    if !matches!(cli.command, Command::Serve(_)) {
        vesselcad::allocator::hold_freed_memory();
    }
    match cli.command {
        Command::Serve(args) => serve_command(args),
        Command::Drawing(args) => drawing_command::run(args),
        Command::Calc(args) => cli::calc::run(args),
        Command::Check {
            design,
            json: true,
            strict,
        } => cli::check::check_json(&design, strict),
        Command::Check {
            design,
            json: false,
            strict,
        } => match load(&design) {
            Ok(d) => {
                println!(
                    "{}: valid ({} vessel(s))",
                    design.display(),
                    d.vessels.len()
                );
                cli::check::print_deficiencies(&d, strict)
            }
            Err(e) => fail(&e),
        },
        Command::Plant(args) => cli::plant::run(args),
        Command::Export(args) => cli::export::run(args),
        Command::Simulate(args) => cli::simulate::run(args),
        Command::Bench(args) => cli::bench::run(args),
        Command::Info {
            design,
            json,
            memory,
            tolerance,
        } => {
            let d = match load(&design) {
                Ok(d) => d,
                Err(e) => return fail(&e),
            };
            let vessels = match report(&d) {
                Ok(v) => v,
                Err(e) => return fail(&e),
            };
            if json {
                let report = serde_json::json!({
                    "format": cli::check::INFO_FORMAT,
                    "units": cli::check::info_units(),
                    "vessels": vessels,
                });
                match serde_json::to_string_pretty(&report) {
                    Ok(text) => println!("{text}"),
                    Err(e) => {
                        eprintln!("error: {e}");
                        return ExitCode::from(2);
                    }
                }
            } else {
                for v in &vessels {
                    println!("{} ({})", v.tag, v.kind);
                    println!(
                        "  parts:            {}",
                        v.parts
                            .iter()
                            .map(|p| format!("{} {}", p.kind, p.id))
                            .collect::<Vec<_>>()
                            .join(", ")
                    );
                    println!(
                        "  nozzles:          {} ({})",
                        v.nozzles.len(),
                        v.nozzles.join(", ")
                    );
                    println!("  tangent length:   {:.1} mm", v.tangent_length);
                    println!("  overall length:   {:.1} mm", v.overall_length);
                    println!("  outside diameter: {:.1} mm", v.outside_diameter);
                    println!(
                        "  volume:           {:.3} m³ (inside the outside surface)",
                        v.volume
                    );
                    println!(
                        "  surface area:     {:.3} m² (outside of heads and courses)",
                        v.surface_area
                    );
                    cli::build::print_operating(v);
                }
            }
            if memory {
                return cli::build::print_memory(&d, &design, tolerance);
            }
            ExitCode::SUCCESS
        }
        Command::Build {
            design,
            output,
            tolerance,
            max_stretch,
        } => {
            let start = Instant::now();
            let to_stdout = output.as_os_str() == "-";
            if !to_stdout
                && output
                    .extension()
                    .is_some_and(|e| e.eq_ignore_ascii_case("gltf"))
            {
                eprintln!(
                    "error: {}: vesselcad writes binary glTF only; name the output .glb \
                     (a .gltf file would be read as JSON glTF and fail)",
                    output.display()
                );
                return ExitCode::from(2);
            }
            let d = match load(&design) {
                Ok(d) => d,
                Err(e) => return fail(&e),
            };
            let model = match cli::build::build_with_progress(
                &d,
                TessellationOptions::chord(tolerance).with_max_stretch(max_stretch),
            ) {
                Ok(m) => m,
                Err(ModelError::Design(e)) => return fail(&e),
                Err(e) => {
                    eprintln!("error: {e}");
                    return ExitCode::from(2);
                }
            };
            if !model.errors().0.is_empty() {
                for (entity, violations) in &model.errors().0 {
                    for v in violations {
                        eprintln!("error: {entity}: {}", v.rule);
                    }
                }
                return ExitCode::from(1);
            }
            let scene = model.scene();
            let triangles: usize = scene
                .vessels
                .iter()
                .flat_map(|v| &v.nodes)
                .flat_map(|n| &n.patches)
                .map(|p| p.mesh.triangle_count())
                .sum();
            let written = if to_stdout {
                let stdout = std::io::stdout().lock();
                let mut out = std::io::BufWriter::new(stdout);
                stream_glb(&scene, &mut out, std::path::Path::new("<stdout>")).and_then(|n| {
                    use std::io::Write;
                    out.flush()
                        .map_err(|source| vesselcad::export::ExportError::Io {
                            path: "<stdout>".into(),
                            source,
                        })?;
                    Ok(n)
                })
            } else {
                stream_glb_to(&scene, &output)
            };
            let bytes = match written {
                Ok(bytes) => bytes,
                Err(e) => {
                    eprintln!("error: {e}");
                    return ExitCode::from(2);
                }
            };
            // On standard error when the GLB itself goes to standard output.
            let summary = format!(
                "{}: {} vessel(s), {} triangles at {} mm, {} bytes, {:.0} ms",
                if to_stdout {
                    "<stdout>".into()
                } else {
                    output.display().to_string()
                },
                scene.vessels.len(),
                triangles,
                tolerance,
                bytes,
                start.elapsed().as_secs_f64() * 1e3
            );
            if to_stdout {
                eprintln!("{summary}");
            } else {
                println!("{summary}");
            }
            ExitCode::SUCCESS
        }
    }
}
