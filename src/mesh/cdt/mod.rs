//! Error-bounded constrained-Delaunay meshing of one patch region.
//!
//! This is the Tessellate stage's mesher for trimmed and untrimmed patches: the
//! caller gives a [`Region`] of the patch's (u, v) domain bounded by loops whose
//! vertices it chose (shared edges sampled once, so neighbours conform), and
//! [`mesh_region`] returns a [`Mesh`](crate::mesh::Mesh) whose triangles all lie
//! within the chordal tolerance of the exact surface.
//!
//! Pipeline: `region` (validate) → for a whole patch closed in u, `rings` (the
//! lattice's rows zipped seam to seam round the `cavity` of each opening, each
//! cavity zipped to its hole or swept round its holes (`sweep`) and flipped to
//! Delaunay (`ring`), checked, refined only if needed); otherwise
//! `seed` (curvature-sized lattice clipped to the
//! region, in the size `metric` of the surface) → `initial` (spade's constrained
//! Delaunay triangulation of loop vertices and seeds, inside found by flood fill) →
//! `refine` (chordal refinement, deviations by `measure`, with metric-Delaunay
//! `flip`s on a `trimesh`) →
//! `output` (weld poles and seams, check every triangle, statistics). `patch` holds
//! the facts about the surface every stage uses.

mod cavity;
mod certify;
mod error;
mod flip;
mod initial;
mod kept;
mod measure;
mod mend;
mod mesher;
mod metric;
mod output;
mod patch;
mod peak;
mod refine;
mod region;
mod ring;
mod rings;
mod screen;
mod sector;
mod seed;
mod sweep;
mod trimesh;

/// Fewest vertices or triangles per parallel task in the mesher's per-item loops:
/// one item costs a few thousand instructions, so smaller tasks on a small patch
/// cost more in hand-offs than they save (a patch is usually meshed beside
/// others, in the Tessellate stage's own parallel loop).
const MIN_VERTICES: usize = 64;

pub use error::CdtError;
pub use kept::KeptCavities;
pub use mesher::{
    VERTEX_BUDGET, mesh_patch_region, mesh_patch_region_keeping, mesh_region, mesh_region_on,
    mesh_region_with_uvs,
};
pub use output::{MeshStats, RegionMesh};
pub use patch::wrap_u;
pub use region::{Region, UvLoop};
