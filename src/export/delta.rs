//! Delta GLB: only the parts of a scene that changed, keyed by their stable ids,
//! for viewers that already hold the rest.
//!
//! The streaming end of the data flow: after an edit the model's
//! [`ChangeLog`](crate::components::ChangeLog) names the stable ids that changed
//! (`tag` for a vessel whose frame changed, `tag/id` for a part or nozzle whose
//! frame or meshes changed). [`delta_scene`] keeps, from the full scene, every
//! vessel that holds a changed id and, under it, only the changed parts and
//! nozzles; [`write_delta_glb`] writes that with the ordinary GLB writer, so a
//! delta has the same tree, names, frames and units as a full file:
//!
//! ```text
//! plant
//! └─ vessel      name = tag (frame and extras always present)
//!    └─ part     name = id, only the changed ones: stable id = "tag/id"
//! ```
//!
//! A viewer replaces, for each changed `tag/id`, its node by the delta's node of
//! that name under the vessel named `tag`; for a changed `tag`, it takes the
//! vessel node's transform. Removed ids are sent beside the delta (they have no
//! geometry).

use std::collections::BTreeSet;

use super::error::ExportError;
use super::glb::write_glb;
use super::scene::{Scene, SceneVessel};

/// The stable id of a part or nozzle node: `tag/id`.
pub fn node_id(tag: &str, id: &str) -> String {
    format!("{tag}/{id}")
}

/// Every stable id in a scene, vessels first then their parts and nozzles, in
/// scene order.
pub fn scene_ids(scene: &Scene) -> Vec<String> {
    let mut ids = Vec::new();
    for vessel in &scene.vessels {
        ids.push(vessel.tag.clone());
        ids.extend(vessel.nodes.iter().map(|n| node_id(&vessel.tag, &n.id)));
    }
    ids
}

/// The part of `scene` a viewer needs to bring itself up to date with `changed`:
/// the vessels holding a changed id (with their frames) and, under them, only the
/// changed parts and nozzles. Ids not in the scene (removed since) are skipped.
pub fn delta_scene(scene: &Scene, changed: &BTreeSet<String>) -> Scene {
    let vessels = scene
        .vessels
        .iter()
        .filter_map(|vessel| {
            let nodes: Vec<_> = vessel
                .nodes
                .iter()
                .filter(|n| changed.contains(&node_id(&vessel.tag, &n.id)))
                .cloned()
                .collect();
            (changed.contains(&vessel.tag) || !nodes.is_empty()).then(|| SceneVessel {
                tag: vessel.tag.clone(),
                frame: vessel.frame,
                extras: vessel.extras.clone(),
                nodes,
            })
        })
        .collect();
    Scene { vessels }
}

/// The GLB of [`delta_scene`]: deterministic bytes, Y-up metres, like
/// [`write_glb`].
///
/// # Errors
///
/// As [`write_glb`].
pub fn write_delta_glb(scene: &Scene, changed: &BTreeSet<String>) -> Result<Vec<u8>, ExportError> {
    write_glb(&delta_scene(scene, changed))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::export::{SceneNode, SceneNodeKind};
    use glam::DAffine3;
    use serde_json::Value;

    fn vessel(tag: &str, ids: &[&str]) -> SceneVessel {
        SceneVessel {
            tag: tag.into(),
            frame: DAffine3::IDENTITY,
            extras: Value::Null,
            nodes: ids
                .iter()
                .map(|id| SceneNode {
                    id: (*id).into(),
                    kind: SceneNodeKind::Part,
                    frame: DAffine3::IDENTITY,
                    extras: Value::Null,
                    patches: Vec::new(),
                })
                .collect(),
        }
    }

    #[test]
    fn keeps_only_changed_parts_under_their_vessels() {
        let scene = Scene {
            vessels: vec![
                vessel("A", &["S1", "H1"]),
                vessel("B", &["S1"]),
                vessel("C", &[]),
            ],
        };
        let changed: BTreeSet<String> = ["A/H1", "C", "Z/gone"].map(String::from).into();
        let delta = delta_scene(&scene, &changed);
        assert_eq!(scene_ids(&delta), ["A", "A/H1", "C"]);
        assert_eq!(scene_ids(&scene), ["A", "A/S1", "A/H1", "B", "B/S1", "C"]);
    }
}
