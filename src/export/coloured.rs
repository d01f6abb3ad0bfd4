//! Vertex-coloured triangle meshes as binary glTF: the writer the result maps
//! share (the FE model's von Mises colours, a scan's deviation map). Each mesh
//! becomes one node under a root node that turns Z-up millimetres into glTF's
//! Y-up metres; positions, `COLOR_0` and indices are plain `f32`/`u32`
//! accessors in one buffer.

use gltf_json as json;
use json::accessor::{ComponentType, GenericComponentType, Type};
use json::buffer::Target;
use json::mesh::{Mode, Primitive, Semantic};
use json::scene::UnitQuaternion;
use json::validation::{Checked, USize64};
use serde_json::Value;

use super::glb::{CHUNK_BIN, CHUNK_JSON};

/// One coloured triangle mesh, in millimetres (Z up).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct ColouredMesh {
    /// The glTF mesh's name.
    pub name: String,
    /// Its node's name.
    pub node: String,
    /// Vertex positions.
    pub positions: Vec<[f32; 3]>,
    /// Vertex colours (linear RGB, 0..=1), one per position.
    pub colours: Vec<[f32; 3]>,
    /// Triangles as vertex indices, three a triangle.
    pub indices: Vec<u32>,
}

/// The GLB of `meshes` under a root node named `top`; `generator` and the
/// asset's `extras` (if any) say what wrote it. Meshes without triangles are
/// left out.
pub fn coloured_glb(
    meshes: &[ColouredMesh],
    top: &str,
    generator: &str,
    extras: Option<Value>,
) -> Vec<u8> {
    let mut root = json::Root {
        asset: json::Asset {
            generator: Some(generator.into()),
            extras: extras.and_then(|e| serde_json::value::to_raw_value(&e).ok()),
            ..Default::default()
        },
        ..Default::default()
    };
    let mut bin: Vec<u8> = Vec::new();
    let mut children = Vec::new();
    for m in meshes.iter().filter(|m| !m.indices.is_empty()) {
        let (mut lo, mut hi) = ([f32::MAX; 3], [f32::MIN; 3]);
        for p in &m.positions {
            for k in 0..3 {
                lo[k] = lo[k].min(p[k]);
                hi[k] = hi[k].max(p[k]);
            }
        }
        let count = m.positions.len();
        let mut view = |bytes: &[u8], target: Target, root: &mut json::Root| {
            let offset = bin.len();
            bin.extend_from_slice(bytes);
            while !bin.len().is_multiple_of(4) {
                bin.push(0);
            }
            root.push(json::buffer::View {
                buffer: json::Index::new(0),
                byte_length: USize64::from(bytes.len()),
                byte_offset: Some(USize64::from(offset)),
                byte_stride: None,
                name: None,
                target: Some(Checked::Valid(target)),
                extensions: None,
                extras: None,
            })
        };
        let pv = view(
            bytemuck::cast_slice(&m.positions),
            Target::ArrayBuffer,
            &mut root,
        );
        let cv = view(
            bytemuck::cast_slice(&m.colours),
            Target::ArrayBuffer,
            &mut root,
        );
        let iv = view(
            bytemuck::cast_slice(&m.indices),
            Target::ElementArrayBuffer,
            &mut root,
        );
        let pa = root.push(accessor(
            pv,
            count,
            Type::Vec3,
            ComponentType::F32,
            Some((lo, hi)),
        ));
        let ca = root.push(accessor(cv, count, Type::Vec3, ComponentType::F32, None));
        let ia = root.push(accessor(
            iv,
            m.indices.len(),
            Type::Scalar,
            ComponentType::U32,
            None,
        ));
        let primitive = Primitive {
            attributes: [
                (Checked::Valid(Semantic::Positions), pa),
                (Checked::Valid(Semantic::Colors(0)), ca),
            ]
            .into_iter()
            .collect(),
            extensions: None,
            extras: None,
            indices: Some(ia),
            material: None,
            mode: Checked::Valid(Mode::Triangles),
            targets: None,
        };
        let mesh = root.push(json::Mesh {
            extensions: None,
            extras: None,
            name: Some(m.name.clone()),
            primitives: vec![primitive],
            weights: None,
        });
        children.push(root.push(json::Node {
            mesh: Some(mesh),
            name: Some(m.node.clone()),
            ..Default::default()
        }));
    }
    root.push(json::Buffer {
        byte_length: USize64::from(bin.len()),
        name: None,
        uri: None,
        extensions: None,
        extras: None,
    });
    let half = std::f32::consts::FRAC_1_SQRT_2;
    let top_node = root.push(json::Node {
        name: Some(top.into()),
        rotation: Some(UnitQuaternion([-half, 0.0, 0.0, half])),
        scale: Some([0.001; 3]),
        children: Some(children),
        ..Default::default()
    });
    root.push(json::Scene {
        extensions: None,
        extras: None,
        name: Some(top.into()),
        nodes: vec![top_node],
    });
    root.scene = Some(json::Index::new(0));
    let mut text = json::serialize::to_vec(&root).unwrap_or_default();
    while !text.len().is_multiple_of(4) {
        text.push(b' ');
    }
    let total = 12 + 8 + text.len() + 8 + bin.len();
    let mut out = Vec::with_capacity(total);
    out.extend_from_slice(b"glTF");
    out.extend_from_slice(&2u32.to_le_bytes());
    out.extend_from_slice(&(total as u32).to_le_bytes());
    out.extend_from_slice(&(text.len() as u32).to_le_bytes());
    out.extend_from_slice(&CHUNK_JSON.to_le_bytes());
    out.extend_from_slice(&text);
    out.extend_from_slice(&(bin.len() as u32).to_le_bytes());
    out.extend_from_slice(&CHUNK_BIN.to_le_bytes());
    out.extend_from_slice(&bin);
    out
}

fn accessor(
    view: json::Index<json::buffer::View>,
    count: usize,
    type_: Type,
    component: ComponentType,
    bounds: Option<([f32; 3], [f32; 3])>,
) -> json::Accessor {
    json::Accessor {
        buffer_view: Some(view),
        byte_offset: Some(USize64(0)),
        count: USize64::from(count),
        component_type: Checked::Valid(GenericComponentType(component)),
        extensions: None,
        extras: None,
        type_: Checked::Valid(type_),
        min: bounds.map(|b| Value::from(b.0.to_vec())),
        max: bounds.map(|b| Value::from(b.1.to_vec())),
        name: None,
        normalized: false,
        sparse: None,
    }
}
