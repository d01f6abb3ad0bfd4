//! Taking an edit back without copying the design: a staged edit's new JSON
//! (the vessels it changed, or the whole document) is swapped into the
//! session's design, and the JSON Patch that leads back is kept — the undo
//! stack's entry and what a store needs to rebuild the design before.
//!
//! For an edit confined to vessels the inverse is the difference of each
//! changed vessel alone, under its `/vessels/<n>` (so it is confined to the
//! same vessels, and an undo is as cheap as the edit); for a whole-document
//! edit it is the difference of the documents (that path reads the whole
//! design anyway). Applied to the design the edit left, the inverse gives the
//! design before it exactly.

use serde_json::Value;

use super::Session;
use super::stage::Next;
use crate::server::scoped;

/// The JSON Patch that takes `next` (staged on `design`) back to `design`.
pub(super) fn inverse(design: &Value, next: &Next) -> json_patch::Patch {
    match next {
        Next::Whole(next) => json_patch::diff(next, design),
        Next::Vessels(vessels) => {
            let mut ops = Vec::new();
            for (i, after) in vessels {
                let before = &design["vessels"][*i];
                let prefix = format!("/vessels/{i}");
                for op in json_patch::diff(after, before).0 {
                    // `diff` writes add, remove and replace only: one path each.
                    let mut op = serde_json::to_value(op).unwrap_or(Value::Null);
                    if let Some(path) = op.get_mut("path")
                        && let Some(p) = path.as_str()
                    {
                        *path = Value::String(format!("{prefix}{p}"));
                    }
                    ops.push(op);
                }
            }
            serde_json::from_value(Value::Array(ops)).unwrap_or_default()
        }
    }
}

impl Session {
    /// Puts a staged edit's new JSON into the session's design (moved, not
    /// copied): returns what it replaced, in the same shape (for
    /// [`Session::put_back`]), and the tags of the vessels that changed.
    pub(super) fn swap_in(&mut self, next: Next) -> (Next, Vec<String>) {
        match next {
            Next::Whole(next) => {
                let touched = scoped::differing_vessels(&self.design, &next);
                let previous = std::mem::replace(&mut self.design, next);
                (Next::Whole(previous), touched)
            }
            Next::Vessels(vessels) => {
                let mut touched = Vec::new();
                let mut previous = Vec::with_capacity(vessels.len());
                for (i, value) in vessels {
                    if let Some(tag) = value.get("tag").and_then(Value::as_str) {
                        touched.push(tag.to_string());
                    }
                    let old = std::mem::replace(&mut self.design["vessels"][i], value);
                    previous.push((i, old));
                }
                (Next::Vessels(previous), touched)
            }
        }
    }

    /// Undoes [`Session::swap_in`] with what it returned, and puts the model
    /// back to that design (an edit that could not be made durable).
    pub(super) fn put_back(&mut self, previous: Next) {
        match previous {
            Next::Whole(previous) => {
                self.design = previous;
                self.restore(&Next::Whole(Value::Null));
            }
            Next::Vessels(previous) => {
                let indices: Vec<(usize, Value)> =
                    previous.iter().map(|(i, _)| (*i, Value::Null)).collect();
                for (i, value) in previous {
                    self.design["vessels"][i] = value;
                }
                self.restore(&Next::Vessels(indices));
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use serde_json::json;

    #[test]
    fn a_vessel_inverse_lies_inside_its_vessel_and_takes_it_back() {
        let design = json!({"vessels": [
            {"tag": "A", "nozzles": [{"mark": "N1", "projection": 200}]},
            {"tag": "B", "nozzles": []},
        ]});
        let after = json!({"tag": "B", "nozzles": [{"mark": "N9"}]});
        let patch = inverse(&design, &Next::Vessels(vec![(1, after.clone())]));
        assert!(!patch.0.is_empty());
        assert_eq!(scoped::vessel_scope(&patch, 2), Some(vec![1]));
        let mut edited = design.clone();
        edited["vessels"][1] = after;
        json_patch::patch(&mut edited, &patch).unwrap();
        assert_eq!(edited, design);
    }

    #[test]
    fn a_whole_inverse_takes_the_document_back() {
        let design = json!({"units": "mm", "vessels": [{"tag": "A"}, {"tag": "B"}]});
        let next = json!({"units": "mm", "vessels": [{"tag": "B"}]});
        let patch = inverse(&design, &Next::Whole(next.clone()));
        let mut edited = next;
        json_patch::patch(&mut edited, &patch).unwrap();
        assert_eq!(edited, design);
    }

    #[test]
    fn an_edit_of_one_vessel_keeps_only_that_vessels_change_for_undo() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("plant.json");
        let source = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("examples/designs/small-plant.json");
        std::fs::copy(source, &path).unwrap();
        let options = crate::mesh::TessellationOptions::DEFAULT;
        let mut session = Session::open(&path, options).unwrap();
        let edit =
            br#"[{"op": "replace", "path": "/vessels/2/nozzles/0/projection", "value": 1234}]"#;
        session.apply_patch(edit).unwrap();
        let kept = serde_json::to_value(&session.undo[0]).unwrap();
        let design = serde_json::to_string(&session.design).unwrap().len();
        let undo = kept.to_string().len();
        assert!(
            undo * 100 < design,
            "{undo} bytes kept for a {design}-byte design"
        );
        assert_eq!(kept[0]["path"], "/vessels/2/nozzles/0/projection", "{kept}");
    }
}
