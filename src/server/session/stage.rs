//! Staging an edit: a JSON Patch applied to the vessels it is confined to (or
//! to the whole design), checked and given to the model, not yet durable; and
//! putting the model back when the edit is not kept.

use serde_json::Value;

use super::{Session, design_value};
use crate::design::{self, Design, DesignError, VesselDesign};
use crate::model::{Edit, ModelError};
use crate::server::error::ApiError;
use crate::server::scoped;
use crate::systems::WorkCounters;

/// Vessels staged by a scoped edit (their index and new JSON) and the work done.
pub(super) type Staged = (Vec<(usize, Value)>, WorkCounters);

/// A JSON value as a JSON Patch document.
pub(super) fn parse_patch(value: Value) -> Result<json_patch::Patch, ApiError> {
    if !value.is_array() {
        return Err(ApiError::Malformed(
            "a JSON Patch document (RFC 6902) is an array of operations such as \
             [{\"op\": \"replace\", \"path\": \"/vessels/0/parts/1/shell/length\", \"value\": 8000}]"
                .into(),
        ));
    }
    serde_json::from_value(value)
        .map_err(|e| ApiError::Malformed(format!("not a JSON Patch document (RFC 6902): {e}")))
}

/// A syntax error without its line and column: those are of the patched text,
/// which the editor never saw; the JSON path says where the problem is.
fn without_position(error: DesignError) -> DesignError {
    match error {
        DesignError::Syntax { path, message } => {
            let message = match message.rfind(" at line ") {
                Some(k) => message[..k].to_string(),
                None => message,
            };
            DesignError::Syntax { path, message }
        }
        other => other,
    }
}

/// Writes every whole number as an integer, so that a `test` of `7200` matches a
/// design value `7200.0`: RFC 6902 compares numbers by value, serde_json by
/// representation. Fractional and very large numbers are left as they are.
pub(super) fn canonical_numbers(value: &mut Value) {
    /// Integers up to 2^53 are exact in f64.
    const EXACT: f64 = 9_007_199_254_740_992.0;
    match value {
        Value::Number(n) => {
            if let Some(f) = n.as_f64()
                && !n.is_i64()
                && !n.is_u64()
                && f.fract() == 0.0
                && f.abs() <= EXACT
            {
                *value = Value::from(f as i64);
            }
        }
        Value::Array(items) => items.iter_mut().for_each(canonical_numbers),
        Value::Object(map) => map.values_mut().for_each(canonical_numbers),
        _ => {}
    }
}

/// A staged edit's new design: the whole document, or the JSON of the vessels
/// it changed, by index.
pub(super) enum Next {
    Whole(Value),
    Vessels(Vec<(usize, Value)>),
}

impl Session {
    /// Applies a patch confined to the vessels at `indices` to them alone and to
    /// the model (not yet journaled): their new JSON by index, and the work done.
    /// `Ok(None)` when the patch must go through the whole document (a vessel
    /// renamed or unparsable); on error the model is unchanged.
    pub(super) fn stage_vessels(
        &mut self,
        patch: &json_patch::Patch,
        indices: &[usize],
    ) -> Result<Option<Staged>, ApiError> {
        let Some(patched) = scoped::patch_vessels(&self.design, patch, indices, canonical_numbers)?
        else {
            return Ok(None);
        };
        let tags: Vec<String> = patched.iter().map(|(_, _, v)| v.tag.clone()).collect();
        let edit = scoped::vessels_edit(patched.into_iter().map(|(_, _, v)| v).collect());
        let work = self.model.edit(edit).map_err(|e| match e {
            ModelError::Design(e) => ApiError::Invalid(e),
            other => ApiError::Refused(other),
        })?;
        // As the model gives them back: defaults in their canonical form.
        let vessels = indices
            .iter()
            .zip(&tags)
            .map(|(&i, tag)| {
                let value = self.model.vessel_design(tag).map_or(Value::Null, |v| {
                    serde_json::to_value(v).unwrap_or(Value::Null)
                });
                (i, value)
            })
            .collect();
        Ok(Some((vessels, work)))
    }

    /// Applies a parsed patch to the model (not yet journaled): returns the new
    /// design JSON and the work done. On error the model is unchanged.
    pub(super) fn stage(
        &mut self,
        patch: &json_patch::Patch,
    ) -> Result<(Value, WorkCounters), ApiError> {
        let mut doc = self.design.clone();
        canonical_numbers(&mut doc);
        json_patch::patch(&mut doc, patch).map_err(|e| match e.kind {
            json_patch::PatchErrorKind::TestFailed => ApiError::TestFailed(e.to_string()),
            _ => ApiError::Unappliable(e.to_string()),
        })?;
        // Parsed from text like a design file, for its exact error paths. The
        // rules are checked by the model's staging, on the vessels that differ
        // only (the others were valid already): the same checks as a design file,
        // without resolving the whole plant on every edit.
        let text =
            serde_json::to_string_pretty(&doc).map_err(|e| ApiError::Malformed(e.to_string()))?;
        let parsed =
            design::parse_unchecked(&text).map_err(|e| ApiError::Invalid(without_position(e)))?;
        let work = self
            .model
            .edit(Edit::ReplaceDesign(parsed))
            .map_err(|e| match e {
                ModelError::Design(e) => ApiError::Invalid(e),
                other => ApiError::Refused(other),
            })?;
        Ok((design_value(&self.model.design()), work))
    }

    /// Puts the model back to the design the session holds (the staged `next`
    /// not being kept): the vessels it changed, or the whole design.
    pub(super) fn restore(&mut self, next: &Next) {
        let edit = match next {
            Next::Whole(_) => serde_json::from_value::<Design>(self.design.clone())
                .ok()
                .map(Edit::ReplaceDesign),
            Next::Vessels(vessels) => vessels
                .iter()
                .map(|(i, _)| serde_json::from_value(self.design["vessels"][*i].clone()).ok())
                .collect::<Option<Vec<VesselDesign>>>()
                .map(scoped::vessels_edit),
        };
        // It was valid a moment ago, so this cannot be refused.
        if let Some(edit) = edit
            && self.model.edit(edit).is_ok()
        {
            self.model.take_changes();
        }
    }
}
