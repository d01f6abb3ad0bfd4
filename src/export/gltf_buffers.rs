//! Packing meshes into the glTF binary buffer: `f32` positions in metres, unit
//! `f32` normals and `u32` indices, with their accessors and buffer views.
//!
//! Part of the glTF writer: [`super::gltf_document`] hands every non-empty patch
//! mesh to [`MeshBuffers::push`], then [`MeshBuffers::finish`] appends one buffer
//! and three buffer views — all positions, all normals, all indices, in that order,
//! each 4-byte aligned — and returns the bytes of the GLB `BIN` chunk. This is where
//! the model's `f64` mm become the file's `f32` m; meshes are checked on the way, so
//! a file is never written with NaNs or indices out of range.

use glam::{DVec3, Vec3};
use gltf_json as json;
use json::accessor::{ComponentType, GenericComponentType, Type};
use json::buffer::{Stride, Target};
use json::validation::{Checked, USize64};
use serde_json::Value;

use super::error::ExportError;
use crate::mesh::PackedMesh;

/// Millimetres → metres.
pub(super) const MM_TO_M: f64 = 1e-3;

/// Index of the positions view, the first one [`MeshBuffers::finish`] pushes.
const POSITIONS_VIEW: u32 = 0;
/// Index of the normals view.
const NORMALS_VIEW: u32 = 1;
/// Index of the indices view.
const INDICES_VIEW: u32 = 2;

/// The accessors of one mesh primitive.
#[derive(Clone, Copy, Debug)]
pub(super) struct PrimitiveAccessors {
    /// `POSITION` accessor.
    pub positions: json::Index<json::Accessor>,
    /// `NORMAL` accessor.
    pub normals: json::Index<json::Accessor>,
    /// Triangle index accessor.
    pub indices: json::Index<json::Accessor>,
}

/// The three growing views of the binary buffer.
#[derive(Default)]
pub(super) struct MeshBuffers {
    positions: Vec<u8>,
    normals: Vec<u8>,
    indices: Vec<u8>,
    /// Bytes of each view so far (kept whether or not the bytes are).
    lengths: [usize; 3],
    /// Lay out only: count the bytes without keeping them, for the streaming
    /// writer ([`super::glb_stream`]), which writes them straight from the meshes.
    layout_only: bool,
}

impl MeshBuffers {
    /// Buffers that only lay the views out: [`finish`](Self::finish) returns no
    /// bytes, but the document is the same.
    pub fn layout_only() -> Self {
        Self {
            layout_only: true,
            ..Self::default()
        }
    }
}

impl MeshBuffers {
    /// Checks `mesh`, appends its data and pushes its accessors onto `root`.
    /// `entity` (`tag/id`) and `patch` name the mesh in errors.
    ///
    /// # Errors
    ///
    /// [`ExportError::MalformedMesh`] for mismatched counts or indices out of
    /// range; [`ExportError::NonFiniteVertex`] for a non-finite position or a
    /// non-finite or zero normal.
    pub fn push(
        &mut self,
        root: &mut json::Root,
        mesh: &PackedMesh,
        entity: &str,
        patch: &str,
    ) -> Result<PrimitiveAccessors, ExportError> {
        check_topology(mesh, entity, patch)?;
        let vertex_error = |vertex| ExportError::NonFiniteVertex {
            entity: entity.to_string(),
            patch: patch.to_string(),
            vertex,
        };
        let count = mesh.vertex_count();
        let [position_offset, normal_offset, index_offset] = self.lengths;
        self.lengths[0] += 12 * count;
        self.lengths[1] += 12 * count;
        self.lengths[2] += 4 * mesh.index_count();
        let keep = !self.layout_only;
        let mut lo = Vec3::splat(f32::INFINITY);
        let mut hi = Vec3::splat(f32::NEG_INFINITY);
        for (vertex, p) in mesh.positions().enumerate() {
            let n = mesh.normal(vertex);
            let p = metres(p);
            let n = unit_normal(n).ok_or_else(|| vertex_error(vertex))?;
            if !p.is_finite() {
                return Err(vertex_error(vertex));
            }
            lo = lo.min(p);
            hi = hi.max(p);
            if keep {
                extend_vec3(&mut self.positions, p);
                extend_vec3(&mut self.normals, n);
            }
        }
        if keep {
            for i in mesh.indices() {
                self.indices.extend_from_slice(&i.to_le_bytes());
            }
        }
        let positions = root.push(json::Accessor {
            min: Some(vec3_value(lo)),
            max: Some(vec3_value(hi)),
            ..accessor(
                POSITIONS_VIEW,
                position_offset,
                count,
                Type::Vec3,
                ComponentType::F32,
            )
        });
        let normals = root.push(accessor(
            NORMALS_VIEW,
            normal_offset,
            count,
            Type::Vec3,
            ComponentType::F32,
        ));
        let indices = root.push(accessor(
            INDICES_VIEW,
            index_offset,
            mesh.index_count(),
            Type::Scalar,
            ComponentType::U32,
        ));
        Ok(PrimitiveAccessors {
            positions,
            normals,
            indices,
        })
    }

    /// Pushes the buffer and its three views onto `root` (which must hold no views
    /// yet) and returns the binary chunk's bytes. Pushes nothing and returns no
    /// bytes when no mesh was added.
    ///
    /// # Errors
    ///
    /// [`ExportError::TooLarge`] when the buffer passes the GLB's 4 GiB limit.
    pub fn finish(self, root: &mut json::Root) -> Result<Vec<u8>, ExportError> {
        let total: usize = self.lengths.iter().sum();
        if total == 0 {
            return Ok(Vec::new());
        }
        if u32::try_from(total).is_err() {
            return Err(ExportError::TooLarge {
                bytes: total as u64,
            });
        }
        let buffer = root.push(json::Buffer {
            byte_length: USize64::from(total),
            name: None,
            uri: None,
            extensions: None,
            extras: None,
        });
        let mut bin = Vec::with_capacity(if self.layout_only { 0 } else { total });
        let views = [
            (self.positions, Some(Stride(12)), Target::ArrayBuffer),
            (self.normals, Some(Stride(12)), Target::ArrayBuffer),
            (self.indices, None, Target::ElementArrayBuffer),
        ];
        let mut offset = 0;
        for ((bytes, stride, target), length) in views.into_iter().zip(self.lengths) {
            root.push(json::buffer::View {
                buffer,
                byte_length: USize64::from(length),
                byte_offset: Some(USize64::from(offset)),
                byte_stride: stride,
                name: None,
                target: Some(Checked::Valid(target)),
                extensions: None,
                extras: None,
            });
            offset += length;
            bin.extend_from_slice(&bytes);
        }
        Ok(bin)
    }
}

/// Checks counts and index ranges of a mesh.
fn check_topology(mesh: &PackedMesh, entity: &str, patch: &str) -> Result<(), ExportError> {
    let malformed = |rule: String| ExportError::MalformedMesh {
        entity: entity.to_string(),
        patch: patch.to_string(),
        rule,
    };
    let count = mesh.vertex_count();
    if mesh.normal_count() != count {
        return Err(malformed(format!(
            "{} normals for {count} positions",
            mesh.normal_count()
        )));
    }
    if !mesh.index_count().is_multiple_of(3) {
        return Err(malformed(format!(
            "{} indices is not a whole number of triangles",
            mesh.index_count()
        )));
    }
    if let Some(bad) = mesh.indices().find(|&i| i as usize >= count) {
        return Err(malformed(format!("index {bad} with {count} vertices")));
    }
    Ok(())
}

/// A position in mm as `f32` metres.
pub(super) fn metres(p: DVec3) -> Vec3 {
    (p * MM_TO_M).as_vec3()
}

/// A normal as a unit `f32` vector, renormalized after the conversion; `None` when
/// it is not finite or (nearly) zero.
pub(super) fn unit_normal(n: DVec3) -> Option<Vec3> {
    n.as_vec3().try_normalize()
}

/// Appends the little-endian bytes of a vector.
fn extend_vec3(bytes: &mut Vec<u8>, v: Vec3) {
    for c in v.to_array() {
        bytes.extend_from_slice(&c.to_le_bytes());
    }
}

/// A `VEC3` min or max as JSON: each `f32` widened exactly to `f64`, so the
/// written number reads back as the very `f32` in the buffer.
fn vec3_value(v: Vec3) -> Value {
    Value::from(v.to_array().map(f64::from).to_vec())
}

/// A tightly packed accessor into one of the three views.
fn accessor(
    view: u32,
    offset: usize,
    count: usize,
    type_: Type,
    component: ComponentType,
) -> json::Accessor {
    json::Accessor {
        buffer_view: Some(json::Index::new(view)),
        byte_offset: Some(USize64::from(offset)),
        count: USize64::from(count),
        component_type: Checked::Valid(GenericComponentType(component)),
        extensions: None,
        extras: None,
        type_: Checked::Valid(type_),
        min: None,
        max: None,
        name: None,
        normalized: false,
        sparse: None,
    }
}
