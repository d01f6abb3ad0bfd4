//! `vesselcad fab <design> --vessel TAG -o out/ [--rules shop_rules.json]`:
//! the fabrication files of one vessel (see `vesselcad::fab`): the process
//! plan — traveler (HTML, CSV), BOM, weld map (CSV, JSON, GLB, SVG) — written
//! into the output directory, with a summary printed.

use std::path::PathBuf;
use std::process::ExitCode;

use clap::Args;
use vesselcad::design::{load, resolve};
use vesselcad::fab::process_files::write_process_files;
use vesselcad::fab::{PlanError, ShopRules, process_plan};

use super::output::outln;

/// Arguments of `vesselcad fab`.
#[derive(Args)]
pub struct FabArgs {
    /// The design file.
    design: PathBuf,
    /// The vessel to plan.
    #[arg(long)]
    vessel: String,
    /// The output directory (created if missing).
    #[arg(short, long)]
    output: PathBuf,
    /// Shop rules (operations, precedence, weld preparations, PWHT) replacing
    /// the built-in `data/shop_rules.json`.
    #[arg(long)]
    rules: Option<PathBuf>,
}

fn fail(error: &PlanError) -> ExitCode {
    eprintln!("error: {error}");
    ExitCode::from(match error {
        PlanError::Io { .. } => 2,
        _ => 1,
    })
}

/// Runs `vesselcad fab`.
pub fn run(args: FabArgs) -> ExitCode {
    let design = match load(&args.design) {
        Ok(d) => d,
        Err(e) => return super::fail(&e),
    };
    let rules = match &args.rules {
        Some(path) => match ShopRules::from_path(path) {
            Ok(r) => r,
            Err(e) => return fail(&e),
        },
        None => ShopRules::builtin(),
    };
    let Some(index) = design.vessels.iter().position(|v| v.tag == args.vessel) else {
        let known: Vec<&str> = design.vessels.iter().map(|v| v.tag.as_str()).collect();
        eprintln!(
            "error: --vessel {}: no such vessel; the design has {}",
            args.vessel,
            known.join(", ")
        );
        return ExitCode::from(1);
    };
    let resolved = match resolve(&design) {
        Ok(r) => r,
        Err(e) => return super::fail(&e),
    };
    let (vessel, resolved) = (&design.vessels[index], &resolved[index]);
    let plan = match process_plan(vessel, resolved, &rules) {
        Ok(p) => p,
        Err(e) => return fail(&e),
    };
    let source = args.design.display().to_string();
    let written = match write_process_files(&plan, resolved.frame, &source, &args.output) {
        Ok(w) => w,
        Err(e) => return fail(&e),
    };
    outln!(
        "{}: {} BOM lines, {:.1} kg; {} welds, {:.1} m; {} operations in {} levels; PWHT {}",
        plan.vessel,
        plan.bom.lines.len(),
        plan.bom.total_mass,
        plan.welds.len(),
        plan.welds.iter().map(|w| w.length).sum::<f64>() * 1e-3,
        plan.operations.len(),
        plan.level_count(),
        if plan.pwht.required {
            "required"
        } else {
            "not required"
        }
    );
    for path in written {
        outln!("  wrote {}", path.display());
    }
    ExitCode::SUCCESS
}
