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
//! keeps `f32` positions. Compact files write vertices that would be written
//! the same once (`gltf_welding`), in meshopt's vertex-cache and fetch order when
//! compressed, and use `u16` indices where they fit.

use glam::{DVec3, Vec3};

use super::glb_options::{Compression, GlbOptions, Normals};
use super::gltf_welding::{WrittenVertices, weld};
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
    /// Normals written.
    pub normals: bool,
    /// Normals as bytes.
    pub byte_normals: bool,
    /// Indices as `u16`.
    pub small_indices: bool,
    /// The vertices written (welded, and in compression order with meshopt)
    /// and the triangles over them, in a compact file; `None`: the mesh's own.
    pub vertices: Option<WrittenVertices>,
}

impl Encoding {
    /// The encoding of `mesh` (checked: finite, indices in range) under
    /// `options`.
    /// `bounds` are the mesh's (min, max), mm.
    pub fn of(mesh: &PackedMesh, bounds: (DVec3, DVec3), options: &GlbOptions) -> Self {
        let quantized = options
            .quantize
            .and_then(|bound| quantization(bounds, bound));
        let mut encoding = Self {
            quantized,
            normals: options.normals == Normals::Smooth,
            byte_normals: options.quantize.is_some(),
            small_indices: false,
            vertices: None,
        };
        if options.is_compact() {
            let oct = mesh.oct_normals();
            let (normals, byte_normals) = (encoding.normals, encoding.byte_normals);
            let welded = weld(mesh, |v| {
                let p = mesh.position(v);
                let position = match quantized {
                    Some(grid) => quantize(grid, p).map(u32::from),
                    None => metres(p).to_array().map(f32::to_bits),
                };
                let normal = if !normals {
                    0
                } else if byte_normals {
                    let [x, y, z] = byte_normal(unit_normal(oct[v].decode()).unwrap_or(Vec3::Z));
                    u32::from_le_bytes([x as u8, y as u8, z as u8, 0])
                } else {
                    let [a, b] = oct[v].0;
                    (u32::from(a as u16) << 16) | u32::from(b as u16)
                };
                (position, normal)
            });
            encoding.vertices = Some(if options.compress == Compression::Meshopt {
                welded.cache_ordered()
            } else {
                welded
            });
            encoding.small_indices = encoding.vertex_count(mesh) <= 1 << 16;
        }
        encoding
    }

    /// Number of vertices written.
    pub fn vertex_count(&self, mesh: &PackedMesh) -> usize {
        self.vertices
            .as_ref()
            .map_or(mesh.vertex_count(), |w| w.kept.len())
    }

    /// Number of triangle indices written.
    pub fn index_count(&self, mesh: &PackedMesh) -> usize {
        self.vertices
            .as_ref()
            .map_or(mesh.index_count(), |w| w.indices.len())
    }

    /// The streams of positions, normals (`None` when not written) and
    /// indices.
    pub fn streams(&self) -> [Option<Stream>; 3] {
        [
            Some(if self.quantized.is_some() {
                Stream::PositionsU16
            } else {
                Stream::PositionsF32
            }),
            self.normals.then_some(if self.byte_normals {
                Stream::NormalsI8
            } else {
                Stream::NormalsF32
            }),
            Some(if self.small_indices {
                Stream::Indices16
            } else {
                Stream::Indices32
            }),
        ]
    }

    /// The patch node's transform that decodes quantized positions:
    /// translation (m) and uniform scale, both exact in `f32`.
    pub fn dequantization(&self) -> Dequantization {
        self.quantized
            .map(|(origin, step)| ((origin * step).as_vec3().to_array(), step as f32))
    }

    /// The quantized position of `p` (mm).
    fn quantize(&self, p: DVec3) -> [u16; 3] {
        quantize(self.quantized.unwrap_or((DVec3::ZERO, 1.0)), p)
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
        let [positions, normals, indices] = self.streams().map(|s| s == Some(stream));
        let count = self.vertex_count(mesh);
        let kept = self.vertices.as_ref().map(|w| &w.kept[..]);
        let old = |k: usize| kept.map_or(k, |kept| kept[k] as usize);
        if positions {
            out.reserve(count * stream.stride());
            if let Some(grid) = self.quantized {
                for k in 0..count {
                    let [x, y, z] = quantize(grid, mesh.position(old(k))).map(u16::to_le_bytes);
                    out.extend_from_slice(&[x[0], x[1], y[0], y[1], z[0], z[1], 0, 0]);
                }
            } else {
                for k in 0..count {
                    let [x, y, z] = metres(mesh.position(old(k)))
                        .to_array()
                        .map(f32::to_le_bytes);
                    out.extend_from_slice(&x);
                    out.extend_from_slice(&y);
                    out.extend_from_slice(&z);
                }
            }
        } else if normals {
            out.reserve(count * stream.stride());
            let oct = mesh.oct_normals();
            for k in 0..count {
                let n = unit_normal(oct[old(k)].decode()).unwrap_or(Vec3::Z);
                if self.byte_normals {
                    let [x, y, z] = byte_normal(n).map(|c| c as u8);
                    out.extend_from_slice(&[x, y, z, 0]);
                } else {
                    for c in n.to_array() {
                        out.extend_from_slice(&c.to_le_bytes());
                    }
                }
            }
        } else if indices {
            let written = self.index_count(mesh);
            out.reserve(written * stream.stride());
            let mut put = |i: u32| {
                if self.small_indices {
                    out.extend_from_slice(&(i as u16).to_le_bytes());
                } else {
                    out.extend_from_slice(&i.to_le_bytes());
                }
            };
            match &self.vertices {
                Some(w) => w.indices.iter().for_each(|&i| put(i)),
                None => mesh.indices().for_each(put),
            }
        }
    }
}

/// The position `p` (mm) on the grid `(origin, step)` (origin in steps, step
/// in metres), clamped to 16 bits.
fn quantize((origin, step): (DVec3, f64), p: DVec3) -> [u16; 3] {
    let q = p * (MM_TO_M / step) - origin;
    q.to_array()
        .map(|c| round_half_away(c).clamp(0.0, f64::from(u16::MAX)) as u16)
}

/// `x.round()` (half away from zero) for |x| < 2⁶², without the library
/// call `f64::round` is on CPUs without SSE4.1: the truncation is the
/// hardware's conversion, and `x − trunc(x)` is exact.
#[inline]
fn round_half_away(x: f64) -> f64 {
    let t = x as i64 as f64;
    let d = x - t;
    t + f64::from(u8::from(d >= 0.5)) - f64::from(u8::from(d <= -0.5))
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
/// that the decoded vector is a unit vector to within 8-bit precision. The
/// error of a candidate `c` is `| |c|/127 − 1 | + ¼ |c/|c| − n|`, the second
/// term from `|c/|c| − n|² = 2 − 2 c·n/|c|` for a unit `n`: two square roots
/// and a division per candidate.
fn byte_normal(n: Vec3) -> [i8; 3] {
    let scaled = n * 127.0;
    // `floor` by truncation (|scaled| ≤ 127): no library call without SSE4.1.
    let floor = scaled.to_array().map(|x| {
        let t = x as i32 as f32;
        t - f32::from(u8::from(x < t))
    });
    let mut best = ([0i8; 3], f32::INFINITY);
    for bits in 0..8u32 {
        let mut c = [0.0f32; 3];
        for (k, c) in c.iter_mut().enumerate() {
            *c = (floor[k] + ((bits >> k) & 1) as f32).clamp(-127.0, 127.0);
        }
        let c3 = Vec3::from(c);
        let length = c3.length();
        if length == 0.0 {
            continue;
        }
        let along = c3.dot(n) / length;
        let error = (length / 127.0 - 1.0).abs() + 0.25 * (2.0 - 2.0 * along).max(0.0).sqrt();
        if error < best.1 {
            best = (c.map(|x| x as i8), error);
        }
    }
    best.0
}
