//! `vesselcad fem <design> --vessel TAG -o model.inp [--size mm] [--order 1|2]
//! [--case design|operating|test] [--quality] [--run]`: the shell finite-element model of
//! one vessel (see `vesselcad::fem`) as a CalculiX deck, with the same mesh as
//! Gmsh `.msh` and ParaView `.vtu` and a units side file beside it;
//! `--quality` prints the mesh quality per part with the cos(min angle)
//! histogram; `--run`
//! solves it with `ccx`, reports the stresses per part against the allowable
//! and writes the deformed shape with von Mises colours as `.glb`.

use std::path::{Path, PathBuf};
use std::process::ExitCode;

use clap::{Args, ValueEnum};
use vesselcad::calc::MaterialTable;
use vesselcad::design::load;
use vesselcad::fem::quality::quality;
use vesselcad::fem::results::{nodal, part_stresses, run_ccx};
use vesselcad::fem::{FemError, FemOptions, LoadCase, frd, glb, inp, msh, vessel_model, vtu};

use super::output::outln;

/// A load case on the command line.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum Case {
    /// Design pressure.
    Design,
    /// Design pressure, liquid at the operating level, weight.
    Operating,
    /// Hydrotest pressure, full of water, weight.
    Test,
}

/// Arguments of `vesselcad fem`.
#[derive(Args)]
pub struct FemArgs {
    /// The design file.
    design: PathBuf,
    /// The vessel to model.
    #[arg(long)]
    vessel: String,
    /// The CalculiX deck to write (`.inp`); `.msh`, `.vtu` and `.units.json`
    /// are written beside it.
    #[arg(short, long)]
    output: PathBuf,
    /// Target element size away from junctions, mm (default √(R·t)).
    #[arg(long)]
    size: Option<f64>,
    /// Element order: 1 (S4R) or 2 (S8R).
    #[arg(long, default_value_t = 2)]
    order: u8,
    /// Load case.
    #[arg(long, value_enum, default_value_t = Case::Design)]
    case: Case,
    /// Report the mesh quality per part (angles, scaled Jacobian, aspect,
    /// grading) and the cos(min angle) histogram.
    #[arg(long)]
    quality: bool,
    /// Run `ccx` on the deck, report the stresses per part and write the
    /// deformed shape with von Mises colours (`.glb`).
    #[arg(long)]
    run: bool,
}

/// Writes `text` to `path`.
fn write(path: &Path, text: &[u8]) -> Result<(), FemError> {
    std::fs::write(path, text).map_err(|source| FemError::Io {
        path: path.to_path_buf(),
        source,
    })
}

/// Runs `vesselcad fem`.
pub fn run(args: FemArgs) -> ExitCode {
    let design = match load(&args.design) {
        Ok(d) => d,
        Err(e) => return super::fail(&e),
    };
    let case = match args.case {
        Case::Design => LoadCase::Design,
        Case::Operating => LoadCase::Operating,
        Case::Test => LoadCase::Test,
    };
    let options = FemOptions {
        size: args.size,
        order: args.order,
    };
    let model = match vessel_model(
        &design,
        &args.vessel,
        &options,
        case,
        &MaterialTable::builtin(),
    ) {
        Ok(m) => m,
        Err(e) => {
            eprintln!("error: {e}");
            return ExitCode::from(1);
        }
    };
    match write_and_run(&args, &model) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {e}");
            match e {
                FemError::Io { .. } => ExitCode::from(2),
                _ => ExitCode::from(1),
            }
        }
    }
}

/// The units side file.
pub const UNITS: &str = "{\"format\": \"vesselcad-fem-units/1\", \"length\": \"mm\", \"force\": \"N\", \"stress\": \"MPa\", \"mass\": \"t\", \"density\": \"t/mm^3\", \"time\": \"s\", \"acceleration\": \"mm/s^2\"}\n";

/// Writes the deck and its companions, and runs the solver if asked.
fn write_and_run(args: &FemArgs, model: &vesselcad::fem::FeModel) -> Result<(), FemError> {
    let beside = |ext: &str| args.output.with_extension(ext);
    write(&args.output, inp::to_inp(model).as_bytes())?;
    write(&beside("msh"), msh::to_msh(&model.mesh).as_bytes())?;
    write(&beside("vtu"), vtu::to_vtu(&model.mesh, None).as_bytes())?;
    write(&beside("units.json"), UNITS.as_bytes())?;
    for note in &model.mesh.notes {
        outln!("note: {note}");
    }
    let q = quality(&model.mesh);
    outln!(
        "{}: {} nodes, {} elements ({} parts), case {}; supports: {}",
        args.output.display(),
        model.mesh.nodes.len(),
        model.mesh.elements.len(),
        model.mesh.parts.len(),
        model.case.name(),
        model.support_note
    );
    outln!(
        "quality: quad angles {:.1}-{:.1} deg, {:.1} % in 45-135, min scaled Jacobian {:.3}, {} inverted, {} free edges, {} coincident nodes, neighbour size ratio <= {:.2}",
        q.quad_angles.0,
        q.quad_angles.1,
        100.0 * q.quads_in_range as f64 / q.quads.max(1) as f64,
        q.min_scaled_jacobian,
        q.inverted,
        q.free_edges,
        q.coincident_nodes,
        q.max_size_ratio
    );
    if args.quality {
        for line in vesselcad::fem::quality_table::report(&model.mesh).lines() {
            outln!("{line}");
        }
    }
    if !args.run {
        return Ok(());
    }
    let frd_path = run_ccx(&args.output)?;
    let frd = frd::read(&frd_path)?;
    let results = nodal(model, &frd);
    write(
        &beside("vtu"),
        vtu::to_vtu(&model.mesh, Some(&results)).as_bytes(),
    )?;
    write(
        &beside("glb"),
        &glb::von_mises_glb(&model.mesh, &results, &model.tag),
    )?;
    let umax = results
        .iter()
        .map(|r| r.displacement.length())
        .fold(0.0, f64::max);
    outln!(
        "{}: largest displacement {umax:.4} mm; {} (deformed x{:.1}, von Mises colours)",
        frd_path.display(),
        beside("glb").display(),
        glb::magnification(&model.mesh, &results)
    );
    outln!(
        "part                 Pm max MPa   PL max MPa   Pm/PL+Pb max MPa   S MPa   check (Pm <= S, PL <= 1.5 S, +Pb <= 1.5 S)"
    );
    let cell = |v: Option<f64>| v.map_or("-".to_string(), |v| format!("{v:.2}"));
    for p in part_stresses(model, &results) {
        let verdict = match p.passes() {
            Some(true) => "ok",
            Some(false) => "EXCEEDS",
            None => "no allowable",
        };
        outln!(
            "{:<20} {:>10} {:>12} {:>18.2} {:>7} {verdict}",
            p.name,
            cell(p.membrane),
            cell(p.local),
            p.membrane_bending,
            p.allowable.map_or("-".to_string(), |s| format!("{s:.1}"))
        );
    }
    Ok(())
}
