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
//!       └─ patch name = patch name, one mesh of one triangle primitive;
//!                quantized: the mesh's translation (m) and uniform scale
//! ```
//!
//! Positions are metres, so every translation is converted mm → m; frames are
//! rigid, which keeps that consistent at every level. Nodes are numbered in
//! depth-first order and everything else in scene order: the same scene gives the
//! same document. Patches with no triangles get no node. With reuse (the
//! default), patches whose meshes are equal — the same mesh object, as the model
//! shares them, or equal contents, as a direct build makes them — point at one
//! glTF mesh (one per material), written once.

use std::collections::HashMap;
use std::f32::consts::FRAC_1_SQRT_2;
use std::hash::{Hash, Hasher};
use std::sync::Arc;

use glam::{DAffine3, DQuat, DVec3};
use gltf_json as json;
use json::mesh::{Mode, Semantic};
use json::scene::UnitQuaternion;
use json::validation::Checked;
use serde_json::Value;
use serde_json::value::RawValue;

use super::error::ExportError;
use super::glb_options::GlbOptions;
use super::gltf_buffers::{FinishedBuffers, MeshBuffers, PrimitiveAccessors};
use super::gltf_encoding::MM_TO_M;
use super::gltf_encoding::{Dequantization, Encoding, Stream};
use super::gltf_instancing::{INSTANCING, InstanceGroups};
use super::gltf_materials::MaterialKind;
use super::scene::{Scene, SceneNode, ScenePatch, SceneVessel};
use crate::mesh::PackedMesh;

/// Name of the root node.
pub const PLANT_NODE: &str = "plant";

/// Rotation of the root node, `(x, y, z, w)`: −90° about X, taking the plant's
/// Z-up frame to glTF's Y-up one: plant (x, y, z) → glTF (x, z, −y).
pub const PLANT_ROTATION: [f32; 4] = [-FRAC_1_SQRT_2, 0.0, 0.0, FRAC_1_SQRT_2];

/// Relative tolerance under which a frame's scale counts as 1 and is not written.
const UNIT_SCALE_EPSILON: f64 = 1e-9;

/// A finished glTF document: the JSON tree, the `BIN` chunk's bytes (empty when
/// the scene has no triangles or the buffers were laid out only), the meshes in
/// the order their bytes were written, and the extensions `gltf_json` has no
/// field for.
pub(super) struct Document<'a> {
    /// The JSON tree.
    pub root: json::Root,
    /// The buffer, extensions and fallback buffer.
    pub buffers: FinishedBuffers,
    /// Every distinct mesh written, in buffer order, with its encoding.
    pub meshes: Vec<(&'a PackedMesh, Encoding)>,
    /// `EXT_mesh_gpu_instancing` objects of instanced nodes, by node index.
    pub node_extensions: Vec<(usize, Value)>,
}

impl Document<'_> {
    /// The JSON chunk's bytes: the tree, with the meshopt extensions of buffer
    /// views and of the fallback buffer added when compressed.
    ///
    /// # Errors
    ///
    /// [`ExportError::Json`] when it cannot be serialized.
    pub fn json_bytes(&self) -> Result<Vec<u8>, ExportError> {
        let fallback = self.buffers.fallback_buffer;
        if fallback.is_none() && self.node_extensions.is_empty() {
            return Ok(serde_json::to_vec(&self.root)?);
        }
        let mut value = serde_json::to_value(&self.root)?;
        for (node, ext) in &self.node_extensions {
            if let Some(n) = value.pointer_mut(&format!("/nodes/{node}")) {
                n["extensions"] = serde_json::json!({ INSTANCING: ext });
            }
        }
        let extension = |v: Value| serde_json::json!({ MESHOPT: v });
        if let Some(buffer) = fallback.and_then(|f| value.pointer_mut(&format!("/buffers/{f}"))) {
            buffer["extensions"] = extension(serde_json::json!({ "fallback": true }));
        }
        for (view, ext) in &self.buffers.view_extensions {
            if let Some(v) = value.pointer_mut(&format!("/bufferViews/{view}")) {
                v["extensions"] = extension(ext.clone());
            }
        }
        Ok(serde_json::to_vec(&value)?)
    }
}

/// `EXT_meshopt_compression`.
const MESHOPT: &str = "EXT_meshopt_compression";
/// `KHR_mesh_quantization`.
const QUANTIZATION: &str = "KHR_mesh_quantization";

/// The glTF document of `scene` written with `options`.
///
/// # Errors
///
/// [`ExportError::MalformedMesh`] and [`ExportError::NonFiniteVertex`] for a mesh
/// that cannot be written, [`ExportError::TooLarge`] past 4 GiB of buffer,
/// [`ExportError::Json`] if an `extras` value cannot be serialized.
pub(super) fn document<'a>(
    scene: &'a Scene,
    options: &GlbOptions,
) -> Result<Document<'a>, ExportError> {
    document_with(scene, MeshBuffers::new(*options))
}

/// The document of `scene` with its mesh data laid out through `buffers` (which
/// may keep the bytes or only count them).
pub(super) fn document_with<'a>(
    scene: &'a Scene,
    buffers: MeshBuffers<'a>,
) -> Result<Document<'a>, ExportError> {
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
    let mut writer = MeshWriter {
        buffers,
        by_pointer: HashMap::new(),
        by_content: HashMap::new(),
        written: Vec::new(),
    };
    let mut placer = if writer.buffers.options().instancing && writer.buffers.options().reuse {
        Placer::Instancing {
            uses: count_uses(&mut root, &mut writer, &materials, scene)?,
            groups: InstanceGroups::default(),
        }
    } else {
        Placer::Nodes
    };
    let mut vessel_nodes = Vec::with_capacity(scene.vessels.len());
    for vessel in &scene.vessels {
        vessel_nodes.push(push_vessel(
            &mut root,
            (&mut writer, &mut placer),
            &materials,
            vessel,
        )?);
    }
    let mut node_extensions = Vec::new();
    if let Placer::Instancing { groups, .. } = placer {
        let (nodes, extensions) = groups.push_nodes(&mut root, &mut writer.buffers);
        vessel_nodes.extend(nodes);
        node_extensions = extensions;
    }
    set_children(&mut root, plant, vessel_nodes);
    root.push(json::Scene {
        extensions: None,
        extras: None,
        name: Some(PLANT_NODE.to_string()),
        nodes: vec![plant],
    });
    root.scene = Some(json::Index::new(0));
    let meshes = writer.buffers.take_meshes();
    let quantized = meshes.iter().any(|(_, e)| {
        e.streams()
            .iter()
            .flatten()
            .any(|s| matches!(s, Stream::PositionsU16 | Stream::NormalsI8))
    });
    let buffers = writer.buffers.finish(&mut root)?;
    let mut extensions = Vec::new();
    if !node_extensions.is_empty() {
        extensions.push(INSTANCING.to_string());
    }
    if quantized {
        extensions.push(QUANTIZATION.to_string());
    }
    if buffers.fallback_buffer.is_some() {
        extensions.push(MESHOPT.to_string());
    }
    root.extensions_used = extensions.clone();
    root.extensions_required = extensions;
    Ok(Document {
        root,
        buffers,
        meshes,
        node_extensions,
    })
}

/// Where patch nodes go: each under its part, or, with instancing, those
/// whose mesh is drawn more than once into instanced nodes.
enum Placer {
    /// A node per patch.
    Nodes,
    /// Patches of meshes used more than once become instances.
    Instancing {
        /// Patches drawing each glTF mesh, by mesh index.
        uses: HashMap<usize, usize>,
        /// The instances so far.
        groups: InstanceGroups,
    },
}

/// How many patches draw each glTF mesh, by mesh index: every mesh written
/// (in the order the node pass finds them again).
fn count_uses<'a>(
    root: &mut json::Root,
    writer: &mut MeshWriter<'a>,
    materials: &[Option<json::Index<json::Material>>; 3],
    scene: &'a Scene,
) -> Result<HashMap<usize, usize>, ExportError> {
    let mut uses = HashMap::new();
    for vessel in &scene.vessels {
        for node in &vessel.nodes {
            let slot = MaterialKind::of(node).slot();
            let entity = format!("{}/{}", vessel.tag, node.id);
            for patch in node.patches.iter().filter(|p| !is_empty(&p.mesh)) {
                let (mesh, _) = writer.mesh(root, patch, (materials[slot], slot), &entity)?;
                *uses.entry(mesh.value()).or_insert(0) += 1;
            }
        }
    }
    Ok(uses)
}

/// The meshes written so far: each distinct mesh once, whichever patches use
/// it.
struct MeshWriter<'a> {
    buffers: MeshBuffers<'a>,
    /// The written mesh of each mesh object seen (by address).
    by_pointer: HashMap<*const PackedMesh, usize>,
    /// The written meshes by content hash (equal meshes built apart).
    by_content: HashMap<u64, Vec<usize>>,
    /// Each written mesh, its glTF mesh per material slot, and its patch
    /// node's dequantization transform.
    written: Vec<WrittenMesh<'a>>,
}

/// One distinct mesh in the file.
struct WrittenMesh<'a> {
    mesh: &'a PackedMesh,
    accessors: PrimitiveAccessors,
    dequantization: Dequantization,
    gltf: [Option<json::Index<json::Mesh>>; 3],
}

impl<'a> MeshWriter<'a> {
    /// The glTF mesh of `mesh` drawn with `material` (in `slot`), and the
    /// patch node's dequantization transform: pushed on first use; with
    /// `reuse`, found again for an equal mesh.
    fn mesh(
        &mut self,
        root: &mut json::Root,
        patch: &'a ScenePatch,
        (material, slot): (Option<json::Index<json::Material>>, usize),
        entity: &str,
    ) -> Result<(json::Index<json::Mesh>, Dequantization), ExportError> {
        let (mesh, reuse) = (&patch.mesh, self.buffers.options().reuse);
        let found = if reuse { self.find(mesh) } else { None };
        let k = match found {
            Some(k) => k,
            None => {
                let (accessors, dequantization) =
                    self.buffers.push(root, mesh, entity, &patch.name)?;
                self.written.push(WrittenMesh {
                    mesh,
                    accessors,
                    dequantization,
                    gltf: [None; 3],
                });
                let k = self.written.len() - 1;
                if reuse {
                    self.by_pointer.insert(Arc::as_ptr(mesh), k);
                    self.by_content
                        .entry(content_hash(mesh))
                        .or_default()
                        .push(k);
                }
                k
            }
        };
        let written = &mut self.written[k];
        let index = match written.gltf[slot] {
            Some(index) => index,
            None => {
                let a = written.accessors;
                let primitive = json::mesh::Primitive {
                    attributes: [
                        Some((Checked::Valid(Semantic::Positions), a.positions)),
                        a.normals.map(|n| (Checked::Valid(Semantic::Normals), n)),
                    ]
                    .into_iter()
                    .flatten()
                    .collect(),
                    extensions: None,
                    extras: None,
                    indices: Some(a.indices),
                    material,
                    mode: Checked::Valid(Mode::Triangles),
                    targets: None,
                };
                let index = root.push(json::Mesh {
                    extensions: None,
                    extras: None,
                    // Compact files leave the name out: the patch nodes name
                    // what they draw.
                    name: (!self.buffers.options().is_compact())
                        .then(|| format!("{entity}/{}", patch.name)),
                    primitives: vec![primitive],
                    weights: None,
                });
                written.gltf[slot] = Some(index);
                index
            }
        };
        Ok((index, written.dequantization))
    }

    /// The written mesh equal to `mesh`, if any.
    fn find(&mut self, mesh: &Arc<PackedMesh>) -> Option<usize> {
        if let Some(&k) = self.by_pointer.get(&Arc::as_ptr(mesh)) {
            return Some(k);
        }
        let candidates = self.by_content.get(&content_hash(mesh))?;
        let k = candidates
            .iter()
            .copied()
            .find(|&k| *self.written[k].mesh == **mesh)?;
        self.by_pointer.insert(Arc::as_ptr(mesh), k);
        Some(k)
    }
}

/// A hash of everything a mesh writes: positions, normals, indices.
fn content_hash(mesh: &PackedMesh) -> u64 {
    let mut h = rustc_hash::FxHasher::default();
    mesh.vertex_count().hash(&mut h);
    for p in mesh.positions() {
        p.to_array().map(f64::to_bits).hash(&mut h);
    }
    mesh.oct_normals().hash(&mut h);
    for i in mesh.indices() {
        i.hash(&mut h);
    }
    h.finish()
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
fn push_vessel<'a>(
    root: &mut json::Root,
    (writer, placer): (&mut MeshWriter<'a>, &mut Placer),
    materials: &[Option<json::Index<json::Material>>; 3],
    vessel: &'a SceneVessel,
) -> Result<json::Index<json::Node>, ExportError> {
    let index = root.push(json::Node {
        name: Some(vessel.tag.clone()),
        extras: raw(&vessel.extras)?,
        ..transformed(&vessel.frame)
    });
    let mut children = Vec::with_capacity(vessel.nodes.len());
    for node in &vessel.nodes {
        let slot = MaterialKind::of(node).slot();
        children.push(push_node(
            root,
            (writer, placer),
            (materials[slot], slot),
            vessel,
            node,
        )?);
    }
    set_children(root, index, children);
    Ok(index)
}

/// Pushes a part or nozzle node and its patch nodes; returns its index.
fn push_node<'a>(
    root: &mut json::Root,
    (writer, placer): (&mut MeshWriter<'a>, &mut Placer),
    (material, slot): (Option<json::Index<json::Material>>, usize),
    vessel: &SceneVessel,
    node: &'a SceneNode,
) -> Result<json::Index<json::Node>, ExportError> {
    let tag = &vessel.tag;
    let index = root.push(json::Node {
        name: Some(node.id.clone()),
        extras: raw(&node.extras)?,
        ..transformed(&node.frame)
    });
    let entity = format!("{tag}/{}", node.id);
    let mut children = Vec::with_capacity(node.patches.len());
    for patch in node.patches.iter().filter(|p| !is_empty(&p.mesh)) {
        let (mesh, dequantization) = writer.mesh(root, patch, (material, slot), &entity)?;
        if let Placer::Instancing { uses, groups } = placer
            && uses.get(&mesh.value()).is_some_and(|&n| n > 1)
        {
            let world = vessel.frame * node.frame;
            groups.add(
                mesh,
                format!("{entity}/{}", patch.name),
                &world,
                dequantization,
            );
            continue;
        }
        children.push(root.push(json::Node {
            name: Some(patch.name.clone()),
            mesh: Some(mesh),
            translation: dequantization.map(|(t, _)| t),
            scale: dequantization.map(|(_, s)| [s; 3]),
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
