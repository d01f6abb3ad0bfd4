//! The glTF document of a scene: the node tree, meshes, materials and the binary
//! buffer, as a `gltf_json::Root` plus the bytes of the buffer.
//!
//! Part of the glTF writer, between the [`Scene`] and the GLB container
//! ([`super::glb`]). The tree is
//!
//! ```text
//! plant          rotation only: plant (x, y, z) → glTF (x, z, −y), Z-up → Y-up
//! └─ vessel      name = tag, vessel frame (translation in m), extras
//!    └─ part     name = part id or nozzle mark, local frame (translation in m), extras
//!       └─ patch name = patch name, one mesh of one triangle primitive
//! ```
//!
//! Positions are metres, so every translation is converted mm → m; frames are
//! rigid, which keeps that consistent at every level. Nodes are numbered in
//! depth-first order and everything else in scene order: the same scene gives the
//! same document. Patches with no triangles get no node.

use std::f32::consts::FRAC_1_SQRT_2;

use glam::{DAffine3, DQuat, DVec3};
use gltf_json as json;
use json::mesh::{Mode, Semantic};
use json::scene::UnitQuaternion;
use json::validation::Checked;
use serde_json::Value;
use serde_json::value::RawValue;

use super::error::ExportError;
use super::gltf_buffers::{MM_TO_M, MeshBuffers};
use super::gltf_materials::MaterialKind;
use super::scene::{Scene, SceneNode, SceneVessel};

/// Name of the root node.
pub const PLANT_NODE: &str = "plant";

/// Rotation of the root node, `(x, y, z, w)`: −90° about X, taking the plant's
/// Z-up frame to glTF's Y-up one: plant (x, y, z) → glTF (x, z, −y).
pub const PLANT_ROTATION: [f32; 4] = [-FRAC_1_SQRT_2, 0.0, 0.0, FRAC_1_SQRT_2];

/// Relative tolerance under which a frame's scale counts as 1 and is not written.
const UNIT_SCALE_EPSILON: f64 = 1e-9;

/// The glTF document of `scene` and the bytes of its binary buffer (empty when the
/// scene has no triangles).
///
/// # Errors
///
/// [`ExportError::MalformedMesh`] and [`ExportError::NonFiniteVertex`] for a mesh
/// that cannot be written, [`ExportError::TooLarge`] past 4 GiB of buffer,
/// [`ExportError::Json`] if an `extras` value cannot be serialized.
pub(super) fn document(scene: &Scene) -> Result<(json::Root, Vec<u8>), ExportError> {
    document_with(scene, MeshBuffers::default())
}

/// The document of `scene` with its mesh data laid out through `buffers` (which
/// may keep the bytes or only count them).
pub(super) fn document_with(
    scene: &Scene,
    mut buffers: MeshBuffers,
) -> Result<(json::Root, Vec<u8>), ExportError> {
    let mut root = json::Root {
        asset: json::Asset {
            generator: Some(format!("vesselcad {}", env!("CARGO_PKG_VERSION"))),
            ..Default::default()
        },
        ..Default::default()
    };
    let materials = push_materials(&mut root, scene);
    let plant = root.push(json::Node {
        name: Some(PLANT_NODE.to_string()),
        rotation: Some(UnitQuaternion(PLANT_ROTATION)),
        extras: raw(&serde_json::json!({ "kind": "plant", "up": "Y", "units": "m" }))?,
        ..Default::default()
    });
    let mut vessel_nodes = Vec::with_capacity(scene.vessels.len());
    for vessel in &scene.vessels {
        vessel_nodes.push(push_vessel(&mut root, &mut buffers, &materials, vessel)?);
    }
    set_children(&mut root, plant, vessel_nodes);
    root.push(json::Scene {
        extensions: None,
        extras: None,
        name: Some(PLANT_NODE.to_string()),
        nodes: vec![plant],
    });
    root.scene = Some(json::Index::new(0));
    let bin = buffers.finish(&mut root)?;
    Ok((root, bin))
}

/// Pushes the materials the scene uses, in palette order; returns each palette
/// slot's index (`None` where unused).
fn push_materials(
    root: &mut json::Root,
    scene: &Scene,
) -> [Option<json::Index<json::Material>>; 3] {
    let mut used = [false; 3];
    for node in scene.vessels.iter().flat_map(|v| &v.nodes) {
        if node.patches.iter().any(|p| !is_empty(&p.mesh)) {
            used[MaterialKind::of(node).slot()] = true;
        }
    }
    MaterialKind::ALL.map(|kind| used[kind.slot()].then(|| root.push(kind.material())))
}

/// Pushes a vessel node and everything under it; returns its index.
fn push_vessel(
    root: &mut json::Root,
    buffers: &mut MeshBuffers,
    materials: &[Option<json::Index<json::Material>>; 3],
    vessel: &SceneVessel,
) -> Result<json::Index<json::Node>, ExportError> {
    let index = root.push(json::Node {
        name: Some(vessel.tag.clone()),
        extras: raw(&vessel.extras)?,
        ..transformed(&vessel.frame)
    });
    let mut children = Vec::with_capacity(vessel.nodes.len());
    for node in &vessel.nodes {
        let material = materials[MaterialKind::of(node).slot()];
        children.push(push_node(root, buffers, material, &vessel.tag, node)?);
    }
    set_children(root, index, children);
    Ok(index)
}

/// Pushes a part or nozzle node and its patch nodes; returns its index.
fn push_node(
    root: &mut json::Root,
    buffers: &mut MeshBuffers,
    material: Option<json::Index<json::Material>>,
    tag: &str,
    node: &SceneNode,
) -> Result<json::Index<json::Node>, ExportError> {
    let index = root.push(json::Node {
        name: Some(node.id.clone()),
        extras: raw(&node.extras)?,
        ..transformed(&node.frame)
    });
    let entity = format!("{tag}/{}", node.id);
    let mut children = Vec::with_capacity(node.patches.len());
    for patch in node.patches.iter().filter(|p| !is_empty(&p.mesh)) {
        let accessors = buffers.push(root, &patch.mesh, &entity, &patch.name)?;
        let primitive = json::mesh::Primitive {
            attributes: [
                (Checked::Valid(Semantic::Positions), accessors.positions),
                (Checked::Valid(Semantic::Normals), accessors.normals),
            ]
            .into_iter()
            .collect(),
            extensions: None,
            extras: None,
            indices: Some(accessors.indices),
            material,
            mode: Checked::Valid(Mode::Triangles),
            targets: None,
        };
        let mesh = root.push(json::Mesh {
            extensions: None,
            extras: None,
            name: Some(format!("{entity}/{}", patch.name)),
            primitives: vec![primitive],
            weights: None,
        });
        children.push(root.push(json::Node {
            name: Some(patch.name.clone()),
            mesh: Some(mesh),
            ..Default::default()
        }));
    }
    set_children(root, index, children);
    Ok(index)
}

/// True for a mesh with no triangle (nothing to draw).
pub(super) fn is_empty(mesh: &crate::mesh::PackedMesh) -> bool {
    mesh.vertex_count() == 0 || mesh.index_count() == 0
}

/// Sets a node's children; an empty list is left out, as glTF requires.
fn set_children(
    root: &mut json::Root,
    parent: json::Index<json::Node>,
    children: Vec<json::Index<json::Node>>,
) {
    if let Some(node) = root.nodes.get_mut(parent.value()) {
        node.children = (!children.is_empty()).then_some(children);
    }
}

/// A node carrying only the transform of a frame (mm), as glTF translation (m),
/// rotation and, for a frame that is not rigid, scale. Identity parts are left out.
fn transformed(frame: &DAffine3) -> json::Node {
    let (scale, rotation, translation) = frame.to_scale_rotation_translation();
    let rigid = (scale - DVec3::ONE).abs().max_element() <= UNIT_SCALE_EPSILON;
    let rotation = canonical(rotation);
    json::Node {
        translation: (translation != DVec3::ZERO)
            .then(|| (translation * MM_TO_M).as_vec3().to_array()),
        rotation: (rotation != DQuat::IDENTITY)
            .then(|| UnitQuaternion(rotation.as_quat().normalize().to_array())),
        scale: (!rigid).then(|| scale.as_vec3().to_array()),
        ..Default::default()
    }
}

/// The quaternion with `w ≥ 0` (the same rotation), so equal frames give equal
/// numbers.
fn canonical(q: DQuat) -> DQuat {
    if q.w < 0.0 { -q } else { q }
}

/// A JSON value as glTF `extras`; `null` is left out.
fn raw(value: &Value) -> Result<Option<Box<RawValue>>, ExportError> {
    if value.is_null() {
        return Ok(None);
    }
    Ok(Some(serde_json::value::to_raw_value(value)?))
}
