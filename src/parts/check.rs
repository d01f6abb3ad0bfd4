//! Parameter checks shared by the part builders: each returns the value or a
//! [`PartError::InvalidParameter`] naming part, field, value and rule.

use super::PartError;

/// A dimension that must be finite and > 0.
pub(crate) fn positive(
    part: &'static str,
    field: &'static str,
    value: f64,
) -> Result<f64, PartError> {
    if value.is_finite() && value > 0.0 {
        Ok(value)
    } else {
        Err(invalid(part, field, value, "must be a finite number > 0"))
    }
}

/// A dimension that must be finite and ≥ 0.
pub(crate) fn non_negative(
    part: &'static str,
    field: &'static str,
    value: f64,
) -> Result<f64, PartError> {
    if value.is_finite() && value >= 0.0 {
        Ok(value)
    } else {
        Err(invalid(part, field, value, "must be a finite number ≥ 0"))
    }
}

/// A finite value (of any sign).
pub(crate) fn finite(
    part: &'static str,
    field: &'static str,
    value: f64,
) -> Result<f64, PartError> {
    if value.is_finite() {
        Ok(value)
    } else {
        Err(invalid(part, field, value, "must be a finite number"))
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
