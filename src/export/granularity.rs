//! How finely a GLB is split into nodes: one mesh per patch (the default), per
//! part, per vessel or for the whole plant.
//!
//! A step before the glTF writer: [`merge_scene`] turns a [`Scene`] into one
//! whose meshes are the concatenation of the finer ones, one per material (so a
//! merged mesh is one draw call). Positions are carried into the merged node's
//! frame with the exact (`f64`) rigid frames, so every vertex stays where it was
//! and the chordal bound of the meshes holds for the merged mesh as it did for
//! each patch; the packed mesh keeps interior vertices within 2⁻³² of its extent
//! (2e-4 mm over a kilometre). Ids and `extras` stay on the nodes that remain: a
//! part merge keeps vessel and part nodes (one patch node, `merged`, per part);
//! a vessel merge keeps vessel nodes, with one node per material under each; a
//! plant merge keeps one vessel node, `plant`, with one node per material. A
//! merged node's `extras` name its material and the ids it holds.

use glam::DAffine3;
use serde_json::{Value, json};
use std::sync::Arc;

use super::gltf_materials::MaterialKind;
use super::scene::{Scene, SceneNode, SceneNodeKind, ScenePatch, SceneVessel};
use crate::mesh::{Mesh, PackedMesh};

/// What one node of the GLB holds.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Granularity {
    /// One mesh per patch: every patch a node (the default).
    #[default]
    Patch,
    /// One mesh per part or nozzle.
    Part,
    /// One mesh per vessel and material.
    Vessel,
    /// One mesh per material for the whole plant.
    Plant,
}

/// Name of a merged patch node.
pub const MERGED_PATCH: &str = "merged";

/// `scene` with its meshes merged to `granularity` (a copy of the tree for
/// [`Granularity::Patch`]; meshes are shared, not copied).
pub fn merge_scene(scene: &Scene, granularity: Granularity) -> Scene {
    match granularity {
        Granularity::Patch => scene.clone(),
        Granularity::Part => Scene {
            vessels: scene
                .vessels
                .iter()
                .map(|v| SceneVessel {
                    nodes: v.nodes.iter().map(merge_part).collect(),
                    ..v.clone_without_nodes()
                })
                .collect(),
        },
        Granularity::Vessel => Scene {
            vessels: scene
                .vessels
                .iter()
                .map(|v| SceneVessel {
                    nodes: merged_nodes(
                        v.nodes.iter().map(|n| (n, n.frame, n.id.clone())).collect(),
                    ),
                    ..v.clone_without_nodes()
                })
                .collect(),
        },
        Granularity::Plant => {
            let all = scene
                .vessels
                .iter()
                .flat_map(|v| {
                    v.nodes
                        .iter()
                        .map(move |n| (n, v.frame * n.frame, format!("{}/{}", v.tag, n.id)))
                })
                .collect();
            let nodes = merged_nodes(all);
            Scene {
                vessels: if nodes.is_empty() {
                    Vec::new()
                } else {
                    vec![SceneVessel {
                        tag: "plant".to_string(),
                        frame: DAffine3::IDENTITY,
                        extras: json!({
                            "kind": "merged",
                            "vessels": scene.vessels.iter().map(|v| v.tag.clone()).collect::<Vec<_>>(),
                        }),
                        nodes,
                    }]
                },
            }
        }
    }
}

impl SceneVessel {
    /// The vessel with no nodes.
    fn clone_without_nodes(&self) -> SceneVessel {
        SceneVessel {
            tag: self.tag.clone(),
            frame: self.frame,
            extras: self.extras.clone(),
            nodes: Vec::new(),
        }
    }
}

/// A part or nozzle with its patches merged into one.
fn merge_part(node: &SceneNode) -> SceneNode {
    let meshes: Vec<(&PackedMesh, DAffine3)> = node
        .patches
        .iter()
        .map(|p| (&*p.mesh, DAffine3::IDENTITY))
        .collect();
    SceneNode {
        id: node.id.clone(),
        kind: node.kind,
        frame: node.frame,
        extras: node.extras.clone(),
        patches: merged_patch(&meshes).into_iter().collect(),
    }
}

/// One node per material holding the patches of `nodes`, each carried by its
/// frame into the merged node's (identity) frame; `ids` names each node in the
/// merged node's `extras`.
fn merged_nodes(nodes: Vec<(&SceneNode, DAffine3, String)>) -> Vec<SceneNode> {
    MaterialKind::ALL
        .into_iter()
        .filter_map(|kind| {
            let members: Vec<_> = nodes
                .iter()
                .filter(|(n, _, _)| MaterialKind::of(n) == kind)
                .collect();
            let meshes: Vec<(&PackedMesh, DAffine3)> = members
                .iter()
                .flat_map(|(n, frame, _)| n.patches.iter().map(|p| (&*p.mesh, *frame)))
                .collect();
            let patch = merged_patch(&meshes)?;
            Some(SceneNode {
                id: kind.name().to_string(),
                kind: if kind == MaterialKind::Nozzle {
                    SceneNodeKind::Nozzle
                } else {
                    SceneNodeKind::Part
                },
                frame: DAffine3::IDENTITY,
                extras: json!({
                    "kind": "merged",
                    "material": kind.name(),
                    "ids": members.iter().map(|(_, _, id)| Value::from(id.as_str())).collect::<Vec<_>>(),
                }),
                patches: vec![patch],
            })
        })
        .collect()
}

/// The meshes, each carried by its frame, as one patch; `None` when they have
/// no triangle.
fn merged_patch(meshes: &[(&PackedMesh, DAffine3)]) -> Option<ScenePatch> {
    let mut merged = Mesh::default();
    for (mesh, frame) in meshes {
        if mesh.vertex_count() == 0 || mesh.index_count() == 0 {
            continue;
        }
        let base = merged.positions.len() as u32;
        merged
            .positions
            .extend(mesh.positions().map(|p| frame.transform_point3(p)));
        merged
            .normals
            .extend((0..mesh.normal_count()).map(|i| frame.transform_vector3(mesh.normal(i))));
        merged.indices.extend(mesh.indices().map(|i| base + i));
    }
    (!merged.indices.is_empty()).then(|| ScenePatch {
        name: MERGED_PATCH.to_string(),
        mesh: Arc::new(PackedMesh::pack(&merged)),
    })
}
