//! Errors of the calculations: bad inputs, geometry outside a formula's scope,
//! unknown materials and unreadable material tables.

use thiserror::Error;

/// Why a calculation could not be made.
#[derive(Clone, Debug, PartialEq, Error)]
pub enum CalcError {
    /// An input value breaks a rule (not finite, not positive, out of range).
    #[error("{entity}: {field} = {value}: {rule}")]
    Input {
        /// What the value belongs to, e.g. `cylinder` or `SA-516-70`.
        entity: String,
        /// The input, e.g. `inside_radius`.
        field: String,
        /// The offending value.
        value: f64,
        /// The rule it breaks.
        rule: String,
    },
    /// The formula's code paragraph does not cover these proportions.
    #[error("{paragraph}: {rule}")]
    OutOfScope {
        /// The paragraph whose limit is exceeded, e.g. `UG-27(c)(1)`.
        paragraph: &'static str,
        /// The limit and the values that exceed it.
        rule: String,
    },
    /// No material of that name in the table.
    #[error("unknown material \"{name}\"; the table has: {known}")]
    UnknownMaterial {
        /// The name asked for.
        name: String,
        /// The table's names.
        known: String,
    },
    /// A materials table could not be read or broke a rule of its format.
    #[error("materials table {path}: {message}")]
    Table {
        /// The table's path.
        path: String,
        /// What is wrong, with the JSON path.
        message: String,
    },
}

/// `Ok(value)` when finite and > 0, else an [`CalcError::Input`].
pub(crate) fn positive(entity: &str, field: &str, value: f64) -> Result<f64, CalcError> {
    if value.is_finite() && value > 0.0 {
        Ok(value)
    } else {
        Err(CalcError::Input {
            entity: entity.into(),
            field: field.into(),
            value,
            rule: "must be finite and greater than 0".into(),
        })
    }
}

/// `Ok(value)` when finite and ≥ 0, else an [`CalcError::Input`].
pub(crate) fn non_negative(entity: &str, field: &str, value: f64) -> Result<f64, CalcError> {
    if value.is_finite() && value >= 0.0 {
        Ok(value)
    } else {
        Err(CalcError::Input {
            entity: entity.into(),
            field: field.into(),
            value,
            rule: "must be finite and at least 0".into(),
        })
    }
}
