//! Designs as the store keeps them: the canonical JSON text (mm, schema order,
//! defaults omitted), addressed by its SHA-256, and the JSON Patch steps between
//! them. A revision's patch is the exact difference between the canonical
//! designs before and after (RFC 6902, as `json_patch::diff` writes it), so
//! replaying patches from any stored snapshot gives the revision's design bit for
//! bit, which its hash then proves.

use serde_json::Value;
use sha2::{Digest, Sha256};

use crate::design::{self, Design};

/// The canonical text of a design (mm).
pub fn canonical_text(design: &Design) -> String {
    design::to_canonical_json(design)
}

/// The content address of a canonical text: SHA-256, lowercase hex.
pub fn content_hash(text: &str) -> String {
    let digest = Sha256::digest(text.as_bytes());
    digest.iter().map(|b| format!("{b:02x}")).collect()
}

/// A design as the JSON value patches apply to.
pub fn design_value(design: &Design) -> Value {
    serde_json::to_value(design).unwrap_or(Value::Null)
}

/// The patch that turns `before` into `after`, as a JSON value.
pub fn patch_between(before: &Design, after: &Design) -> Value {
    let patch = json_patch::diff(&design_value(before), &design_value(after));
    serde_json::to_value(patch).unwrap_or(Value::Array(Vec::new()))
}

/// Applies a stored patch to `design`.
///
/// # Errors
///
/// The reason, when the patch does not apply or its result is not a design.
pub fn apply(design: &Design, patch: &Value) -> Result<Design, String> {
    let patch: json_patch::Patch =
        serde_json::from_value(patch.clone()).map_err(|e| format!("not a JSON Patch: {e}"))?;
    let mut value = design_value(design);
    json_patch::patch(&mut value, &patch).map_err(|e| e.to_string())?;
    serde_json::from_value(value).map_err(|e| format!("the patched document is not a design: {e}"))
}

/// Reads a stored snapshot (canonical text, already in mm).
///
/// # Errors
///
/// The reason, when the text is not a design.
pub fn parse_snapshot(text: &str) -> Result<Design, String> {
    design::parse_unchecked(text).map_err(|e| e.to_string())
}
