//! `EXT_mesh_gpu_instancing`: the patches of a plant that draw one glTF mesh,
//! drawn by one node, one draw call for them all.
//!
//! Part of the glTF writer, used by [`super::gltf_document`] when
//! [`GlbOptions::instancing`](super::GlbOptions::instancing) is on. The document
//! counts how many patch nodes each glTF mesh would have; a patch whose mesh is
//! drawn more than once leaves its part's children and becomes an instance of
//! that mesh's node, a child of the plant node (so its transform is in the
//! plant frame, Z-up, metres, before the root's Y-up rotation). A mesh drawn
//! once keeps its plain patch node. Each instance's transform is its patch
//! node's world transform — vessel frame × part frame × the quantized mesh's
//! dequantization — composed in `f64` and written as `f32` `TRANSLATION`,
//! `ROTATION` (left out when every rotation is the identity) and `SCALE` (left
//! out when every scale is 1). The node's `extras` are
//! `{"kind": "instances", "ids": ["tag/part/patch", …]}`, the stable id of
//! each instance in instance order, so a viewer picking instance `k` knows the
//! patch and part it hit. Node order and ids are deterministic: groups in mesh
//! order, instances in scene order.

use std::collections::BTreeMap;

use glam::{DAffine3, DQuat, DVec3};
use gltf_json as json;
use json::accessor::Type;
use serde_json::{Value, json};

use super::gltf_buffers::MeshBuffers;
use super::gltf_encoding::{Dequantization, MM_TO_M};

/// The extension's name.
pub(super) const INSTANCING: &str = "EXT_mesh_gpu_instancing";

/// Relative tolerance under which a scale counts as 1 and a rotation as the
/// identity (`f32` cannot tell them apart).
const IDENTITY_EPSILON: f64 = 1e-9;

/// One instance: the patch's stable id and its transform, plant frame, metres.
struct Instance {
    id: String,
    translation: DVec3,
    rotation: DQuat,
    scale: DVec3,
}

/// The instances of each glTF mesh drawn more than once, by mesh index.
#[derive(Default)]
pub(super) struct InstanceGroups {
    groups: BTreeMap<usize, Vec<Instance>>,
}

impl InstanceGroups {
    /// Adds an instance of `mesh`: patch `id` (`tag/part/patch`) placed by
    /// `world` (part frame → plant frame, mm) and its mesh's `dequantization`.
    pub fn add(
        &mut self,
        mesh: json::Index<json::Mesh>,
        id: String,
        world: &DAffine3,
        dequantization: Dequantization,
    ) {
        let (scale, rotation, translation) = world.to_scale_rotation_translation();
        let (offset, step) = dequantization.unwrap_or(([0.0; 3], 1.0));
        // x_plant(m) = T/1000 + R·S·(offset + step·q): translation, rotation, scale.
        let offset = DVec3::from_array(offset.map(f64::from));
        let rotation = if rotation.w < 0.0 {
            -rotation
        } else {
            rotation
        };
        self.groups.entry(mesh.value()).or_default().push(Instance {
            id,
            translation: translation * MM_TO_M + rotation * (scale * offset),
            rotation,
            scale: scale * f64::from(step),
        });
    }

    /// Pushes one instanced node per mesh, with its attribute accessors;
    /// returns the nodes (children of the plant node) and each node's
    /// extension object, by node index.
    pub fn push_nodes(
        self,
        root: &mut json::Root,
        buffers: &mut MeshBuffers<'_>,
    ) -> (Vec<json::Index<json::Node>>, Vec<(usize, Value)>) {
        let mut nodes = Vec::with_capacity(self.groups.len());
        let mut extensions = Vec::with_capacity(self.groups.len());
        for (mesh, instances) in self.groups {
            let flat = |f: &dyn Fn(&Instance) -> Vec<f64>| -> Vec<f32> {
                instances.iter().flat_map(f).map(|x| x as f32).collect()
            };
            let mut attributes = serde_json::Map::new();
            let translations = flat(&|i| i.translation.to_array().to_vec());
            let a = buffers.push_instances(root, Type::Vec3, &translations);
            attributes.insert("TRANSLATION".into(), json!(a.value()));
            if instances
                .iter()
                .any(|i| !i.rotation.abs_diff_eq(DQuat::IDENTITY, IDENTITY_EPSILON))
            {
                let rotations = flat(&|i| {
                    let q = i.rotation.as_quat().normalize();
                    q.to_array().map(f64::from).to_vec()
                });
                let a = buffers.push_instances(root, Type::Vec4, &rotations);
                attributes.insert("ROTATION".into(), json!(a.value()));
            }
            if instances
                .iter()
                .any(|i| !i.scale.abs_diff_eq(DVec3::ONE, IDENTITY_EPSILON))
            {
                let scales = flat(&|i| i.scale.to_array().to_vec());
                let a = buffers.push_instances(root, Type::Vec3, &scales);
                attributes.insert("SCALE".into(), json!(a.value()));
            }
            let ids: Vec<Value> = instances.iter().map(|i| Value::from(&*i.id)).collect();
            let extras = json!({ "kind": "instances", "ids": ids });
            let node = root.push(json::Node {
                name: Some("instances".to_string()),
                mesh: Some(json::Index::new(mesh as u32)),
                // A `Value` always serializes.
                extras: serde_json::value::to_raw_value(&extras).ok(),
                ..Default::default()
            });
            extensions.push((node.value(), json!({ "attributes": attributes })));
            nodes.push(node);
        }
        (nodes, extensions)
    }
}
