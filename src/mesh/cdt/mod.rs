//! Error-bounded constrained-Delaunay meshing of one patch region.
//!
//! This is the Tessellate stage's mesher for trimmed and untrimmed patches: the
//! caller gives a [`Region`] of the patch's (u, v) domain bounded by loops whose
//! vertices it chose (shared edges sampled once, so neighbours conform), and
//! [`mesh_region`] returns a [`Mesh`](crate::mesh::Mesh) whose triangles all lie
//! within the chordal tolerance of the exact surface.
//!
//! Pipeline: `region` (validate) → `plan` (the decision table: which path
//! meshes the region, and the order a cavity's fills are tried) → the sector or
//! structured path (`structured`: the lattice's rows zipped seam to seam round
//! the `cavity` of each opening, each cavity filled by `cavity_fill` (zip, `sweep`,
//! ears) or taken from `kept`; `sector` turns a first quarter round; the types
//! in `lattice`; triangles screened by `screen`, mended by `mend`) or the
//! general path (`seed`: curvature-sized lattice clipped to the region, in the
//! size `metric` of the surface → `initial`: spade's constrained Delaunay
//! triangulation of loop vertices and seeds, inside found by flood fill →
//! `refine`: chordal refinement, deviations by `measure`, with metric-Delaunay
//! `flip`s on a `trimesh`) → `output` (weld poles and seams, check every
//! triangle, statistics). The checks: `certify` (closed form on planes,
//! cylinders, spheres), `peak` (the cubic deviation model). `patch` holds the
//! facts about the surface every stage uses.

mod checks;
mod error;
mod flip;
mod general;
mod mesher;
mod metric;
mod output;
mod patch;
mod plan;
mod quarter;
mod region;
mod stats;
mod structured;
mod trimesh;

/// Fewest vertices or triangles per parallel task in the mesher's per-item loops:
/// one item costs a few thousand instructions, so smaller tasks on a small patch
/// cost more in hand-offs than they save (a patch is usually meshed beside
/// others, in the Tessellate stage's own parallel loop).
const MIN_VERTICES: usize = 64;

pub use error::CdtError;
pub use mesher::{
    mesh_patch_region, mesh_patch_region_keeping, mesh_region, mesh_region_on, mesh_region_with_uvs,
};
pub use output::RegionMesh;
pub use patch::wrap_u;
pub use plan::{CAVITY_FILLS, CavityFill, MeshPath};
pub use region::{Region, UvLoop};
pub use stats::MeshStats;
pub use structured::kept::KeptCavities;
