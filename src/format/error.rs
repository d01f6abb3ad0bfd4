//! Errors of loading, checking and editing designs.
//!
//! A [`RuleViolation`] names the exact JSON path, the entity (`V-101/N3`), the
//! field, the offending value and the rule; a [`DesignError`] is either a file that
//! could not be read as a design at all, or the full list of rule violations.

use std::fmt;

use thiserror::Error;

/// One broken rule in a design or an edit.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct RuleViolation {
    /// JSON path of the value, e.g. `vessels[0].nozzles[3].rating`.
    pub path: String,
    /// The entity's stable id, e.g. `V-101/N3` (or `V-101` for the vessel).
    pub entity: String,
    /// The field, e.g. `rating`.
    pub field: String,
    /// The offending value as written, e.g. `175`.
    pub value: String,
    /// The rule, e.g. `expected one of 150, 300, 600, 900`.
    pub rule: String,
}

impl fmt::Display for RuleViolation {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "{}: {} (entity {}, {} = {})",
            self.path, self.rule, self.entity, self.field, self.value
        )
    }
}

/// Why a design could not be loaded or an edit was rejected.
#[derive(Debug, Error)]
pub enum DesignError {
    /// The file could not be read.
    #[error("cannot read {path}: {source}")]
    Io {
        /// The file.
        path: String,
        /// The I/O error.
        source: std::io::Error,
    },
    /// Malformed JSON, a wrong type, an unknown field or enumeration value.
    #[error("{path}: {message}")]
    Syntax {
        /// JSON path where parsing failed (`.` for the document).
        path: String,
        /// What was expected and found, with line and column.
        message: String,
    },
    /// The `format` tag is not one this version reads.
    #[error("format: expected \"{expected}\", got \"{found}\"")]
    Format {
        /// What the file says.
        found: String,
        /// What this version reads.
        expected: &'static str,
    },
    /// The design parsed but breaks one or more rules; every violation is listed.
    #[error("{} problem(s):\n{}", .0.len(), .0.iter().map(|v| format!("  - {v}")).collect::<Vec<_>>().join("\n"))]
    Invalid(Vec<RuleViolation>),
}

impl DesignError {
    /// The rule violations, if this is [`DesignError::Invalid`].
    pub fn violations(&self) -> &[RuleViolation] {
        match self {
            DesignError::Invalid(v) => v,
            _ => &[],
        }
    }
}
