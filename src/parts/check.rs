//! Parameter checks shared by the part builders: each returns the value or a
//! [`PartError::InvalidParameter`] naming part, field, value and rule.

use super::PartError;

/// Smallest dimension a part accepts, mm (a micrometre).
pub const MIN_DIMENSION: f64 = 1e-3;
/// Largest dimension a part accepts, mm (a kilometre).
pub const MAX_DIMENSION: f64 = 1e6;

/// A dimension that must lie in [`MIN_DIMENSION`, `MAX_DIMENSION`].
pub(crate) fn positive(
    part: &'static str,
    field: &'static str,
    value: f64,
) -> Result<f64, PartError> {
    if (MIN_DIMENSION..=MAX_DIMENSION).contains(&value) {
        Ok(value)
    } else {
        Err(invalid(
            part,
            field,
            value,
            format!("must be a finite number between {MIN_DIMENSION} and {MAX_DIMENSION} mm"),
        ))
    }
}

/// A dimension that is 0 (absent) or lies in [`MIN_DIMENSION`, `MAX_DIMENSION`].
pub(crate) fn non_negative(
    part: &'static str,
    field: &'static str,
    value: f64,
) -> Result<f64, PartError> {
    if value == 0.0 || (MIN_DIMENSION..=MAX_DIMENSION).contains(&value) {
        Ok(value)
    } else {
        Err(invalid(
            part,
            field,
            value,
            format!("must be 0 or a finite number between {MIN_DIMENSION} and {MAX_DIMENSION} mm"),
        ))
    }
}

/// A value in the open or closed range `[low, high]` (`open` excludes both ends).
pub(crate) fn in_range(
    part: &'static str,
    field: &'static str,
    value: f64,
    low: f64,
    high: f64,
    open: bool,
) -> Result<f64, PartError> {
    let ok = value.is_finite()
        && if open {
            value > low && value < high
        } else {
            value >= low && value <= high
        };
    if ok {
        Ok(value)
    } else if open {
        Err(invalid(
            part,
            field,
            value,
            format!("must lie strictly between {low} and {high}"),
        ))
    } else {
        Err(invalid(
            part,
            field,
            value,
            format!("must lie between {low} and {high}"),
        ))
    }
}

/// `value < limit`, where the limit comes from another parameter named in the rule.
pub(crate) fn less_than(
    part: &'static str,
    field: &'static str,
    value: f64,
    limit: f64,
    limit_name: &str,
) -> Result<f64, PartError> {
    if value < limit {
        Ok(value)
    } else {
        Err(invalid(
            part,
            field,
            value,
            format!("must be smaller than {limit_name} ({limit})"),
        ))
    }
}

/// Builds an [`PartError::InvalidParameter`].
pub(crate) fn invalid(
    part: &'static str,
    field: &'static str,
    value: f64,
    rule: impl Into<String>,
) -> PartError {
    PartError::InvalidParameter {
        part,
        field,
        value,
        rule: rule.into(),
    }
}
