//! `vesselcad check`: whether a design is valid, every problem listed otherwise.
//!
//! `check --json` prints one object on standard output, whatever the outcome:
//!
//! ```text
//! {"format": "vesselcad-check/1", "file": "...", "valid": true, "vessels": 3,
//!  "deficiencies": [{"vessel", "deficiency"}]}
//! {"format": "vesselcad-check/1", "file": "...", "valid": false, "kind": "invalid",
//!  "error": "<message>", "violations": [{"path", "entity", "field", "value", "rule"}]}
//! ```
//!
//! with the same exit codes as `check`: 0 valid, 1 invalid (or, with `--strict`,
//! deficient), 2 unreadable.

use std::path::{Path, PathBuf};
use std::process::ExitCode;

use clap::Args;
use serde_json::{Value, json};
use vesselcad::design::{Design, DesignError, load};

use super::fail;
use super::output::outln;

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
}

/// Runs `vesselcad check`: exit 0 when valid, 1 when invalid, 2 when unreadable.
pub fn run(args: CheckArgs) -> ExitCode {
    if args.json {
        return check_json(&args.design, args.strict);
    }
    match load(&args.design) {
        Ok(d) => {
            outln!(
                "{}: valid ({} vessel(s))",
                args.design.display(),
                d.vessels.len()
            );
            print_deficiencies(&d, args.strict)
        }
        Err(e) => fail(&e),
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

/// Runs `check --json` on `path`; with `strict`, a deficiency makes it exit 1.
fn check_json(path: &Path, strict: bool) -> ExitCode {
    let file = path.display().to_string();
    let (report, code) = match load(path) {
        Ok(design) => {
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
