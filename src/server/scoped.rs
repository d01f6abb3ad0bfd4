//! Edits confined to vessels: a JSON Patch whose every operation lies inside
//! existing vessels (`/vessels/<n>/…`, `from` included) is applied to those
//! vessels' JSON alone and given to the model as [`Edit::SetVessel`]s, so an edit
//! of one vessel of a 1,000-vessel plant costs what that vessel costs, not a copy,
//! print and parse of the whole design.
//!
//! Where it sits: [`super::session::Session::apply_patch`] tries
//! [`vessel_scope`] first and falls back to the whole document (top-level fields,
//! vessels added, removed or renamed, and any patch whose vessels do not parse,
//! so that syntax errors keep the whole-document paths and messages). Rule
//! violations already name `vessels[n]…` either way: the model checks a vessel
//! at its design order.
//!
//! The patch is applied to `{"vessels": {"<n>": <vessel n>, …}}`: a JSON
//! Pointer token names an object key as it names an array index, so every
//! operation, `test` included, reads and writes exactly what it would in the
//! whole document, and a failure reports the same operation and path.

use std::collections::BTreeMap;

use serde_json::{Map, Value};

use super::error::ApiError;
use crate::design::VesselDesign;
use crate::model::Edit;

/// The vessels a patch touches, by index, when every operation lies strictly
/// inside one of the `count` existing vessels; `None` otherwise.
pub fn vessel_scope(patch: &json_patch::Patch, count: usize) -> Option<Vec<usize>> {
    let mut out = Vec::new();
    for op in &patch.0 {
        let mut pointers = vec![op.path()];
        match op {
            json_patch::PatchOperation::Move(m) => pointers.push(&m.from),
            json_patch::PatchOperation::Copy(c) => pointers.push(&c.from),
            _ => {}
        }
        for pointer in pointers {
            let index = inside_vessel(pointer.as_str(), count)?;
            if !out.contains(&index) {
                out.push(index);
            }
        }
    }
    out.sort_unstable();
    (!out.is_empty()).then_some(out)
}

/// The vessel index of a pointer `/vessels/<n>/<more>` (canonical `n` below
/// `count`, something after it).
fn inside_vessel(pointer: &str, count: usize) -> Option<usize> {
    let rest = pointer.strip_prefix("/vessels/")?;
    let (token, below) = rest.split_once('/')?;
    let index: usize = token.parse().ok()?;
    (index.to_string() == token && index < count && !below.is_empty()).then_some(index)
}

/// A patched vessel: its index in the design, its JSON and its design.
pub type PatchedVessel = (usize, Value, VesselDesign);

/// The patched vessels, by index, as JSON and as designs; `Ok(None)` when one of
/// them changed its tag or does not parse (the caller then patches the whole
/// document, for its exact messages).
///
/// # Errors
///
/// The patch's own failures, as the whole document would report them.
pub fn patch_vessels(
    design: &Value,
    patch: &json_patch::Patch,
    indices: &[usize],
    canonical: impl Fn(&mut Value),
) -> Result<Option<Vec<PatchedVessel>>, ApiError> {
    let Some(vessels) = design.get("vessels").and_then(Value::as_array) else {
        return Ok(None);
    };
    let mut scoped = Map::new();
    for &i in indices {
        let Some(v) = vessels.get(i) else {
            return Ok(None);
        };
        let mut v = v.clone();
        canonical(&mut v);
        scoped.insert(i.to_string(), v);
    }
    let mut doc = Value::Object(Map::from_iter([(
        "vessels".to_string(),
        Value::Object(scoped),
    )]));
    json_patch::patch(&mut doc, patch).map_err(|e| match e.kind {
        json_patch::PatchErrorKind::TestFailed => ApiError::TestFailed(e.to_string()),
        _ => ApiError::Unappliable(e.to_string()),
    })?;
    let Value::Object(mut scoped) = doc["vessels"].take() else {
        return Ok(None);
    };
    let mut out = Vec::new();
    for &i in indices {
        let Some(value) = scoped.remove(&i.to_string()) else {
            return Ok(None);
        };
        let Ok(vessel) = serde_json::from_value::<VesselDesign>(value.clone()) else {
            return Ok(None);
        };
        if vessels[i].get("tag").and_then(Value::as_str) != Some(vessel.tag.as_str()) {
            return Ok(None);
        }
        out.push((i, value, vessel));
    }
    Ok(Some(out))
}

/// The model edit of patched vessels: one [`Edit::SetVessel`], or a batch.
pub fn vessels_edit(vessels: Vec<VesselDesign>) -> Edit {
    let mut edits: Vec<Edit> = vessels.into_iter().map(Edit::SetVessel).collect();
    if edits.len() == 1 {
        edits.remove(0)
    } else {
        Edit::Batch(edits)
    }
}

/// The tags of the vessels whose JSON differs between two designs (or that one
/// of them lacks), compared by tag.
pub fn differing_vessels(before: &Value, after: &Value) -> Vec<String> {
    let by_tag = |d: &Value| -> BTreeMap<String, Value> {
        d.get("vessels")
            .and_then(Value::as_array)
            .into_iter()
            .flatten()
            .filter_map(|v| Some((v.get("tag")?.as_str()?.to_string(), v.clone())))
            .collect()
    };
    let (a, b) = (by_tag(before), by_tag(after));
    let mut out: Vec<String> = a
        .iter()
        .filter(|(t, v)| b.get(*t) != Some(*v))
        .map(|(t, _)| t.clone())
        .collect();
    out.extend(b.keys().filter(|t| !a.contains_key(*t)).cloned());
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use serde_json::json;

    fn patch(v: Value) -> json_patch::Patch {
        serde_json::from_value(v).unwrap()
    }

    #[test]
    fn scope_is_the_vessels_every_operation_lies_inside() {
        let p = patch(json!([
            {"op": "replace", "path": "/vessels/3/parts/1/shell/length", "value": 1},
            {"op": "move", "from": "/vessels/0/nozzles/0", "path": "/vessels/3/nozzles/-"},
        ]));
        assert_eq!(vessel_scope(&p, 4), Some(vec![0, 3]));
        assert_eq!(vessel_scope(&p, 3), None, "vessel 3 does not exist");
        for outside in [
            "/vessels/3",
            "/vessels/-",
            "/vessels/03/tag",
            "/units",
            "/vessels/1/",
        ] {
            let p = patch(json!([{"op": "remove", "path": outside}]));
            assert_eq!(vessel_scope(&p, 4), None, "{outside}");
        }
    }

    #[test]
    fn a_scoped_patch_fails_as_the_whole_document_would() {
        let design = json!({"vessels": [{"tag": "A", "parts": [1, 2]}]});
        let p = patch(json!([
            {"op": "test", "path": "/vessels/0/parts/1", "value": 3},
        ]));
        let whole = json_patch::patch(&mut design.clone(), &p).unwrap_err();
        let scoped = patch_vessels(&design, &p, &[0], |_| {}).unwrap_err();
        assert!(scoped.to_string().contains(&whole.to_string()), "{scoped}");
    }

    #[test]
    fn differing_vessels_are_named_by_tag() {
        let a = json!({"vessels": [{"tag": "A", "x": 1}, {"tag": "B"}]});
        let b = json!({"vessels": [{"tag": "A", "x": 2}, {"tag": "C"}]});
        assert_eq!(differing_vessels(&a, &b), ["A", "B", "C"]);
    }
}
