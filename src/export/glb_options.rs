//! How compact a GLB is: mesh reuse, `KHR_mesh_quantization`,
//! `EXT_meshopt_compression` and `EXT_mesh_gpu_instancing`, chosen by the caller of the glTF writer.
//!
//! The writer ([`super::write_glb_with`], [`super::stream_glb_with`]) takes these
//! options; [`GlbOptions::default`] is what [`super::write_glb`] writes: patches
//! that share a mesh share one glTF mesh, `f32` positions and normals, `u32`
//! indices — every viewer reads it without an extension.
//!
//! Quantization moves every vertex by at most half a quantization step along each
//! axis, so it takes part of the chordal budget: a caller that asks for tolerance
//! `t` meshes to `t − q` with `q` = [`quantization_budget`]`(t)` = `t / 4` (a
//! quarter: meshing to 0.75 t costs about 15 % more triangles on curved patches,
//! while the 16-bit step of a patch up to 16 m across fits in 0.25 mm), and
//! quantizes each mesh only when its step's bound is within `q`; a larger patch
//! keeps `f32` positions. [`GlbOptions::meshing_tolerance`] is that `t − q`.

/// Compression of the binary buffer.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Compression {
    /// Plain bytes.
    #[default]
    None,
    /// `EXT_meshopt_compression` (meshoptimizer's vertex codec version 0 and
    /// triangle index codec), required by the file.
    Meshopt,
}

/// Whether a file writes vertex normals.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Normals {
    /// A unit normal per vertex, as the mesher made it (the exact surface's):
    /// smooth shading across patches, sharp at creases.
    #[default]
    Smooth,
    /// No `NORMAL` attribute: the glTF specification has the viewer compute
    /// flat normals (three.js shades the mesh with `flatShading`), so curved
    /// surfaces show their facets. The smallest file; for viewers that
    /// compute their own normals.
    Flat,
}

/// What the glTF writer does to make a file small.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct GlbOptions {
    /// Patches whose meshes are equal share one glTF mesh (one set of
    /// accessors, many nodes). On by default.
    pub reuse: bool,
    /// `KHR_mesh_quantization` within this bound, mm: positions as 16-bit
    /// integers in the coarsest power-of-two step whose `√3/2 · step` is within
    /// the bound (the step and offset in the patch node's scale and
    /// translation; a mesh wider than 65 535 steps keeps `f32`), normals as
    /// normalized bytes, `u16` indices where they fit, no mesh names. `None`:
    /// `f32`.
    pub quantize: Option<f64>,
    /// Compression of the buffer.
    pub compress: Compression,
    /// `EXT_mesh_gpu_instancing`: the patches that draw one glTF mesh (with
    /// `reuse`) are drawn by one instanced node, a draw call for them all,
    /// instead of a node each. Off by default: plain nodes (a node per patch,
    /// under its part) are what every viewer reads and what the live viewer
    /// picks and replaces by id.
    pub instancing: bool,
    /// Vertex normals written or left to the viewer ([`Normals::Smooth`] by
    /// default, and in [`GlbOptions::compact`]).
    pub normals: Normals,
}

impl Default for GlbOptions {
    fn default() -> Self {
        Self {
            reuse: true,
            quantize: None,
            compress: Compression::None,
            instancing: false,
            normals: Normals::Smooth,
        }
    }
}

impl GlbOptions {
    /// The smallest file: reuse, quantization within
    /// [`quantization_budget`]`(tolerance)` and meshopt compression.
    pub fn compact(tolerance: f64) -> Self {
        Self {
            reuse: true,
            quantize: Some(quantization_budget(tolerance)),
            compress: Compression::Meshopt,
            instancing: false,
            normals: Normals::Smooth,
        }
    }

    /// These options without vertex normals ([`Normals::Flat`]).
    pub fn flat(self) -> Self {
        Self {
            normals: Normals::Flat,
            ..self
        }
    }

    /// These options with `EXT_mesh_gpu_instancing` on.
    pub fn instanced(self) -> Self {
        Self {
            instancing: true,
            ..self
        }
    }

    /// The tolerance to mesh to, mm, for the file to hold `tolerance`: less the
    /// quantization bound when quantizing.
    pub fn meshing_tolerance(&self, tolerance: f64) -> f64 {
        tolerance - self.quantize.unwrap_or(0.0)
    }

    /// True when the writer packs data more tightly than plain `f32`/`u32`
    /// (`u16` indices where they fit, normals as bytes when quantizing).
    pub(super) fn is_compact(&self) -> bool {
        self.quantize.is_some() || self.compress != Compression::None
    }
}

/// The share of a chordal tolerance `tolerance` (mm) given to quantization: a
/// quarter of it.
pub fn quantization_budget(tolerance: f64) -> f64 {
    0.25 * tolerance
}
