//! `vesselcad scan simulate …`, `vesselcad scan fit …` and `vesselcad scan
//! interpolate …`: synthetic scans with a known truth, a scan compared with its
//! design, and an ordered CMM grid interpolated exactly (see `vesselcad::scan`).

use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::time::Instant;

use clap::{Args, Subcommand};
use vesselcad::design::load;
use vesselcad::scan::checks::CheckOptions;
use vesselcad::scan::defects::parse_defects;
use vesselcad::scan::fit::FitOptions;
use vesselcad::scan::glb::deviation_glb;
use vesselcad::scan::grid::{Parametrization, interpolate_grid};
use vesselcad::scan::grid_file::{max_residual, read_grid, surface_json};
use vesselcad::scan::inspect::{InspectOptions, inspect};
use vesselcad::scan::points::{PointFormat, load_points, write_points};
use vesselcad::scan::register::RegisterOptions;
use vesselcad::scan::report::{to_html_with_maps, to_json};
use vesselcad::scan::simulate::{SimulateOptions, SiteTransform, simulate};
use vesselcad::scan::step::fitted_step;
use vesselcad::scan::unrolled::unrolled_maps;
use vesselcad::scan::{Envelope, ScanError};

use super::output::outln;

/// Arguments of `vesselcad scan`.
#[derive(Args)]
pub struct ScanArgs {
    #[command(subcommand)]
    command: ScanCommand,
}

#[derive(Subcommand)]
enum ScanCommand {
    /// Draw a synthetic scan of a vessel with known defects, noise, gaps and a
    /// site pose (its truth is written beside it as `<out>.truth.json`).
    Simulate(SimulateArgs),
    /// Compare a scan with its design: register, fit, check, report.
    Fit(FitArgs),
    /// Interpolate an ordered grid of points (a CMM's rows and columns) exactly
    /// by a B-spline surface and write it as JSON.
    Interpolate(InterpolateArgs),
}

/// Arguments of `vesselcad scan interpolate`.
#[derive(Args)]
pub struct InterpolateArgs {
    /// The grid: one point `x y z` a line (spaces, commas, tabs or
    /// semicolons), rows separated by blank lines, every row as long as the first.
    grid: PathBuf,
    /// The surface, JSON (degrees, knots, control points, parameters, residual).
    #[arg(short, long)]
    output: PathBuf,
    /// Degree along the rows (u) and along each row (v); lowered to the points
    /// less one in a direction that has fewer.
    #[arg(long, default_value_t = 3)]
    degree: usize,
    /// Data parameters: `chord`, `centripetal` or `uniform` (the seed's paper).
    #[arg(long, default_value = "chord")]
    parametrization: String,
}

/// Arguments of `vesselcad scan simulate`.
#[derive(Args)]
pub struct SimulateArgs {
    /// The design file.
    design: PathBuf,
    /// The vessel to scan.
    #[arg(long)]
    vessel: String,
    /// Defects, e.g. `ovality=0.8%@course:S2,dent=25mm@EL4000/90°,peaking=8mm@seam,tilt=0.3°,settlement=cosine:40mm`.
    #[arg(long, default_value = "")]
    defects: String,
    /// Noise (standard deviation per coordinate), mm.
    #[arg(long, default_value_t = 1.5)]
    noise: f64,
    /// Points per m², e.g. `20` or `20/m²`.
    #[arg(long, default_value = "20")]
    density: String,
    /// Fraction of the surface hidden, e.g. `20%` or `0.2`.
    #[arg(long, default_value = "0")]
    occlusion: String,
    /// Seed of every random choice.
    #[arg(long, default_value_t = 1)]
    seed: u64,
    /// Keep plant coordinates (no site transform).
    #[arg(long)]
    plant_frame: bool,
    /// Write PLY as ASCII (binary otherwise).
    #[arg(long)]
    ascii: bool,
    /// Output: `.ply` (PLY), `.las` (LAS 1.2), `.laz` (compressed LAS),
    /// anything else XYZ text.
    #[arg(short, long)]
    output: PathBuf,
}

/// Arguments of `vesselcad scan fit`.
#[derive(Args)]
pub struct FitArgs {
    /// The design file.
    design: PathBuf,
    /// The vessel scanned.
    #[arg(long)]
    vessel: String,
    /// The scan: XYZ/CSV text, PLY (ASCII or binary), LAS or LAZ; mm.
    points: PathBuf,
    /// The HTML report.
    #[arg(short, long)]
    output: PathBuf,
    /// Also write the report as JSON to this file.
    #[arg(long, value_name = "PATH")]
    json: Option<PathBuf>,
    /// Write the deviation map as binary glTF with vertex colours.
    #[arg(long)]
    glb: Option<PathBuf>,
    /// Write the fitted (as-built) surfaces as STEP (AP214) faces.
    #[arg(long)]
    step: Option<PathBuf>,
    /// The points are already in plant coordinates: do not register.
    #[arg(long)]
    keep_frame: bool,
    /// Free all six degrees of freedom in registration (the scanner was not levelled).
    #[arg(long)]
    unlevelled: bool,
    /// The scanner's noise, mm: the fit's net grows until its residual is this.
    #[arg(long, default_value_t = FitOptions::DEFAULT.noise)]
    noise: f64,
    /// Smallest local deviation reported as a dent or bulge, mm.
    #[arg(long, default_value_t = CheckOptions::DEFAULT.dent_threshold)]
    dent_threshold: f64,
}

/// Runs `vesselcad scan`.
pub fn run(args: ScanArgs) -> ExitCode {
    let result = match args.command {
        ScanCommand::Simulate(a) => run_simulate(&a),
        ScanCommand::Fit(a) => run_fit(&a),
        ScanCommand::Interpolate(a) => run_interpolate(&a),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {e}");
            match e {
                ScanError::Io { .. } | ScanError::SameFile { .. } => ExitCode::from(2),
                _ => ExitCode::from(1),
            }
        }
    }
}

/// A number with an optional suffix (`20/m²`, `20%`): `percent` divides by 100
/// when the `%` is written.
fn option_number(field: &'static str, text: &str, suffixes: &[&str]) -> Result<f64, ScanError> {
    let mut t = text.trim();
    let mut percent = false;
    for s in suffixes {
        if let Some(rest) = t.strip_suffix(s) {
            percent = *s == "%";
            t = rest;
            break;
        }
    }
    let v: f64 = t.trim().parse().map_err(|_| ScanError::Options {
        field,
        value: f64::NAN,
        rule: "must be a number",
    })?;
    Ok(if percent { v / 100.0 } else { v })
}

fn envelope(design: &Path, vessel: &str) -> Result<Envelope, ScanError> {
    let design = load(design)?;
    Envelope::of_design(&design, vessel)
}

fn run_simulate(a: &SimulateArgs) -> Result<(), ScanError> {
    let start = Instant::now();
    let env = envelope(&a.design, &a.vessel)?;
    let defects = parse_defects(&a.defects, &env)?;
    let options = SimulateOptions {
        density: option_number("--density", &a.density, &["/m²", "/m2"])?,
        noise: a.noise,
        occlusion: option_number("--occlusion", &a.occlusion, &["%"])?,
        seed: a.seed,
        site: (!a.plant_frame).then(|| SiteTransform::from_seed(a.seed)),
        defects,
    };
    let scan = simulate(&env, &options)?;
    let format = PointFormat::of_path(&a.output, a.ascii);
    write_points(&a.output, format, &scan.points)?;
    let truth_path = a.output.with_extension("truth.json");
    let truth = serde_json::to_string_pretty(&scan.truth).unwrap_or_default();
    std::fs::write(&truth_path, truth).map_err(|e| ScanError::io(&truth_path, e))?;
    outln!(
        "{}: {} points of {} ({} defects), truth in {} ({:.2} s)",
        a.output.display(),
        scan.points.len(),
        a.vessel,
        options.defects.len(),
        truth_path.display(),
        start.elapsed().as_secs_f64()
    );
    Ok(())
}

/// Whether two paths name the same file: the same path once made absolute, or
/// (for files that exist) the same canonical path.
fn same_file(a: &Path, b: &Path) -> bool {
    match (a.canonicalize(), b.canonicalize()) {
        (Ok(x), Ok(y)) => x == y,
        _ => std::path::absolute(a).ok() == std::path::absolute(b).ok(),
    }
}

/// Refuses an output (`-o`, `--json`, `--glb`, `--step`) that names an input or another
/// output, before anything is read or written.
fn refuse_overwrites(a: &FitArgs) -> Result<(), ScanError> {
    let mut outputs: Vec<(&'static str, &Path, &'static str)> =
        vec![("-o", a.output.as_path(), "HTML report")];
    if let Some(p) = &a.json {
        outputs.push(("--json", p, "JSON report"));
    }
    if let Some(p) = &a.glb {
        outputs.push(("--glb", p, "GLB map"));
    }
    if let Some(p) = &a.step {
        outputs.push(("--step", p, "STEP model"));
    }
    for (k, &(option, path, _)) in outputs.iter().enumerate() {
        let inputs = [
            (a.design.as_path(), "design file"),
            (a.points.as_path(), "scan"),
        ];
        let earlier = outputs[..k].iter().map(|&(_, p, what)| (p, what));
        for (other, what) in inputs.into_iter().chain(earlier) {
            if same_file(path, other) {
                return Err(ScanError::SameFile {
                    option,
                    path: path.to_path_buf(),
                    other: what,
                });
            }
        }
    }
    Ok(())
}

fn run_fit(a: &FitArgs) -> Result<(), ScanError> {
    let start = Instant::now();
    let env = envelope(&a.design, &a.vessel)?;
    if !(a.noise > 0.0 && a.noise.is_finite()) {
        return Err(ScanError::Options {
            field: "--noise",
            value: a.noise,
            rule: "must be > 0 mm",
        });
    }
    refuse_overwrites(a)?;
    let points = load_points(&a.points)?;
    let read = start.elapsed().as_secs_f64();
    let options = InspectOptions {
        register: (!a.keep_frame).then_some(RegisterOptions {
            levelled: !a.unlevelled,
            ..RegisterOptions::DEFAULT
        }),
        fit: FitOptions {
            noise: a.noise,
            ..FitOptions::DEFAULT
        },
        checks: CheckOptions {
            dent_threshold: a.dent_threshold,
            ..CheckOptions::DEFAULT
        },
    };
    let inspection = inspect(&env, points, &options)?;
    let scale = (3.0 * a.noise).max(5.0);
    let maps = unrolled_maps(&env, &inspection);
    std::fs::write(&a.output, to_html_with_maps(&inspection, &maps, scale))
        .map_err(|e| ScanError::io(&a.output, e))?;
    if let Some(path) = &a.json {
        std::fs::write(path, to_json(&inspection)).map_err(|e| ScanError::io(path, e))?;
    }
    if let Some(path) = &a.glb {
        let bytes = deviation_glb(&env, &inspection, scale);
        std::fs::write(path, bytes).map_err(|e| ScanError::io(path, e))?;
    }
    if let Some(path) = &a.step {
        let name = path
            .file_name()
            .map_or_else(String::new, |n| n.to_string_lossy().into_owned());
        let text = fitted_step(&env, &inspection.fits, &name)?;
        std::fs::write(path, text).map_err(|e| ScanError::io(path, e))?;
    }
    for f in &inspection.checks.findings {
        outln!(
            "{}{} {}: {:.3} {} at EL {:.0} / {:.1}°",
            if f.exceeds { "EXCEEDS " } else { "" },
            f.kind,
            f.part,
            f.size,
            f.unit,
            f.elevation,
            f.orientation
        );
    }
    outln!(
        "{}: {} points, {} findings ({} over limits), registration RMS {:.3} mm (read {:.2} s, total {:.2} s)",
        a.output.display(),
        inspection.points,
        inspection.checks.findings.len(),
        inspection
            .checks
            .findings
            .iter()
            .filter(|f| f.exceeds)
            .count(),
        inspection.registration.rms,
        read,
        start.elapsed().as_secs_f64()
    );
    Ok(())
}

fn run_interpolate(a: &InterpolateArgs) -> Result<(), ScanError> {
    let parametrization = match a.parametrization.as_str() {
        "chord" => Parametrization::ChordLength,
        "centripetal" => Parametrization::Centripetal,
        "uniform" => Parametrization::Uniform,
        other => {
            return Err(ScanError::Unsupported {
                option: "--parametrization",
                value: other.to_string(),
                rule: "must be chord, centripetal or uniform",
            });
        }
    };
    if !a
        .output
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("json"))
    {
        return Err(ScanError::Unsupported {
            option: "-o",
            value: a.output.display().to_string(),
            rule: "must name a .json file (the surface's degrees, knots and control points)",
        });
    }
    if same_file(&a.output, &a.grid) {
        return Err(ScanError::SameFile {
            option: "-o",
            path: a.output.clone(),
            other: "grid",
        });
    }
    let grid = read_grid(&a.grid)?;
    let degrees = (a.degree.min(grid.rows - 1), a.degree.min(grid.columns - 1));
    let fit = interpolate_grid(
        &grid.points,
        (grid.rows, grid.columns),
        degrees,
        parametrization,
    )?;
    let residual = max_residual(&fit, &grid);
    let json = surface_json(&fit, parametrization, residual);
    std::fs::write(&a.output, json).map_err(|e| ScanError::io(&a.output, e))?;
    outln!(
        "{}: {} × {} grid, degrees {} × {}, {} × {} control points, max residual {:.3e} mm at the grid points",
        a.output.display(),
        grid.rows,
        grid.columns,
        degrees.0,
        degrees.1,
        fit.surface.u_count(),
        fit.surface.v_count(),
        residual
    );
    Ok(())
}
