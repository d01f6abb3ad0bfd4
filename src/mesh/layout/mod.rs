//! Region layout: a patch's (u, v) region for the mesher (the Tessellate stage's
//! `lay_out_regions`).
//!
//! Edge vertices come from the edge curve alone (`edges`, with exact circles in
//! `circles`), so two patches sharing an edge sample it alike and their meshes
//! conform; `region` closes them into the outer loop, adds the openings' loops as
//! holes (or the trimmed bottom of a neck) and the seam cut of a closed patch.

mod circles;
mod edges;
mod region;

pub use edges::{MAX_EDGE_SEGMENTS, edge_parameters, edge_segments};
pub use region::{
    LayoutError, PatchSides, SEAM_CUTS, closed_in_u, host_region, host_region_with, pad_region,
    patch_region,
};
