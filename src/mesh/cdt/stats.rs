//! The counts of what happened while meshing a region ([`MeshStats`]), which
//! every stage adds to. Apart from `output` (which reads the structured path's
//! types), so that the stages count without depending on the output; it reads
//! only the decision table, whose path and cavity fills it records.

use super::plan::{CAVITY_FILLS, MeshPath};

/// Counts of what happened while meshing, reported not swallowed.
#[derive(Default, Clone, Copy, Debug, PartialEq)]
pub struct MeshStats {
    /// Triangles in the output mesh.
    pub triangles: usize,
    /// Vertices inserted by refinement (centroids, edge midpoints, and pole
    /// vertices welded away on output).
    pub refinement_insertions: usize,
    /// Seed points spade rejected (out-of-range coordinates, duplicates).
    pub failed_insertions: usize,
    /// Loop segments spade could not insert as constraint edges (each one also
    /// makes meshing fail).
    pub failed_constraints: usize,
    /// Triangles dropped because welding collapsed them (at a pole or seam).
    pub dropped_degenerate: usize,
    /// Smallest interior angle of an output triangle, degrees (in 3D).
    pub min_angle_deg: f64,
    /// Cavities round openings whose triangles were taken from the patch's
    /// previous meshing (see [`mesh_patch_region_keeping`](super::mesh_patch_region_keeping)).
    pub cavities_reused: usize,
    /// The path that meshed the region (see [`MeshPath`](super::MeshPath) and the
    /// decision table of `cdt::plan`).
    pub path: MeshPath,
    /// Cavities round openings filled by each fill, indexed as
    /// [`CAVITY_FILLS`](super::CAVITY_FILLS) (all zero off the structured path).
    pub cavity_fills: [usize; CAVITY_FILLS.len()],
}
