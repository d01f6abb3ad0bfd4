//! Why a scan could not be read, simulated, registered or fitted.

use std::path::{Path, PathBuf};

use thiserror::Error;

use crate::design::DesignError;
use crate::parts::PartError;

/// Why a scan operation failed.
#[derive(Debug, Error)]
pub enum ScanError {
    /// The design breaks its rules; every violation is listed.
    #[error("invalid design: {0}")]
    Design(#[from] DesignError),
    /// `--vessel` named a tag the design does not hold.
    #[error("vessels: no vessel tagged {tag:?} in the design")]
    UnknownVessel {
        /// The tag asked for.
        tag: String,
    },
    /// A part or nozzle could not build its patches.
    #[error("{entity}: cannot build patches: {source}")]
    Part {
        /// Stable id, `tag/id`.
        entity: String,
        /// The part builder's error.
        source: PartError,
    },
    /// A file could not be read or written.
    #[error("{path}: {source}")]
    Io {
        /// The file.
        path: PathBuf,
        /// The I/O error.
        source: std::io::Error,
    },
    /// A points file is malformed: the file, the line (or byte offset for binary
    /// PLY), what was wrong.
    #[error("{path}:{line}: {message}")]
    Points {
        /// The file.
        path: PathBuf,
        /// 1-based line of a text file, or the byte offset in binary data.
        line: u64,
        /// What is wrong there.
        message: String,
    },
    /// A defect specification (`--defects`) is malformed or names something the
    /// vessel does not have: the item, the field, its value and the rule.
    #[error("--defects {item:?}: {field} = {value:?} {rule}")]
    Defect {
        /// The comma-separated item as written.
        item: String,
        /// The field of the item (`ovality`, `@course`, `size`...).
        field: String,
        /// The value found.
        value: String,
        /// The rule it breaks.
        rule: String,
    },
    /// A numeric option is out of range.
    #[error("{field} = {value} {rule}")]
    Options {
        /// The option.
        field: &'static str,
        /// Its value.
        value: f64,
        /// The rule it breaks.
        rule: &'static str,
    },
    /// A text option names something not supported: the option, its value and
    /// the rule.
    #[error("{option} {value:?}: {rule}")]
    Unsupported {
        /// The option.
        option: &'static str,
        /// Its value.
        value: String,
        /// The rule it breaks.
        rule: &'static str,
    },
    /// An output path names one of the inputs (or another output): writing it
    /// would overwrite that file.
    #[error("{option} {path}: is the {other} as well; refusing to overwrite it")]
    SameFile {
        /// The output option (`-o`, `--json`, `--glb`).
        option: &'static str,
        /// The path given.
        path: PathBuf,
        /// What else that path is (`design file`, `scan`, `HTML report`...).
        other: &'static str,
    },
    /// Too few points to do what was asked (register, fit a part).
    #[error("{what}: {found} points, at least {needed} needed")]
    TooFewPoints {
        /// What needed them.
        what: String,
        /// Points found.
        found: usize,
        /// Points needed.
        needed: usize,
    },
    /// A least-squares or interpolation system is singular: the data break the
    /// Schoenberg–Whitney condition (a basis function without data) or the
    /// normal matrix is not positive definite.
    #[error("{what}: {rule}")]
    Singular {
        /// The system (part, patch).
        what: String,
        /// The condition that failed.
        rule: String,
    },
    /// The fitted surfaces could not be made a B-rep for STEP.
    #[error("{entity}: cannot write the fitted surfaces: {source}")]
    Exchange {
        /// The model, `<tag> as-built`.
        entity: String,
        /// The exchange pipeline's error.
        source: Box<crate::exchange::ExchangeError>,
    },
}

impl ScanError {
    /// An I/O error on `path`.
    pub fn io(path: &std::path::Path, source: std::io::Error) -> Self {
        ScanError::Io {
            path: path.to_path_buf(),
            source,
        }
    }
}

/// A point file's error at `line` (0 when not line-based).
pub(super) fn bad(path: &Path, line: u64, message: impl Into<String>) -> ScanError {
    ScanError::Points {
        path: path.to_path_buf(),
        line,
        message: message.into(),
    }
}
