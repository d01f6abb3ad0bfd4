//! Error-bounded constrained-Delaunay meshing of one patch region.
//!
//! This is the Tessellate stage's mesher for trimmed and untrimmed patches: the
//! caller gives a [`Region`] of the patch's (u, v) domain bounded by loops whose
//! vertices it chose (shared edges sampled once, so neighbours conform), and
//! [`mesh_region`] returns a [`Mesh`](crate::mesh::Mesh) whose triangles all lie
//! within the chordal tolerance of the exact surface.
//!
//! Pipeline: `region` (validate) → `plan` (the decision table: which path
//! meshes the region, and the order a cavity's fills are tried; `quarter` tells
//! whether the sector path applies) → `structured/` (the lattice's rows zipped
//! seam to seam round each opening's cavity, cavities filled or kept, failures
//! mended; `sector` turns a first quarter round) or `general/` (`seed`: a
//! curvature-sized lattice → `initial`: spade's constrained Delaunay
//! triangulation → `refine`: chordal refinement) → `output` (weld poles and
//! seams, check every triangle). `checks/` holds the measures every path is held
//! to (`measure`, `certify`, `peak`, and the structured path's batch `screen`).
//! Shared by all: `patch` (the facts about the surface), `metric` (its size
//! metric), `trimesh` and `flip` (the triangulation and its predicates),
//! `stats` ([`MeshStats`]), `error` ([`CdtError`]). The modules form a DAG
//! (`tests/module_graph.rs` fails on any cycle here): the groups use the shared
//! modules, `structured/` uses `checks/` and `general/`, `general/` uses
//! `checks/`, and only `mesher` and `output` use a group from outside.

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
