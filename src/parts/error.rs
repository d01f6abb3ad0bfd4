//! The error every part builder returns for impossible parameters.

use thiserror::Error;

use super::tables::TableError;
use crate::nurbs::NurbsError;

/// Why a part could not be built.
#[derive(Debug, Error, Clone, PartialEq)]
pub enum PartError {
    /// A parameter is out of range (negative, NaN, too large for another parameter…).
    #[error("{part}.{field} = {value}: {rule}")]
    InvalidParameter {
        /// The part kind, e.g. `"torispherical head"`.
        part: &'static str,
        /// The parameter, e.g. `"knuckle_radius"`.
        field: &'static str,
        /// Its value in mm or degrees.
        value: f64,
        /// The rule it breaks, with the limit it was compared with.
        rule: String,
    },
    /// The kernel rejected a construction (a bug if parameters were validated).
    #[error("geometry kernel: {0}")]
    Kernel(#[from] NurbsError),
    /// A size, schedule or class that the ASME tables do not list.
    #[error("{0}")]
    Table(#[from] TableError),
}
