//! How one patch mesh goes into the glTF buffer: which streams (element
//! layouts) it uses, its quantization step and offset, its vertex order, and the
//! bytes of each stream.
//!
//! Part of the glTF writer, below `gltf_buffers` (which lays the
//! streams out as buffer views and accessors). A mesh is encoded once, however
//! many nodes use it. Plain: `f32` metres, unit `f32` normals, `u32` indices.
//! Quantized (`KHR_mesh_quantization`): positions as `u16` offsets, in the
//! coarsest step of a power of two metres whose bound `√3/2 · step` is within the
//! budget, from an origin that is a whole number of steps — the patch node's
//! translation and uniform scale, both exact in `f32`, so decoding adds no
//! rounding — and normals as normalized bytes; a mesh wider than 65 535 steps
//! keeps `f32` positions. Compact files use
//! `u16` indices where they fit. For meshopt compression the triangles are put in
//! vertex-cache order and the vertices in first-use order (meshoptimizer's
//! `optimizeVertexCache` and `optimizeVertexFetchRemap`), which compresses better.

use glam::{DVec3, Vec3};

use super::glb_options::{Compression, GlbOptions};
use crate::mesh::PackedMesh;

/// Millimetres → metres.
pub(super) const MM_TO_M: f64 = 1e-3;

/// A position in mm as `f32` metres.
pub(super) fn metres(p: DVec3) -> Vec3 {
    (p * MM_TO_M).as_vec3()
}

/// A normal as a unit `f32` vector, renormalized after the conversion; `None` when
/// it is not finite or (nearly) zero.
pub(super) fn unit_normal(n: DVec3) -> Option<Vec3> {
    n.as_vec3().try_normalize()
}

/// Largest quantized coordinate.
const QUANTIZED_RANGE: f64 = u16::MAX as f64;

/// Largest magnitude of an origin, in steps, that `f32` holds exactly.
const F32_EXACT: f64 = (1u32 << 24) as f64;

/// A patch node's dequantization transform: translation (m) and uniform
/// scale, or `None` for a mesh written in metres.
pub(super) type Dequantization = Option<([f32; 3], f32)>;

/// One element layout of the buffer, in view order.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Stream {
    /// `f32` metres, `VEC3`.
    PositionsF32,
    /// Unit `f32` normals, `VEC3`.
    NormalsF32,
    /// `u32` triangle indices.
    Indices32,
    /// `u16` quantized positions, `VEC3` padded to 8 bytes.
    PositionsU16,
    /// Normalized `i8` normals, `VEC3` padded to 4 bytes.
    NormalsI8,
    /// `u16` triangle indices.
    Indices16,
    /// `f32` words of `EXT_mesh_gpu_instancing` attributes (translations,
    /// rotations, scales), tightly packed: no mesh writes it.
    Instances,
}

impl Stream {
    /// Every stream, in view order.
    pub const ALL: [Stream; Stream::COUNT] = [
        Stream::PositionsF32,
        Stream::NormalsF32,
        Stream::Indices32,
        Stream::PositionsU16,
        Stream::NormalsI8,
        Stream::Indices16,
        Stream::Instances,
    ];

    /// How many streams there are.
    pub const COUNT: usize = 7;

    /// Position in [`Stream::ALL`].
    pub fn slot(self) -> usize {
        self as usize
    }

    /// Bytes per element.
    pub fn stride(self) -> usize {
        match self {
            Stream::PositionsF32 | Stream::NormalsF32 => 12,
            Stream::PositionsU16 => 8,
            Stream::NormalsI8 | Stream::Indices32 | Stream::Instances => 4,
            Stream::Indices16 => 2,
        }
    }

    /// True for an index stream.
    pub fn is_index(self) -> bool {
        matches!(self, Stream::Indices32 | Stream::Indices16)
    }

    /// True for a stream of vertex attributes (a view with a stride and the
    /// `ARRAY_BUFFER` target).
    pub fn is_vertex(self) -> bool {
        !self.is_index() && self != Stream::Instances
    }
}

/// How one mesh is written.
#[derive(Clone, Debug)]
pub(super) struct Encoding {
    /// Positions quantized: origin, in steps, and the step, metres.
    pub quantized: Option<(DVec3, f64)>,
    /// Normals as bytes.
    pub byte_normals: bool,
    /// Indices as `u16`.
    pub small_indices: bool,
    /// Vertex and triangle order for compression: the old index of each new
    /// vertex, and the new indices.
    pub reorder: Option<(Vec<u32>, Vec<u32>)>,
}

impl Encoding {
    /// The encoding of `mesh` (checked: finite, indices in range) under
    /// `options`.
    /// `bounds` are the mesh's (min, max), mm.
    pub fn of(mesh: &PackedMesh, bounds: (DVec3, DVec3), options: &GlbOptions) -> Self {
        let compact = options.is_compact();
        let count = mesh.vertex_count();
        let quantized = options
            .quantize
            .and_then(|bound| quantization(bounds, bound));
        let reorder = (options.compress == Compression::Meshopt).then(|| {
            let indices: Vec<u32> = mesh.indices().collect();
            let indices = meshopt::optimize_vertex_cache(&indices, count);
            let remap = meshopt::optimize_vertex_fetch_remap(&indices, count);
            // Unused vertices (none in a mesher's output) go last, in order.
            let mut next = remap.iter().filter(|&&r| r != u32::MAX).count() as u32;
            let remap: Vec<u32> = remap
                .into_iter()
                .map(|r| {
                    if r == u32::MAX {
                        next += 1;
                        next - 1
                    } else {
                        r
                    }
                })
                .collect();
            let mut old_of_new = vec![0u32; count];
            for (old, &new) in remap.iter().enumerate() {
                old_of_new[new as usize] = old as u32;
            }
            let indices = indices.into_iter().map(|i| remap[i as usize]).collect();
            (old_of_new, indices)
        });
        Self {
            quantized,
            byte_normals: options.quantize.is_some(),
            small_indices: compact && count <= 1 << 16,
            reorder,
        }
    }

    /// The streams of positions, normals and indices.
    pub fn streams(&self) -> [Stream; 3] {
        [
            if self.quantized.is_some() {
                Stream::PositionsU16
            } else {
                Stream::PositionsF32
            },
            if self.byte_normals {
                Stream::NormalsI8
            } else {
                Stream::NormalsF32
            },
            if self.small_indices {
                Stream::Indices16
            } else {
                Stream::Indices32
            },
        ]
    }

    /// The patch node's transform that decodes quantized positions:
    /// translation (m) and uniform scale, both exact in `f32`.
    pub fn dequantization(&self) -> Dequantization {
        self.quantized
            .map(|(origin, step)| ((origin * step).as_vec3().to_array(), step as f32))
    }

    /// The old vertex index of each written vertex.
    fn vertex_order(&self, count: usize) -> Box<dyn Iterator<Item = usize> + '_> {
        match &self.reorder {
            Some((order, _)) => Box::new(order.iter().map(|&i| i as usize)),
            None => Box::new(0..count),
        }
    }

    /// The quantized position of `p` (mm).
    fn quantize(&self, p: DVec3) -> [u16; 3] {
        let (origin, step) = self.quantized.unwrap_or((DVec3::ZERO, 1.0));
        let q = (p * MM_TO_M / step - origin).round();
        q.to_array()
            .map(|c| c.clamp(0.0, f64::from(u16::MAX)) as u16)
    }

    /// The bounds of the written positions in the accessor's own numbers, from
    /// the mesh's bounds `(lo, hi)` (mm): both conversions (to `f32` metres,
    /// to quantized integers) are monotonic in each coordinate, so they map the
    /// bounds onto the bounds.
    pub fn position_bounds(&self, (lo, hi): (DVec3, DVec3)) -> ([f64; 3], [f64; 3]) {
        let convert = |p: DVec3| -> [f64; 3] {
            if self.quantized.is_some() {
                self.quantize(p).map(f64::from)
            } else {
                metres(p).to_array().map(f64::from)
            }
        };
        (convert(lo), convert(hi))
    }

    /// Appends the bytes of `mesh` in `stream` (nothing for a stream it does
    /// not use). The mesh was checked: every normal decodes.
    pub fn write(&self, stream: Stream, mesh: &PackedMesh, out: &mut Vec<u8>) {
        let [positions, normals, indices] = self.streams();
        let count = mesh.vertex_count();
        if stream == positions {
            for v in self.vertex_order(count) {
                let p = mesh.position(v);
                if self.quantized.is_some() {
                    for c in self.quantize(p) {
                        out.extend_from_slice(&c.to_le_bytes());
                    }
                    out.extend_from_slice(&[0, 0]);
                } else {
                    for c in metres(p).to_array() {
                        out.extend_from_slice(&c.to_le_bytes());
                    }
                }
            }
        } else if stream == normals {
            let oct = mesh.oct_normals();
            for v in self.vertex_order(count) {
                let n = unit_normal(oct[v].decode()).unwrap_or(Vec3::Z);
                if self.byte_normals {
                    out.extend_from_slice(&byte_normal(n).map(|c| c as u8));
                    out.push(0);
                } else {
                    for c in n.to_array() {
                        out.extend_from_slice(&c.to_le_bytes());
                    }
                }
            }
        } else if stream == indices {
            let mut put = |i: u32| {
                if self.small_indices {
                    out.extend_from_slice(&(i as u16).to_le_bytes());
                } else {
                    out.extend_from_slice(&i.to_le_bytes());
                }
            };
            match &self.reorder {
                Some((_, reordered)) => reordered.iter().for_each(|&i| put(i)),
                None => mesh.indices().for_each(put),
            }
        }
    }
}

/// The origin (in steps) and step (m) quantizing a mesh of bounds `(lo, hi)`
/// (mm) within `bound` mm, or
/// `None` when 16 bits cannot: the coarsest power-of-two step (in metres) whose
/// bound `√3/2 · step` is within `bound`, if the mesh spans at most 65 534
/// steps. Every mesh of a file has that one step and an origin on its grid, so
/// the boundary vertices that neighbouring patches of a part share land on the
/// same grid point: quantization opens no crack between them.
fn quantization((lo, hi): (DVec3, DVec3), bound: f64) -> Option<(DVec3, f64)> {
    let step = quantization_step(bound)?;
    let (lo, hi) = (lo * MM_TO_M, hi * MM_TO_M);
    let origin = (lo / step).floor();
    let span = (hi / step).ceil() - origin;
    let fits = span.max_element() <= QUANTIZED_RANGE
        && origin.abs().max_element() + QUANTIZED_RANGE + 1.0 < F32_EXACT;
    fits.then_some((origin, step))
}

/// The coarsest power of two, metres, whose [`quantization_bound`] is within
/// `bound` mm (`None` for a bound that is not positive and finite).
pub fn quantization_step(bound: f64) -> Option<f64> {
    if !(bound.is_finite() && bound > 0.0) {
        return None;
    }
    let mut step = 2f64.powi((bound * MM_TO_M * 2.0 / 3f64.sqrt()).log2().floor() as i32);
    // log2's rounding either way.
    while quantization_bound(step) > bound {
        step *= 0.5;
    }
    while quantization_bound(2.0 * step) <= bound {
        step *= 2.0;
    }
    Some(step)
}

/// The largest distance, mm, quantizing to a step of `step` metres moves a
/// point: half a step along each axis.
pub fn quantization_bound(step: f64) -> f64 {
    3f64.sqrt() * 0.5 * step / MM_TO_M * (1.0 + 1e-9)
}

/// A unit normal as three normalized bytes: of the roundings of its components
/// up or down, the one whose length is nearest 1 (then nearest the normal), so
/// that the decoded vector is a unit vector to within 8-bit precision.
fn byte_normal(n: Vec3) -> [i8; 3] {
    let scaled = n * 127.0;
    let floor = scaled.floor();
    let mut best = ([0i8; 3], f32::INFINITY);
    for bits in 0..8u32 {
        let mut c = [0.0f32; 3];
        for (k, c) in c.iter_mut().enumerate() {
            *c = (floor[k] + ((bits >> k) & 1) as f32).clamp(-127.0, 127.0);
        }
        let v = Vec3::from(c) / 127.0;
        let error = (v.length() - 1.0).abs() + 0.25 * (v.normalize_or_zero() - n).length();
        if error < best.1 {
            best = (c.map(|x| x as i8), error);
        }
    }
    best.0
}
