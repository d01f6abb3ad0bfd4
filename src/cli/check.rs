//! `vesselcad check`: whether a design is valid, every problem listed otherwise.
//!
//! A design that passes every rule is then built (at `--tolerance`, unless
//! `--rules-only`): a part or nozzle whose geometry cannot be built makes it
//! invalid too, reported as what it is — a build failure naming the design
//! path, the stable id, the stage that failed and the typed cause — never as a
//! broken rule.
//!
//! `check --json` prints one object on standard output, whatever the outcome:
//!
//! ```text
//! {"format": "vesselcad-check/1", "file": "...", "valid": true, "vessels": 3,
//!  "built": true, "deficiencies": [{"vessel", "deficiency"}]}
//! {"format": "vesselcad-check/1", "file": "...", "valid": false, "kind": "invalid",
//!  "error": "<message>", "violations": [{"path", "entity", "field", "value", "rule"}]}
//! {"format": "vesselcad-check/1", "file": "...", "valid": false, "kind": "geometry",
//!  "error": "<message>", "failures": [{"path", "entity", "stage", "patch", "cause"}]}
//! ```
//!
//! with the same exit codes as `check`: 0 valid, 1 invalid or unbuildable (or,
//! with `--strict`, deficient), 2 unreadable or bad options.

use std::path::{Path, PathBuf};
use std::process::ExitCode;

use clap::Args;
use serde_json::{Value, json};
use vesselcad::design::{Design, DesignError, load};
use vesselcad::mesh::{
    DEFAULT_VERTEX_BUDGET, MAX_VERTEX_BUDGET, MIN_VERTEX_BUDGET, TessellationOptions,
};
use vesselcad::model::{BuildFailure, ModelError};
use vesselcad::plant::build_plant;

use super::output::outln;
use super::{fail, model_error};

/// The format tag of `check --json`.
pub const CHECK_FORMAT: &str = "vesselcad-check/1";

/// Arguments of `vesselcad check`.
#[derive(Args)]
pub struct CheckArgs {
    /// The design file.
    design: PathBuf,
    /// Print the result as JSON (`vesselcad-check/1`) on standard output.
    #[arg(long)]
    json: bool,
    /// Also exit 1 when a part or nozzle is thinner than the code requires.
    #[arg(long)]
    strict: bool,
    /// Chordal tolerance the geometry is built to, mm.
    #[arg(long, default_value_t = TessellationOptions::DEFAULT.tolerance, allow_negative_numbers = true)]
    tolerance: f64,
    /// Most vertices the mesher may give one patch (1000 to 4294967295): a
    /// patch that needs more is refused, naming it, instead of taking the
    /// memory and time it would need.
    #[arg(long, value_name = "N", default_value_t = DEFAULT_VERTEX_BUDGET as u64,
          value_parser = clap::value_parser!(u64).range(MIN_VERTEX_BUDGET as u64..=MAX_VERTEX_BUDGET as u64))]
    max_vertices: u64,
    /// Check the design rules only: do not build the geometry.
    #[arg(long)]
    rules_only: bool,
}

/// Why a design that passes every rule is still not valid.
enum Unbuilt {
    /// Parts or nozzles whose geometry cannot be built.
    Geometry(Vec<BuildFailure>),
    /// Bad options, or another refusal of the model (exit 2).
    Other(ModelError),
}

/// Builds `design` unless `args` say rules only.
fn build(design: &Design, args: &CheckArgs) -> Result<(), Unbuilt> {
    if args.rules_only {
        return Ok(());
    }
    let options =
        TessellationOptions::chord(args.tolerance).with_max_vertices(args.max_vertices as usize);
    match build_plant(design, options, &mut |_, _| {}) {
        Ok(_) => Ok(()),
        Err(ModelError::Geometry(failures)) => Err(Unbuilt::Geometry(failures)),
        Err(e) => Err(Unbuilt::Other(e)),
    }
}

/// The message of a design that passes every rule but cannot be built.
fn unbuildable(failures: &[BuildFailure], tolerance: f64) -> String {
    format!(
        "every rule holds, but the geometry cannot be built at {tolerance} mm: {} failure(s):\n{}",
        failures.len(),
        failures
            .iter()
            .map(|f| format!("  - {f}"))
            .collect::<Vec<_>>()
            .join("\n")
    )
}

/// Runs `vesselcad check`: exit 0 when valid, 1 when invalid or unbuildable,
/// 2 when unreadable.
pub fn run(args: CheckArgs) -> ExitCode {
    if args.json {
        return check_json(&args);
    }
    let d = match load(&args.design) {
        Ok(d) => d,
        Err(e) => return fail(&e),
    };
    match build(&d, &args) {
        Ok(()) => {
            outln!(
                "{}: valid ({} vessel(s){})",
                args.design.display(),
                d.vessels.len(),
                if args.rules_only {
                    String::from(", rules only")
                } else {
                    format!(", built at {} mm", args.tolerance)
                }
            );
            print_deficiencies(&d, args.strict)
        }
        Err(Unbuilt::Geometry(failures)) => {
            eprintln!(
                "error: {}: {}",
                args.design.display(),
                unbuildable(&failures, args.tolerance)
            );
            ExitCode::from(1)
        }
        Err(Unbuilt::Other(e)) => {
            eprintln!("error: {}: {}", args.design.display(), model_error(&e));
            ExitCode::from(2)
        }
    }
}

/// Prints the deficiencies of a valid design (parts or nozzles thinner than the
/// code requires, see `vesselcad calc`) as warnings; exit 1 under `strict` when
/// there is one, else 0.
fn print_deficiencies(design: &Design, strict: bool) -> ExitCode {
    let found = super::calc::deficiencies(design);
    for (tag, d) in &found {
        outln!("deficiency: {tag}/{d}");
    }
    if strict && !found.is_empty() {
        ExitCode::from(1)
    } else {
        ExitCode::SUCCESS
    }
}

/// Runs `check --json`; with `--strict`, a deficiency makes it exit 1.
fn check_json(args: &CheckArgs) -> ExitCode {
    let (path, strict): (&Path, bool) = (&args.design, args.strict);
    let file = path.display().to_string();
    let loaded = load(path).map(|design| {
        let built = build(&design, args);
        (design, built)
    });
    let (report, code) = match loaded {
        Ok((_, Err(Unbuilt::Geometry(failures)))) => (
            json!({
                "format": CHECK_FORMAT,
                "file": file,
                "valid": false,
                "kind": "geometry",
                "error": unbuildable(&failures, args.tolerance),
                "failures": failures.iter().map(BuildFailure::to_json).collect::<Vec<_>>(),
            }),
            ExitCode::from(1),
        ),
        Ok((_, Err(Unbuilt::Other(e)))) => (
            json!({
                "format": CHECK_FORMAT,
                "file": file,
                "valid": false,
                "kind": "options",
                "error": model_error(&e),
            }),
            ExitCode::from(2),
        ),
        Ok((design, Ok(()))) => {
            let found = super::calc::deficiencies(&design);
            let code = if strict && !found.is_empty() {
                ExitCode::from(1)
            } else {
                ExitCode::SUCCESS
            };
            let found: Vec<Value> = found
                .into_iter()
                .map(|(vessel, text)| json!({"vessel": vessel, "deficiency": text}))
                .collect();
            (
                json!({
                    "format": CHECK_FORMAT,
                    "file": file,
                    "valid": true,
                    "vessels": design.vessels.len(),
                    "built": !args.rules_only,
                    "deficiencies": found,
                }),
                code,
            )
        }
        Err(e) => {
            let (kind, code) = match &e {
                DesignError::Io { .. } => ("unreadable", ExitCode::from(2)),
                DesignError::Syntax { .. } => ("syntax", ExitCode::from(1)),
                DesignError::Format { .. } => ("format", ExitCode::from(1)),
                DesignError::Invalid(_) => ("invalid", ExitCode::from(1)),
            };
            let violations: Vec<Value> = e
                .violations()
                .iter()
                .map(|v| {
                    json!({
                        "path": v.path, "entity": v.entity, "field": v.field,
                        "value": v.value, "rule": v.rule,
                    })
                })
                .collect();
            let mut report = json!({
                "format": CHECK_FORMAT,
                "file": file,
                "valid": false,
                "kind": kind,
                "error": e.to_string(),
            });
            if let DesignError::Syntax { path, .. } = &e {
                report["path"] = json!(path);
            }
            if !violations.is_empty() {
                report["violations"] = json!(violations);
            }
            (report, code)
        }
    };
    outln!(
        "{}",
        serde_json::to_string_pretty(&report).unwrap_or_default()
    );
    code
}
