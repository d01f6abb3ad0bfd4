//! Why a fabrication plan (BOM, weld map, operations) cannot be made: a shop
//! rule that names nothing, a precedence cycle, a vessel whose model cannot be
//! measured. Every variant names where the problem is.

use thiserror::Error;

/// A fabrication-plan failure.
#[derive(Debug, Error, Clone, PartialEq)]
pub enum PlanError {
    /// A shop-rules file cannot be read.
    #[error("{path}: {message}")]
    Io {
        /// The file.
        path: String,
        /// The system's message.
        message: String,
    },
    /// A value of a shop-rules file breaks a rule.
    #[error("{file}: {path} = {value:?}: {rule}")]
    Rule {
        /// The rules file.
        file: String,
        /// JSON path of the value.
        path: String,
        /// The value.
        value: String,
        /// What it must be.
        rule: String,
    },
    /// The precedence rules order operations in a cycle.
    #[error(
        "vessel {vessel}: the shop rules' precedence has a cycle: {}; no operation of a cycle can start",
        cycle.join(" → ")
    )]
    Cycle {
        /// Vessel tag.
        vessel: String,
        /// The operation ids of one cycle, the first repeated at the end.
        cycle: Vec<String>,
    },
    /// A part or nozzle of the vessel cannot be measured.
    #[error("vessel {vessel}, {entity}: {message}")]
    Model {
        /// Vessel tag.
        vessel: String,
        /// Part id or nozzle mark.
        entity: String,
        /// Why.
        message: String,
    },
}

impl PlanError {
    /// A [`PlanError::Rule`].
    pub fn rule(
        file: &str,
        path: impl Into<String>,
        value: impl Into<String>,
        rule: impl Into<String>,
    ) -> PlanError {
        PlanError::Rule {
            file: file.to_string(),
            path: path.into(),
            value: value.into(),
            rule: rule.into(),
        }
    }
}
