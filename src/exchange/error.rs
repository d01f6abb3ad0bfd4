//! Why an exchange file could not be written: the design, a part, an opening,
//! a trim the B-rep builder does not handle, or I/O.

use thiserror::Error;

use crate::design::DesignError;
use crate::nurbs::NurbsError;
use crate::parts::PartError;

/// Why an exchange export failed.
#[derive(Debug, Error)]
pub enum ExchangeError {
    /// The design breaks its rules; every violation is listed.
    #[error("invalid design: {0}")]
    Design(#[from] DesignError),
    /// `--vessel` named a tag the design does not hold.
    #[error("vessels: no vessel tagged {tag:?} in the design")]
    UnknownVessel {
        /// The tag asked for.
        tag: String,
    },
    /// The exchange options are out of range.
    #[error("exchange options: {field} = {value} {rule}")]
    Options {
        /// The option.
        field: &'static str,
        /// Its value.
        value: f64,
        /// The rule it breaks.
        rule: &'static str,
    },
    /// A part or nozzle could not build its patches.
    #[error("{entity}: cannot build patches: {source}")]
    Part {
        /// Stable id, `tag/id`.
        entity: String,
        /// The part builder's error.
        source: PartError,
    },
    /// A nozzle's (or boot's) opening could not be cut.
    #[error("{entity}: cannot cut the opening: {message}")]
    Opening {
        /// Stable id of the nozzle or boot, `tag/id`.
        entity: String,
        /// What went wrong.
        message: String,
    },
    /// A patch's boundary could not be made into B-rep topology.
    #[error("{entity}/{patch}: cannot bound the face: {rule}")]
    Topology {
        /// Stable id of the part or nozzle, `tag/id`.
        entity: String,
        /// Patch name.
        patch: String,
        /// What is not handled.
        rule: String,
    },
    /// A surface or curve could not be transformed or split.
    #[error("{entity}: {source}")]
    Geometry {
        /// Stable id of the part or nozzle, `tag/id`.
        entity: String,
        /// The kernel's error.
        source: NurbsError,
    },
    /// Writing the file failed.
    #[error("cannot write {path}: {source}")]
    Io {
        /// The file.
        path: String,
        /// The I/O error.
        source: std::io::Error,
    },
}
