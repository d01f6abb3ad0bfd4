//! `vesselcad check`: whether a design is valid, every problem listed otherwise.
//!
//! `check --json` prints one object on standard output, whatever the outcome:
//!
//! ```text
//! {"format": "vesselcad-check/1", "file": "...", "valid": true, "vessels": 3}
//! {"format": "vesselcad-check/1", "file": "...", "valid": false, "kind": "invalid",
//!  "error": "<message>", "violations": [{"path", "entity", "field", "value", "rule"}]}
//! ```
//!
//! with the same exit codes as `check`: 0 valid, 1 invalid, 2 unreadable.

use std::path::{Path, PathBuf};
use std::process::ExitCode;

use clap::Args;
use serde_json::{Value, json};
use vesselcad::design::{DesignError, load};

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
}

/// Runs `vesselcad check`: exit 0 when valid, 1 when invalid, 2 when unreadable.
pub fn run(args: CheckArgs) -> ExitCode {
    if args.json {
        return check_json(&args.design);
    }
    match load(&args.design) {
        Ok(d) => {
            outln!(
                "{}: valid ({} vessel(s))",
                args.design.display(),
                d.vessels.len()
            );
            ExitCode::SUCCESS
        }
        Err(e) => fail(&e),
    }
}

/// Runs `check --json` on `path`.
fn check_json(path: &Path) -> ExitCode {
    let file = path.display().to_string();
    let (report, code) = match load(path) {
        Ok(design) => (
            json!({
                "format": CHECK_FORMAT,
                "file": file,
                "valid": true,
                "vessels": design.vessels.len(),
            }),
            ExitCode::SUCCESS,
        ),
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
