//! Why a finite-element model cannot be made, written or read: each error names
//! the vessel, part or file and the value that broke the rule.

use std::path::PathBuf;

use thiserror::Error;

/// A finite-element model error.
#[derive(Debug, Error)]
pub enum FemError {
    /// The design has no vessel of that tag.
    #[error("no vessel tagged {tag:?} in the design (vessels: {known})")]
    NoVessel {
        /// The tag asked for.
        tag: String,
        /// The tags the design has.
        known: String,
    },
    /// A pressure part gives no wall thickness: a shell section needs one.
    #[error(
        "vessels[{vessel}].parts[{index}] ({id}): thickness is not given; a shell section needs the wall thickness"
    )]
    NoThickness {
        /// Vessel tag.
        vessel: String,
        /// Index of the part in the design.
        index: usize,
        /// Part id.
        id: String,
    },
    /// The mid-surface profile cannot be made (a wall too thick for its part).
    #[error("vessel {vessel}: {message}")]
    Profile {
        /// Vessel tag.
        vessel: String,
        /// What the profile builder said.
        message: String,
    },
    /// The vessel has no pressure envelope (no course, reducer or head).
    #[error("vessel {vessel}: no course, reducer or head to mesh")]
    Empty {
        /// Vessel tag.
        vessel: String,
    },
    /// An option out of its range.
    #[error("{field} = {value}: {rule}")]
    Option {
        /// The option.
        field: &'static str,
        /// Its value.
        value: String,
        /// The rule it breaks.
        rule: String,
    },
    /// A load case needs a design field that is missing or out of range.
    #[error("vessels[{vessel}].{path} = {value}: {rule}")]
    Conditions {
        /// Vessel tag.
        vessel: String,
        /// JSON path inside the vessel.
        path: String,
        /// The value (or `missing`).
        value: String,
        /// The rule.
        rule: String,
    },
    /// A file could not be read or written.
    #[error("{path}: {source}")]
    Io {
        /// The file.
        path: PathBuf,
        /// The I/O error.
        source: std::io::Error,
    },
    /// A results file does not read as CalculiX `.frd`.
    #[error("{path}: line {line}: {message}")]
    Frd {
        /// The file.
        path: PathBuf,
        /// 1-based line number.
        line: usize,
        /// What is wrong.
        message: String,
    },
    /// The solver failed.
    #[error("ccx: {0}")]
    Solver(String),
}
