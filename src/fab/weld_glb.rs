//! The weld map as a GLB for the viewer: each weld a node with one line
//! primitive (`LINE_LOOP` for closed curves, `LINE_STRIP` otherwise) in a
//! material coloured by its UW-3 category — A red, B blue, C green, D orange,
//! attachments grey — under a root node turned like the main export's (plant
//! Z-up → glTF Y-up, metres), so the file overlays the vessel's GLB.
//!
//! Extras let a viewer step through fabrication by level: each weld node has
//! `{weld, category, kind, length_mm, operation, level}` (the operation that
//! makes it and its level), and the root node has `{kind: "weld_map", levels,
//! operations: [{id, level, item}]}` — every operation of the plan. The main
//! GLB carries levels on its part and nozzle nodes and the seams as lines
//! with `vesselcad build --fab` ([`super::scene_levels`], [`super::seam_glb`]).

use crate::export::{ExportError, glb_container};
use std::f32::consts::FRAC_1_SQRT_2;

use glam::DAffine3;
use gltf_json as json;
use json::accessor::{ComponentType, GenericComponentType, Type};
use json::material::{PbrBaseColorFactor, PbrMetallicRoughness, StrengthFactor};
use json::mesh::{Mode, Semantic};
use json::scene::UnitQuaternion;
use json::validation::{Checked, USize64};
use serde_json::json;

use super::process::ProcessPlan;
use super::welds::{Category, Weld, WeldKind};

/// The rotation of the root node: plant Z-up to glTF Y-up (as `export`).
const Y_UP: [f32; 4] = [-FRAC_1_SQRT_2, 0.0, 0.0, FRAC_1_SQRT_2];

/// Colours by category slot: A, B, C, D, none.
const COLOURS: [(&str, [f32; 4]); 5] = [
    ("category A", [0.85, 0.1, 0.1, 1.0]),
    ("category B", [0.1, 0.3, 0.9, 1.0]),
    ("category C", [0.1, 0.65, 0.2, 1.0]),
    ("category D", [0.95, 0.55, 0.05, 1.0]),
    ("attachment", [0.5, 0.5, 0.5, 1.0]),
];

fn slot(c: Option<Category>) -> usize {
    match c {
        Some(Category::A) => 0,
        Some(Category::B) => 1,
        Some(Category::C) => 2,
        Some(Category::D) => 3,
        None => 4,
    }
}

/// The operation kind that makes a weld of `kind`.
pub fn operation_kind(kind: WeldKind) -> &'static str {
    match kind {
        WeldKind::LongSeam => "weld_long_seam",
        WeldKind::CircSeam => "weld_circ_seam",
        WeldKind::Nozzle => "fit_weld_nozzle",
        WeldKind::Flange => "weld_flange",
        WeldKind::PadInner | WeldKind::PadOuter => "weld_pad",
        WeldKind::Support => "weld_support",
    }
}

fn raw(v: &serde_json::Value) -> Option<Box<serde_json::value::RawValue>> {
    serde_json::value::to_raw_value(v).ok()
}

/// The weld map of `plan` as GLB bytes; `frame` maps the vessel frame into
/// the plant frame.
///
/// # Errors
///
/// [`ExportError::TooLarge`] past the format's 4 GiB.
pub fn weld_glb(plan: &ProcessPlan, frame: DAffine3) -> Result<Vec<u8>, ExportError> {
    let mut root = json::Root {
        asset: json::Asset {
            generator: Some(format!("vesselcad {} weld map", env!("CARGO_PKG_VERSION"))),
            ..Default::default()
        },
        ..Default::default()
    };
    let materials: Vec<_> = COLOURS
        .iter()
        .map(|(name, rgba)| {
            root.push(json::Material {
                name: Some((*name).to_string()),
                pbr_metallic_roughness: PbrMetallicRoughness {
                    base_color_factor: PbrBaseColorFactor(*rgba),
                    metallic_factor: StrengthFactor(0.0),
                    ..Default::default()
                },
                ..Default::default()
            })
        })
        .collect();
    let drawn: Vec<&Weld> = plan.welds.iter().filter(|w| w.path.len() >= 2).collect();
    let mut bin: Vec<u8> = Vec::new();
    let buffer = root.push(json::Buffer {
        byte_length: USize64(0),
        name: None,
        uri: None,
        extensions: None,
        extras: None,
    });
    let mut children = Vec::new();
    for w in &drawn {
        let points: Vec<[f32; 3]> = w
            .path
            .iter()
            .map(|p| (frame.transform_point3(*p) * 1e-3).as_vec3().to_array())
            .collect();
        let (mut min, mut max) = ([f32::MAX; 3], [f32::MIN; 3]);
        for p in &points {
            for ((lo, hi), c) in min.iter_mut().zip(max.iter_mut()).zip(p) {
                *lo = lo.min(*c);
                *hi = hi.max(*c);
            }
        }
        let offset = bin.len();
        for p in &points {
            for c in p {
                bin.extend_from_slice(&c.to_le_bytes());
            }
        }
        let view = root.push(json::buffer::View {
            buffer,
            byte_length: USize64::from(points.len() * 12),
            byte_offset: Some(USize64::from(offset)),
            byte_stride: None,
            name: None,
            target: Some(Checked::Valid(json::buffer::Target::ArrayBuffer)),
            extensions: None,
            extras: None,
        });
        let accessor = root.push(json::Accessor {
            buffer_view: Some(view),
            byte_offset: None,
            count: USize64::from(points.len()),
            component_type: Checked::Valid(GenericComponentType(ComponentType::F32)),
            extensions: None,
            extras: None,
            type_: Checked::Valid(Type::Vec3),
            min: Some(json!(min)),
            max: Some(json!(max)),
            name: None,
            normalized: false,
            sparse: None,
        });
        let mesh = root.push(json::Mesh {
            extensions: None,
            extras: None,
            name: Some(format!("weld {}", w.id)),
            primitives: vec![json::mesh::Primitive {
                attributes: [(Checked::Valid(Semantic::Positions), accessor)]
                    .into_iter()
                    .collect(),
                extensions: None,
                extras: None,
                indices: None,
                material: Some(materials[slot(w.category)]),
                mode: Checked::Valid(if w.closed {
                    Mode::LineLoop
                } else {
                    Mode::LineStrip
                }),
                targets: None,
            }],
            weights: None,
        });
        let op_id = format!("{}:{}", operation_kind(w.kind), w.item);
        let level = plan
            .operations
            .iter()
            .find(|o| o.id == op_id)
            .map(|o| o.level);
        children.push(root.push(json::Node {
            name: Some(format!("{}/{}", plan.vessel, w.id)),
            mesh: Some(mesh),
            extras: raw(&json!({
                "weld": w.id,
                "category": w.category.map(|c| format!("{c:?}")),
                "kind": w.kind,
                "length_mm": w.length,
                "operation": level.map(|_| op_id),
                "level": level,
            })),
            ..Default::default()
        }));
    }
    root.buffers[buffer.value()].byte_length = USize64::from(bin.len());
    let operations: Vec<_> = plan
        .operations
        .iter()
        .map(|o| json!({"id": o.id, "level": o.level, "item": o.item}))
        .collect();
    let top = root.push(json::Node {
        name: Some(format!("{} weld map", plan.vessel)),
        rotation: Some(UnitQuaternion(Y_UP)),
        children: Some(children),
        extras: raw(&json!({
            "kind": "weld_map",
            "vessel": plan.vessel,
            "up": "Y",
            "units": "m",
            "levels": plan.level_count(),
            "operations": operations,
        })),
        ..Default::default()
    });
    root.push(json::Scene {
        extensions: None,
        extras: None,
        name: Some("weld map".into()),
        nodes: vec![top],
    });
    root.scene = Some(json::Index::new(0));
    if bin.is_empty() {
        root.buffers.clear();
    }
    let text = serde_json::to_vec(&root).unwrap_or_default();
    glb_container(&text, &bin)
}
