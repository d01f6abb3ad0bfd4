//! Meshes: triangle approximations of patches, in the patch's part-local frame.
//!
//! The Tessellate stage (`systems::remesh_dirty_patches`) meshes each dirty patch
//! with the error-bounded constrained-Delaunay mesher of [`cdt`]
//! ([`cdt::mesh_patch_region_keeping`]), over the (u, v) region laid out here
//! ([`patch_region`], [`host_region`]: the patch's boundary and the loops of the
//! openings cut into it, [`cut_opening`]), driven by [`TessellationOptions`].
//! Meshes equal by content are meshed once and shared ([`MeshInstances`]); the model
//! keeps each finished mesh as a [`PackedMesh`] (fixed-point positions, octahedral
//! normals, narrow indices); exporters convert them to `f32` buffers. By stage:
//! `cut` (opening cuts), `layout` (regions), [`cdt`] (the mesher, whose
//! `plan` is its decision table), `store` (content-keyed tables).

pub mod cdt;
mod cut;
mod layout;
mod options;
mod packed;
mod storage;
mod store;
mod surface;
#[cfg(test)]
mod test_parts;

pub use cut::SharedCuts;
pub use cut::{
    AxialCut, Cut, CutError, CutLoop, HostTrim, Notch, OpeningPlan, PAD_PATCH, PadCut, ReusableCut,
    cut_opening, cut_opening_reusing,
};
pub use layout::{
    LayoutError, MAX_EDGE_SEGMENTS, PatchSides, SEAM_CUTS, closed_in_u, edge_parameters,
    edge_segments, host_region, host_region_with, pad_region, patch_region,
};
pub use options::{
    DEFAULT_VERTEX_BUDGET, MAX_VERTEX_BUDGET, MIN_VERTEX_BUDGET, OptionsError, TessellationOptions,
};
pub use packed::{OctNormal, PackedMesh};
pub use storage::{
    check_storable, f32_rounding_bound, patch_extent, smallest_storable_tolerance, storage_options,
};
pub use store::{MeshInstances, WeakTable, mesh_key, mesh_key_of, surface_key};
pub(crate) use surface::Extrusion;

use glam::DVec3;

/// An indexed triangle mesh with per-vertex exact normals.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Mesh {
    /// Vertex positions, mm.
    pub positions: Vec<DVec3>,
    /// Unit normals from the exact surface, one per vertex.
    pub normals: Vec<DVec3>,
    /// Triangles as vertex-index triples, counter-clockwise seen from outside.
    pub indices: Vec<u32>,
}

impl Mesh {
    /// Number of triangles.
    pub fn triangle_count(&self) -> usize {
        self.indices.len() / 3
    }

    /// Number of vertices.
    pub fn vertex_count(&self) -> usize {
        self.positions.len()
    }

    /// Heap bytes held (by capacity), with the struct itself.
    pub fn heap_bytes(&self) -> usize {
        std::mem::size_of::<Self>()
            + (self.positions.capacity() + self.normals.capacity()) * std::mem::size_of::<DVec3>()
            + self.indices.capacity() * std::mem::size_of::<u32>()
    }

    /// Axis-aligned bounds `(min, max)` of the vertices; `None` when empty.
    pub fn bounds(&self) -> Option<(DVec3, DVec3)> {
        let first = *self.positions.first()?;
        Some(
            self.positions
                .iter()
                .fold((first, first), |(lo, hi), &p| (lo.min(p), hi.max(p))),
        )
    }
}
