//! Part builders' errors recorded as rule violations under the part's JSON path.

use super::Report;
use crate::parts::PartError;

/// Records a part builder's error under the part's JSON path, renaming builder
/// fields to design fields with `names` (`(builder, design)` pairs).
pub(crate) fn report_part_error(
    report: &mut Report,
    path: &str,
    id: &str,
    error: &PartError,
    names: &[(&str, &str)],
) {
    match error {
        PartError::InvalidParameter {
            field,
            value,
            rule,
            part,
        } => {
            let design_field = names
                .iter()
                .find(|(b, _)| b == field)
                .map_or(*field, |(_, d)| *d);
            let path = if design_field.contains(' ') {
                path.to_string()
            } else {
                format!("{path}.{design_field}")
            };
            report.push(
                path,
                Some(id),
                design_field,
                value,
                format!("{part}: {rule}"),
            );
        }
        other => report.push(path, Some(id), "", "", other.to_string()),
    }
}
