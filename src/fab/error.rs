//! The one error type of fabrication planning.

use std::path::PathBuf;

use crate::format::RuleViolation;

/// Why a fabrication plan cannot be made or written.
#[derive(Debug, thiserror::Error)]
pub enum FabError {
    /// A file could not be read or written.
    #[error("{path}: {source}")]
    Io {
        /// The file.
        path: PathBuf,
        /// The cause.
        source: std::io::Error,
    },
    /// A shop data value is bad.
    #[error("{file}: {field} = {value}: {rule}")]
    Shop {
        /// The shop file (`data/shop.json` for the built-in one).
        file: String,
        /// The field.
        field: String,
        /// The value as read.
        value: String,
        /// The rule it breaks.
        rule: String,
    },
    /// The design has no vessel of this tag.
    #[error("no vessel tagged {tag:?} in the design")]
    UnknownVessel {
        /// The tag asked for.
        tag: String,
    },
    /// The vessel breaks rules of the design or of fabrication (a part
    /// without thickness, an opening across a seam, overlapping openings, a
    /// pad over a seam, …): every broken rule, each naming path, entity, field,
    /// value and rule (the rule names the other entity where there is one).
    #[error("{}", list(.0))]
    Rules(Vec<RuleViolation>),
    /// The process plan cannot be made (a shop rule, a cycle, a model
    /// measure).
    #[error(transparent)]
    Plan(#[from] super::plan_error::PlanError),
    /// A DXF file could not be written.
    #[error("{path}: cannot write DXF: {message}")]
    Dxf {
        /// The file.
        path: PathBuf,
        /// The writer's message.
        message: String,
    },
}

fn list(violations: &[RuleViolation]) -> String {
    violations
        .iter()
        .map(ToString::to_string)
        .collect::<Vec<_>>()
        .join("\n")
}
