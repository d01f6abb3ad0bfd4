//! `vesselcad build` of large designs: the chunked build with a progress bar and
//! the streaming GLB writer; `vesselcad info --memory`: the measured memory of a
//! built model per vessel.

use std::path::Path;
use std::process::ExitCode;

use vesselcad::design::Design;
use vesselcad::mesh::TessellationOptions;
use vesselcad::model::{Model, ModelError};
use vesselcad::plant::build_plant;

use super::alloc::live_bytes;
use super::progress::bar;

/// Builds `design` with a progress bar on a terminal.
///
/// # Errors
///
/// As [`build_plant`].
pub fn build_with_progress(
    design: &Design,
    options: TessellationOptions,
) -> Result<Model, ModelError> {
    let progress = bar(design.vessels.len(), "building");
    let model = build_plant(design, options, &mut |done, _| {
        progress.set_position(done as u64)
    });
    progress.finish_and_clear();
    model
}

/// Prints the counts of a built plant and its measured memory per vessel.
pub fn print_memory(design: &Design, path: &Path, tolerance: f64) -> ExitCode {
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
    println!("{} at {tolerance} mm:", path.display());
    println!(
        "  counts:            {} vessels, {parts} parts, {nozzles} nozzles, {notes} notes, {entities} entities",
        design.vessels.len()
    );
    println!(
        "  memory per vessel: {:.0} KB measured heap ({:.0} KB of it meshes); {:.1} MB in all",
        heap as f64 / n / 1024.0,
        meshes as f64 / n / 1024.0,
        heap as f64 / 1e6
    );
    ExitCode::SUCCESS
}

/// Prints a vessel's operating figures (`vesselcad info`).
pub fn print_operating(v: &vesselcad::report::VesselReport) {
    match (&v.operating, &v.operating_problem) {
        (Some(o), _) => {
            println!(
                "  liquid:           {:.3} m³ at level {:.0} mm (capacity {:.3} m³)",
                o.liquid_volume, o.liquid_level, o.interior_volume
            );
            let [x, y, z] = o.centre_of_gravity;
            println!(
                "  weight empty:     {:.0} kg (all metal: walls {:.0} kg, supports, nozzles, flanges, pads {:.0} kg)",
                o.metal_mass,
                o.walls_mass,
                o.metal_mass - o.walls_mass
            );
            println!(
                "  operating mass:   {:.0} kg, centre of gravity ({x:.0}, {y:.0}, {z:.0}) mm",
                o.operating_mass
            );
            println!("  weight test:      {:.0} kg (full of water)", o.test_mass);
        }
        (None, Some(problem)) => println!("  operating:        not computed: {problem}"),
        (None, None) => {}
    }
    let c = &v.calculation;
    match (c.mawp, &c.hydrotest) {
        (Some(m), Some(h)) => println!(
            "  {}:      MAWP {:.0} kPa(g) at the top ({}), hydrotest {:.0} kPa(g); {} deficienc(ies)",
            c.code,
            m * 1e3,
            c.governing.as_deref().unwrap_or("—"),
            h.value * 1e3,
            c.deficiencies.len()
        ),
        _ => println!(
            "  {}:      not calculated: {}",
            c.code,
            c.problems.first().map_or("—", String::as_str)
        ),
    }
    for d in &c.deficiencies {
        println!("  deficiency:       {d}");
    }
}
