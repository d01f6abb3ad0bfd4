//! The deviation map as binary glTF: each envelope patch's fitted surface (the
//! design where no points fell) as a grid mesh in the plant frame, with vertex
//! colours from blue (inward) through white to red (outward). Written through
//! `gltf-json`'s types; the root node turns Z-up millimetres into glTF's Y-up
//! metres.

use gltf_json as json;
use json::accessor::{ComponentType, GenericComponentType, Type};
use json::buffer::Target;
use json::mesh::{Mode, Primitive, Semantic};
use json::scene::UnitQuaternion;
use json::validation::{Checked, USize64};
use serde_json::Value;

use super::envelope::Envelope;
use super::fit::deviation_at;
use super::inspect::Inspection;

/// Grid of each patch's mesh (u × v cells).
const CELLS: (usize, usize) = (96, 24);

/// The colour of a deviation `d` on a scale of ±`scale` mm.
pub fn colour(d: f64, scale: f64) -> [f32; 3] {
    let t = (d / scale).clamp(-1.0, 1.0) as f32;
    if t >= 0.0 {
        [1.0, 1.0 - t, 1.0 - t]
    } else {
        [1.0 + t, 1.0 + t, 1.0]
    }
}

fn view(
    root: &mut json::Root,
    offset: usize,
    length: usize,
    target: Target,
) -> json::Index<json::buffer::View> {
    root.push(json::buffer::View {
        buffer: json::Index::new(0),
        byte_length: USize64::from(length),
        byte_offset: Some(USize64::from(offset)),
        byte_stride: None,
        name: None,
        target: Some(Checked::Valid(target)),
        extensions: None,
        extras: None,
    })
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

/// The coloured deviation map of an inspection, as GLB bytes; `scale` mm is full
/// colour.
pub fn deviation_glb(envelope: &Envelope, inspection: &Inspection, scale: f64) -> Vec<u8> {
    let mut root = json::Root {
        asset: json::Asset {
            generator: Some("vesselcad scan".into()),
            ..Default::default()
        },
        ..Default::default()
    };
    let mut bin: Vec<u8> = Vec::new();
    let mut children = Vec::new();
    let scale = if scale > 0.0 { scale } else { 1.0 };
    for (index, s) in envelope.surfaces.iter().enumerate() {
        if !envelope.parts[s.part].role.is_envelope() {
            continue;
        }
        let design = &s.patch.surface;
        let fit = inspection.fits.get(index).and_then(Option::as_ref);
        let ((u0, u1), (v0, v1)) = design.domain();
        let (nu, nv) = CELLS;
        let place = envelope.frame * s.frame;
        let mut positions: Vec<f32> = Vec::new();
        let mut colours: Vec<f32> = Vec::new();
        let (mut lo, mut hi) = ([f32::MAX; 3], [f32::MIN; 3]);
        for i in 0..=nu {
            for j in 0..=nv {
                let u = u0 + (u1 - u0) * i as f64 / nu as f64;
                let v = v0 + (v1 - v0) * j as f64 / nv as f64;
                let (p, c) = match fit {
                    Some(f) => (
                        f.surface.point(u, v),
                        colour(deviation_at(design, &f.surface, u, v), scale),
                    ),
                    None => (design.point(u, v), [0.6, 0.6, 0.6]),
                };
                let p = place.transform_point3(p).as_vec3().to_array();
                for k in 0..3 {
                    lo[k] = lo[k].min(p[k]);
                    hi[k] = hi[k].max(p[k]);
                }
                positions.extend(p);
                colours.extend(c);
            }
        }
        let mut indices: Vec<u32> = Vec::new();
        let at = |i: usize, j: usize| (i * (nv + 1) + j) as u32;
        for i in 0..nu {
            for j in 0..nv {
                indices.extend([at(i, j), at(i + 1, j), at(i + 1, j + 1)]);
                indices.extend([at(i, j), at(i + 1, j + 1), at(i, j + 1)]);
            }
        }
        let count = (nu + 1) * (nv + 1);
        let mut push = |bytes: &[u8], target: Target, root: &mut json::Root| {
            let offset = bin.len();
            bin.extend_from_slice(bytes);
            while !bin.len().is_multiple_of(4) {
                bin.push(0);
            }
            view(root, offset, bytes.len(), target)
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
            name: Some(format!("{} {}", envelope.parts[s.part].id, s.patch.name)),
            primitives: vec![primitive],
            weights: None,
        });
        children.push(root.push(json::Node {
            mesh: Some(mesh),
            name: Some(format!("{}/{}", envelope.tag, envelope.parts[s.part].id)),
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
        name: Some(envelope.tag.clone()),
        rotation: Some(UnitQuaternion([-half, 0.0, 0.0, half])),
        scale: Some([0.001; 3]),
        children: Some(children),
        ..Default::default()
    });
    root.push(json::Scene {
        extensions: None,
        extras: None,
        name: Some(envelope.tag.clone()),
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
