//! `vesselcad info`: each vessel's parts, nozzles, lengths, OD, volume, area and
//! operating figures, as text or JSON (`vesselcad-info/1`); with `--memory`, the
//! measured memory of the built model per vessel.

use std::path::{Path, PathBuf};
use std::process::ExitCode;

use clap::Args;
use serde_json::{Value, json};
use vesselcad::design::{Design, load};
use vesselcad::mesh::TessellationOptions;
use vesselcad::report::{VesselReport, report};

use super::alloc::live_bytes;
use super::build::build_with_progress;
use super::fail;
use super::output::outln;

/// Arguments of `vesselcad info`.
#[derive(Args)]
pub struct InfoArgs {
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
}

/// The format tag of `info --json`.
pub const INFO_FORMAT: &str = "vesselcad-info/1";

/// The units of `info --json`'s figures.
pub fn info_units() -> Value {
    json!({
        "length": "mm",
        "volume": "m3",
        "area": "m2",
        "mass": "kg",
        "angle": "deg",
    })
}

/// Runs `vesselcad info`.
pub fn run(args: InfoArgs) -> ExitCode {
    let d = match load(&args.design) {
        Ok(d) => d,
        Err(e) => return fail(&e),
    };
    let vessels = match report(&d) {
        Ok(v) => v,
        Err(e) => return fail(&e),
    };
    if args.json {
        let report = json!({
            "format": INFO_FORMAT,
            "units": info_units(),
            "vessels": vessels,
        });
        match serde_json::to_string_pretty(&report) {
            Ok(text) => outln!("{text}"),
            Err(e) => {
                eprintln!("error: {e}");
                return ExitCode::from(2);
            }
        }
    } else {
        for v in &vessels {
            print_vessel(v);
        }
    }
    if args.memory {
        return print_memory(&d, &args.design, args.tolerance);
    }
    ExitCode::SUCCESS
}

/// Prints one vessel's figures as text.
fn print_vessel(v: &VesselReport) {
    outln!("{} ({})", v.tag, v.kind);
    outln!(
        "  parts:            {}",
        v.parts
            .iter()
            .map(|p| format!("{} {}", p.kind, p.id))
            .collect::<Vec<_>>()
            .join(", ")
    );
    outln!(
        "  nozzles:          {} ({})",
        v.nozzles.len(),
        v.nozzles.join(", ")
    );
    outln!("  tangent length:   {:.1} mm", v.tangent_length);
    outln!("  overall length:   {:.1} mm", v.overall_length);
    outln!("  outside diameter: {:.1} mm", v.outside_diameter);
    outln!(
        "  volume:           {:.3} m³ (inside the outside surface)",
        v.volume
    );
    outln!(
        "  surface area:     {:.3} m² (outside of heads and courses)",
        v.surface_area
    );
    print_operating(v);
}

/// Prints the counts of a built plant and its measured memory per vessel.
fn print_memory(design: &Design, path: &Path, tolerance: f64) -> ExitCode {
    let options = TessellationOptions::chord(tolerance);
    let before = live_bytes();
    let model = match build_with_progress(design, options) {
        Ok(m) => m,
        Err(e) => {
            eprintln!("error: {e}");
            return ExitCode::from(1);
        }
    };
    let heap = live_bytes().saturating_sub(before);
    let world = model.world();
    let entities = world.entities().len();
    let meshes = model.mesh_bytes();
    let n = design.vessels.len().max(1) as f64;
    let parts: usize = design.vessels.iter().map(|v| v.parts.len()).sum();
    let nozzles: usize = design.vessels.iter().map(|v| v.nozzles.len()).sum();
    let notes: usize = design.vessels.iter().map(|v| v.notes.len()).sum();
    outln!("{} at {tolerance} mm:", path.display());
    outln!(
        "  counts:            {} vessels, {parts} parts, {nozzles} nozzles, {notes} notes, {entities} entities",
        design.vessels.len()
    );
    outln!(
        "  memory per vessel: {:.0} KB measured heap ({:.0} KB of it meshes); {:.1} MB in all",
        heap as f64 / n / 1024.0,
        meshes as f64 / n / 1024.0,
        heap as f64 / 1e6
    );
    ExitCode::SUCCESS
}

/// Prints a vessel's operating figures (`vesselcad info`).
fn print_operating(v: &VesselReport) {
    match (&v.operating, &v.operating_problem) {
        (Some(o), _) => {
            outln!(
                "  liquid:           {:.3} m³ at level {:.0} mm (capacity {:.3} m³)",
                o.liquid_volume,
                o.liquid_level,
                o.interior_volume
            );
            let [x, y, z] = o.centre_of_gravity;
            outln!(
                "  weight empty:     {:.0} kg (all metal: walls {:.0} kg, supports, nozzles, flanges, pads {:.0} kg)",
                o.metal_mass,
                o.walls_mass,
                o.metal_mass - o.walls_mass
            );
            outln!(
                "  operating mass:   {:.0} kg, centre of gravity ({x:.0}, {y:.0}, {z:.0}) mm",
                o.operating_mass
            );
            outln!("  weight test:      {:.0} kg (full of water)", o.test_mass);
        }
        (None, Some(problem)) => outln!("  operating:        not computed: {problem}"),
        (None, None) => {}
    }
    let c = &v.calculation;
    match (c.mawp, &c.hydrotest) {
        (Some(m), Some(h)) => outln!(
            "  {}:      MAWP {:.0} kPa(g) at the top ({}), hydrotest {:.0} kPa(g); {} deficienc(ies)",
            c.code,
            m * 1e3,
            c.governing.as_deref().unwrap_or("—"),
            h.value * 1e3,
            c.deficiencies.len()
        ),
        _ => outln!(
            "  {}:      not calculated: {}",
            c.code,
            c.problems.first().map_or("—", String::as_str)
        ),
    }
    for d in &c.deficiencies {
        outln!("  deficiency:       {d}");
    }
}
