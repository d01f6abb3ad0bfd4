//! Packing meshes into the glTF binary buffer: a view per stream (element
//! layout), the accessors of every mesh, and the `BIN` chunk's bytes.
//!
//! Part of the glTF writer: [`super::gltf_document`] hands every distinct patch
//! mesh to [`MeshBuffers::push`], which checks it (so a file is never written
//! with NaNs or indices out of range), encodes it ([`super::gltf_encoding`]:
//! plain `f32` metres and `u32` indices, or quantized) and appends it to its
//! streams; [`MeshBuffers::finish`] then appends the buffer and one view per
//! non-empty stream — plain files have three, all positions, all normals, all
//! indices, in that order, each 4-byte aligned — and returns the bytes of the
//! GLB `BIN` chunk. With meshopt compression each view's bytes are encoded on
//! their own (`EXT_meshopt_compression`): the `BIN` chunk holds the encoded
//! views and a second buffer, without data, the uncompressed layout the views
//! and accessors describe.

use glam::{DVec3, Vec3};
use gltf_json as json;
use json::accessor::{ComponentType, GenericComponentType, Type};
use json::buffer::{Stride, Target};
use json::validation::{Checked, USize64};
use serde_json::Value;

use super::error::ExportError;
use super::glb_options::{Compression, GlbOptions};
use super::gltf_encoding::{Dequantization, Encoding, Stream, metres, unit_normal};
use crate::mesh::PackedMesh;

/// The accessors of one mesh primitive.
#[derive(Clone, Copy, Debug)]
pub(super) struct PrimitiveAccessors {
    /// `POSITION` accessor.
    pub positions: json::Index<json::Accessor>,
    /// `NORMAL` accessor, when normals are written.
    pub normals: Option<json::Index<json::Accessor>>,
    /// Triangle index accessor.
    pub indices: json::Index<json::Accessor>,
}

/// The buffer's streams as they grow, and the meshes in them.
pub(super) struct MeshBuffers<'a> {
    /// The bytes of each stream ([`Stream::ALL`] order), unless laying out only.
    /// The instancing stream's bytes are kept even then: they are few, and
    /// the streaming writer takes them from [`FinishedBuffers::instances`].
    streams: [Vec<u8>; Stream::COUNT],
    /// Bytes of each stream so far (kept whether or not the bytes are).
    lengths: [usize; Stream::COUNT],
    /// The accessors into each stream, to point at its view in `finish`.
    accessors: [Vec<usize>; Stream::COUNT],
    /// Every mesh written, in order, with its encoding: what the streaming
    /// writer writes.
    meshes: Vec<(&'a PackedMesh, Encoding)>,
    /// How compact the file is.
    options: GlbOptions,
    /// Lay out only: count the bytes without keeping them, for the streaming
    /// writer ([`super::glb_stream`]), which writes them straight from the meshes.
    layout_only: bool,
}

/// The buffer of a finished document: the `BIN` chunk's bytes, and the
/// extensions to add to the JSON (meshopt views and their fallback buffer).
#[derive(Default)]
pub(super) struct FinishedBuffers {
    /// The `BIN` chunk (empty when laid out only or without triangles).
    pub bin: Vec<u8>,
    /// `EXT_meshopt_compression` objects of buffer views, by view index.
    pub view_extensions: Vec<(usize, Value)>,
    /// The uncompressed fallback buffer's index, when compressed.
    pub fallback_buffer: Option<usize>,
    /// The instancing stream's bytes when laid out only (the streaming writer
    /// writes them after the meshes' streams).
    pub instances: Vec<u8>,
}

impl<'a> MeshBuffers<'a> {
    /// Empty buffers for a file written with `options`.
    pub fn new(options: GlbOptions) -> Self {
        Self {
            streams: Default::default(),
            lengths: [0; Stream::COUNT],
            accessors: Default::default(),
            meshes: Vec::new(),
            options,
            layout_only: false,
        }
    }

    /// Buffers that only lay the views out: [`finish`](Self::finish) returns no
    /// bytes, but the document is the same. Not for compressed files (their
    /// layout depends on the bytes).
    pub fn layout_only(options: GlbOptions) -> Self {
        Self {
            layout_only: true,
            ..Self::new(options)
        }
    }

    /// The options the buffers are written with.
    pub fn options(&self) -> &GlbOptions {
        &self.options
    }

    /// Takes the meshes written so far, in order, with their encodings.
    pub fn take_meshes(&mut self) -> Vec<(&'a PackedMesh, Encoding)> {
        std::mem::take(&mut self.meshes)
    }

    /// Checks `mesh`, appends its data and pushes its accessors onto `root`;
    /// returns them and the patch node's dequantization transform.
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
        mesh: &'a PackedMesh,
        entity: &str,
        patch: &str,
    ) -> Result<(PrimitiveAccessors, Dequantization), ExportError> {
        check_topology(mesh, entity, patch)?;
        let vertex_error = |vertex| ExportError::NonFiniteVertex {
            entity: entity.to_string(),
            patch: patch.to_string(),
            vertex,
        };
        let oct = mesh.oct_normals();
        let (mut lo, mut hi) = (DVec3::INFINITY, DVec3::NEG_INFINITY);
        for (vertex, p) in mesh.positions().enumerate() {
            if unit_normal(oct[vertex].decode()).is_none() || !metres(p).is_finite() {
                return Err(vertex_error(vertex));
            }
            lo = lo.min(p);
            hi = hi.max(p);
        }
        let encoding = Encoding::of(mesh, (lo, hi), &self.options);
        let count = encoding.vertex_count(mesh);
        let index_count = encoding.index_count(mesh);
        let streams = encoding.streams();
        let offsets = streams.map(|s| s.map_or(0, |s| self.lengths[s.slot()]));
        for (stream, n) in streams.into_iter().zip([count, count, index_count]) {
            let Some(stream) = stream else { continue };
            self.lengths[stream.slot()] += stream.stride() * n;
            if !self.layout_only {
                encoding.write(stream, mesh, &mut self.streams[stream.slot()]);
            }
        }
        // Every element is 2 or 4 bytes aligned within its stream, and every
        // stream's view starts on a multiple of 4: accessors stay aligned.
        let (lo, hi) = encoding.position_bounds((lo, hi));
        let [ps, ns, is] = streams;
        let positions = root.push(json::Accessor {
            min: Some(Value::from(lo.to_vec())),
            max: Some(Value::from(hi.to_vec())),
            ..accessor(
                offsets[0],
                count,
                Type::Vec3,
                if ps == Some(Stream::PositionsU16) {
                    ComponentType::U16
                } else {
                    ComponentType::F32
                },
                false,
            )
        });
        let normals = ns.map(|ns| {
            root.push(accessor(
                offsets[1],
                count,
                Type::Vec3,
                if ns == Stream::NormalsI8 {
                    ComponentType::I8
                } else {
                    ComponentType::F32
                },
                ns == Stream::NormalsI8,
            ))
        });
        let indices = root.push(accessor(
            offsets[2],
            index_count,
            Type::Scalar,
            if is == Some(Stream::Indices16) {
                ComponentType::U16
            } else {
                ComponentType::U32
            },
            false,
        ));
        for (stream, a) in [(ps, Some(positions)), (ns, normals), (is, Some(indices))] {
            if let (Some(stream), Some(a)) = (stream, a) {
                self.accessors[stream.slot()].push(a.value());
            }
        }
        let dequantization = encoding.dequantization();
        self.meshes.push((mesh, encoding));
        Ok((
            PrimitiveAccessors {
                positions,
                normals,
                indices,
            },
            dequantization,
        ))
    }

    /// Appends `EXT_mesh_gpu_instancing` attribute data — `f32` elements of
    /// `type_` (`VEC3` translations or scales, `VEC4` rotations), tightly
    /// packed — and pushes its accessor onto `root`.
    pub fn push_instances(
        &mut self,
        root: &mut json::Root,
        type_: Type,
        elements: &[f32],
    ) -> json::Index<json::Accessor> {
        let stream = Stream::Instances;
        let width = match type_ {
            Type::Vec4 => 4,
            _ => 3,
        };
        let offset = self.lengths[stream.slot()];
        let bytes = &mut self.streams[stream.slot()];
        for x in elements {
            bytes.extend_from_slice(&x.to_le_bytes());
        }
        self.lengths[stream.slot()] = bytes.len();
        let index = root.push(accessor(
            offset,
            elements.len() / width,
            type_,
            ComponentType::F32,
            false,
        ));
        self.accessors[stream.slot()].push(index.value());
        index
    }

    /// Pushes the buffer(s) and a view per non-empty stream onto `root` (which
    /// must hold no views yet), points the accessors at their views, and returns
    /// the binary chunk's bytes with the extensions the JSON needs. Pushes
    /// nothing and returns no bytes when no mesh was added.
    ///
    /// # Errors
    ///
    /// [`ExportError::TooLarge`] when the buffer passes the GLB's 4 GiB limit.
    pub fn finish(self, root: &mut json::Root) -> Result<FinishedBuffers, ExportError> {
        let total: usize = self.lengths.iter().map(|&l| padded4(l)).sum();
        if total == 0 {
            return Ok(FinishedBuffers::default());
        }
        let too_large = |bytes: usize| ExportError::TooLarge {
            bytes: bytes as u64,
        };
        if u32::try_from(total).is_err() {
            return Err(too_large(total));
        }
        let compressed = self.options.compress == Compression::Meshopt;
        let mut out = FinishedBuffers::default();
        // Compressed: the BIN chunk (buffer 0) holds the encoded views; buffer 1
        // is the uncompressed layout, with no data, that the views describe.
        let (encoded, bin_length) = if compressed {
            let encoded: Vec<Option<Vec<u8>>> = Stream::ALL
                .iter()
                .zip(&self.streams)
                .map(|(&stream, bytes)| (!bytes.is_empty()).then(|| encode_view(stream, bytes)))
                .collect();
            let length = encoded.iter().flatten().map(|e| padded4(e.len())).sum();
            (encoded, length)
        } else {
            (Vec::new(), total)
        };
        let bin_buffer = root.push(json::Buffer {
            byte_length: USize64::from(bin_length),
            name: None,
            uri: None,
            extensions: None,
            extras: None,
        });
        let view_buffer = if compressed {
            let fallback = root.push(json::Buffer {
                byte_length: USize64::from(total),
                name: None,
                uri: None,
                extensions: None,
                extras: None,
            });
            out.fallback_buffer = Some(fallback.value());
            fallback
        } else {
            bin_buffer
        };
        if !self.layout_only {
            out.bin.reserve(bin_length);
        }
        let mut offset = 0;
        for (k, stream) in Stream::ALL.into_iter().enumerate() {
            let length = self.lengths[k];
            if length == 0 {
                continue;
            }
            let view = root.push(json::buffer::View {
                buffer: view_buffer,
                byte_length: USize64::from(length),
                byte_offset: Some(USize64::from(offset)),
                byte_stride: stream.is_vertex().then_some(Stride(stream.stride())),
                name: None,
                target: if stream.is_index() {
                    Some(Checked::Valid(Target::ElementArrayBuffer))
                } else {
                    stream
                        .is_vertex()
                        .then_some(Checked::Valid(Target::ArrayBuffer))
                },
                extensions: None,
                extras: None,
            });
            for &a in &self.accessors[k] {
                root.accessors[a].buffer_view = Some(view);
            }
            if let Some(Some(bytes)) = encoded.get(k) {
                let mut extension = serde_json::json!({
                    "buffer": bin_buffer.value(),
                    "byteOffset": out.bin.len(),
                    "byteLength": bytes.len(),
                    "byteStride": stream.stride(),
                    "mode": if stream.is_index() { "TRIANGLES" } else { "ATTRIBUTES" },
                    "count": length / stream.stride(),
                });
                if stream == Stream::NormalsI8 {
                    extension["filter"] = serde_json::json!("OCTAHEDRAL");
                }
                out.view_extensions.push((view.value(), extension));
                out.bin.extend_from_slice(bytes);
                out.bin.resize(padded4(out.bin.len()), 0);
            } else if !self.layout_only {
                out.bin.extend_from_slice(&self.streams[k]);
                out.bin.resize(padded4(out.bin.len()), 0);
            } else if stream == Stream::Instances {
                out.instances = self.streams[k].clone();
            }
            offset += padded4(length);
        }
        Ok(out)
    }
}

/// A stream's bytes in meshoptimizer's encoding: the vertex codec (version 0,
/// the one `EXT_meshopt_compression` specifies) for attributes, the triangle
/// codec for indices. Byte normals go through the `OCTAHEDRAL` filter first
/// (two 8-bit octahedral coordinates and a constant, which the decoder turns
/// back into normalized bytes): on the example drum merged per vessel its
/// normals took 17.3 KB as `x, y, z` bytes.
fn encode_view(stream: Stream, bytes: &[u8]) -> Vec<u8> {
    fn vertices<const N: usize>(bytes: &[u8]) -> Vec<u8> {
        let elements: Vec<[u8; N]> = bytes
            .chunks_exact(N)
            .map(|c| c.try_into().unwrap_or([0; N]))
            .collect();
        // Encoding into a buffer of the bound's size cannot fail.
        meshopt::encode_vertex_buffer_level(&elements, 2, Some(0)).unwrap_or_default()
    }
    match stream {
        Stream::PositionsF32 | Stream::NormalsF32 => vertices::<12>(bytes),
        Stream::PositionsU16 => vertices::<8>(bytes),
        Stream::NormalsI8 => {
            let unit: Vec<[f32; 4]> = bytes
                .chunks_exact(4)
                .map(|c| {
                    let n = Vec3::new(
                        f32::from(c[0] as i8),
                        f32::from(c[1] as i8),
                        f32::from(c[2] as i8),
                    )
                    .normalize_or(Vec3::Z);
                    [n.x, n.y, n.z, 0.0]
                })
                .collect();
            let oct = meshopt::encode_filter_oct::<i8>(&unit, 8);
            let oct: Vec<u8> = oct.iter().flatten().map(|&c| c as u8).collect();
            vertices::<4>(&oct)
        }
        Stream::Instances => vertices::<4>(bytes),
        Stream::Indices32 | Stream::Indices16 => {
            let indices: Vec<u32> = if stream == Stream::Indices16 {
                bytes
                    .chunks_exact(2)
                    .map(|c| u32::from(u16::from_le_bytes([c[0], c[1]])))
                    .collect()
            } else {
                bytes
                    .chunks_exact(4)
                    .map(|c| u32::from_le_bytes([c[0], c[1], c[2], c[3]]))
                    .collect()
            };
            let vertices = indices.iter().max().map_or(0, |&m| m as usize + 1);
            meshopt::encode_index_buffer(&indices, vertices).unwrap_or_default()
        }
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

/// A tightly packed accessor at `offset` of its stream's view (set by
/// [`MeshBuffers::finish`]).
fn accessor(
    offset: usize,
    count: usize,
    type_: Type,
    component: ComponentType,
    normalized: bool,
) -> json::Accessor {
    json::Accessor {
        buffer_view: None,
        byte_offset: Some(USize64::from(offset)),
        count: USize64::from(count),
        component_type: Checked::Valid(GenericComponentType(component)),
        extensions: None,
        extras: None,
        type_: Checked::Valid(type_),
        min: None,
        max: None,
        name: None,
        normalized,
        sparse: None,
    }
}

/// `len` rounded up to a multiple of 4.
fn padded4(len: usize) -> usize {
    len.div_ceil(4) * 4
}
