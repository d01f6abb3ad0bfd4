//! A solved shell model as binary glTF: the deformed mid-surface (every node
//! moved by its displacement times a stated magnification), one mesh per part
//! named by its set (`V-101/S1`), with the von Mises stress at each node as a
//! vertex colour (`COLOR_0`) on a blue–cyan–green–yellow–red scale from zero to
//! the model's largest value. Quadratic elements are split at their mid-side
//! nodes (an 8-node quad into six triangles, a 6-node triangle into four) so
//! the colours follow the nodal values. The root node turns Z-up millimetres
//! into glTF's Y-up metres; the magnification and the scale's top are in the
//! asset's extras (`vesselcad_fem`).

use gltf_json as json;
use json::accessor::{ComponentType, GenericComponentType, Type};
use json::buffer::Target;
use json::mesh::{Mode, Primitive, Semantic};
use json::scene::UnitQuaternion;
use json::validation::{Checked, USize64};
use serde_json::Value;

use super::results::NodeResult;
use super::{ElementKind, FeMesh};

/// Share of the model's largest extent the largest displacement is drawn as.
pub const DRAWN_DISPLACEMENT: f64 = 0.05;

/// The colour of `t` in 0..=1 on the blue–cyan–green–yellow–red scale.
pub fn colour(t: f64) -> [f32; 3] {
    let t = if t.is_finite() {
        t.clamp(0.0, 1.0)
    } else {
        0.0
    };
    let stops = [
        [0.0, 0.0, 1.0],
        [0.0, 1.0, 1.0],
        [0.0, 1.0, 0.0],
        [1.0, 1.0, 0.0],
        [1.0, 0.0, 0.0],
    ];
    let x = t * 4.0;
    let k = (x.floor() as usize).min(3);
    let f = x - k as f64;
    let (a, b) = (stops[k], stops[k + 1]);
    [0, 1, 2].map(|i| (a[i] + (b[i] - a[i]) * f) as f32)
}

/// The magnification that draws the largest displacement of `results` as
/// [`DRAWN_DISPLACEMENT`] of the model's largest extent (1 when nothing moves).
pub fn magnification(mesh: &FeMesh, results: &[NodeResult]) -> f64 {
    let (lo, hi) = mesh.nodes.iter().fold(
        (
            glam::DVec3::splat(f64::INFINITY),
            glam::DVec3::splat(f64::NEG_INFINITY),
        ),
        |(lo, hi), &p| (lo.min(p), hi.max(p)),
    );
    let extent = (hi - lo).max_element();
    let umax = results
        .iter()
        .map(|r| r.displacement.length())
        .fold(0.0, f64::max);
    if umax > 0.0 && extent.is_finite() {
        DRAWN_DISPLACEMENT * extent / umax
    } else {
        1.0
    }
}

/// The triangles of one element, as node indices, following its orientation.
fn triangles(kind: ElementKind, n: &[usize]) -> Vec<[usize; 3]> {
    match kind {
        ElementKind::Quad4 => vec![[n[0], n[1], n[2]], [n[0], n[2], n[3]]],
        ElementKind::Tri3 => vec![[n[0], n[1], n[2]]],
        ElementKind::Quad8 => vec![
            [n[0], n[4], n[7]],
            [n[1], n[5], n[4]],
            [n[2], n[6], n[5]],
            [n[3], n[7], n[6]],
            [n[4], n[5], n[6]],
            [n[4], n[6], n[7]],
        ],
        ElementKind::Tri6 => vec![
            [n[0], n[3], n[5]],
            [n[1], n[4], n[3]],
            [n[2], n[5], n[4]],
            [n[3], n[4], n[5]],
        ],
    }
}

/// The deformed model `mesh` with `results` (one per node) as GLB bytes, named
/// `tag`.
pub fn von_mises_glb(mesh: &FeMesh, results: &[NodeResult], tag: &str) -> Vec<u8> {
    let scale = magnification(mesh, results);
    let top_stress = results.iter().map(|r| r.von_mises).fold(0.0, f64::max);
    let mut root = json::Root {
        asset: json::Asset {
            generator: Some("vesselcad fem".into()),
            extras: Some(
                serde_json::value::to_raw_value(&serde_json::json!({
                    "vesselcad_fem": {
                        "displacement_magnification": scale,
                        "von_mises_max_mpa": top_stress,
                        "colours": "blue 0 MPa, cyan, green, yellow, red at von_mises_max_mpa",
                    }
                }))
                .ok()
                .unwrap_or_default(),
            ),
            ..Default::default()
        },
        ..Default::default()
    };
    let mut bin: Vec<u8> = Vec::new();
    let mut children = Vec::new();
    for (k, part) in mesh.parts.iter().enumerate() {
        // This part's nodes, renumbered.
        let mut local: std::collections::HashMap<usize, u32> = Default::default();
        let mut positions: Vec<f32> = Vec::new();
        let mut colours: Vec<f32> = Vec::new();
        let mut indices: Vec<u32> = Vec::new();
        let (mut lo, mut hi) = ([f32::MAX; 3], [f32::MIN; 3]);
        for el in mesh.elements.iter().filter(|e| e.part == k) {
            for tri in triangles(el.kind, &el.nodes) {
                for n in tri {
                    let next = local.len() as u32;
                    let id = *local.entry(n).or_insert_with(|| {
                        let r = results.get(n).copied().unwrap_or_default();
                        let p = (mesh.nodes[n] + r.displacement * scale)
                            .as_vec3()
                            .to_array();
                        for i in 0..3 {
                            lo[i] = lo[i].min(p[i]);
                            hi[i] = hi[i].max(p[i]);
                        }
                        positions.extend(p);
                        let t = if top_stress > 0.0 {
                            r.von_mises / top_stress
                        } else {
                            0.0
                        };
                        colours.extend(colour(t));
                        next
                    });
                    indices.push(id);
                }
            }
        }
        if indices.is_empty() {
            continue;
        }
        let count = local.len();
        let mut push = |bytes: &[u8], target: Target, root: &mut json::Root| {
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
        let pv = push(
            bytemuck::cast_slice(&positions),
            Target::ArrayBuffer,
            &mut root,
        );
        let cv = push(
            bytemuck::cast_slice(&colours),
            Target::ArrayBuffer,
            &mut root,
        );
        let iv = push(
            bytemuck::cast_slice(&indices),
            Target::ElementArrayBuffer,
            &mut root,
        );
        let accessor =
            |view, count: usize, type_, component, bounds: Option<([f32; 3], [f32; 3])>| {
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
            };
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
            indices.len(),
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
            name: Some(part.name.clone()),
            primitives: vec![primitive],
            weights: None,
        });
        children.push(root.push(json::Node {
            mesh: Some(mesh),
            name: Some(part.name.clone()),
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
    let top = root.push(json::Node {
        name: Some(tag.into()),
        rotation: Some(UnitQuaternion([-half, 0.0, 0.0, half])),
        scale: Some([0.001; 3]),
        children: Some(children),
        ..Default::default()
    });
    root.push(json::Scene {
        extensions: None,
        extras: None,
        name: Some(tag.into()),
        nodes: vec![top],
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
    out.extend_from_slice(&0x4E4F_534Au32.to_le_bytes());
    out.extend_from_slice(&text);
    out.extend_from_slice(&(bin.len() as u32).to_le_bytes());
    out.extend_from_slice(&0x004E_4942u32.to_le_bytes());
    out.extend_from_slice(&bin);
    out
}
