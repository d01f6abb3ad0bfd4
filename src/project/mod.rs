//! Project stage: orthographic and isometric views of each vessel, in the vessel's
//! frame, as 2D polylines classified visible / hidden / centre, cached per entity
//! per view.
//!
//! Sits after Tessellate in the data flow: views read the exact patches (for
//! exact silhouettes), the trimmed regions and the meshes (edges, occlusion), and
//! are read by the drawing sheet (`crate::drawing`). `types` holds the vocabulary
//! both sides share; `frames` the four projections; `silhouette`, `edges`,
//! `occlusion` and `classify` the line builders; `build` one entity's view. The ECS
//! cache and the incremental rebuild live in `systems/project.rs`.

mod build;
mod classify;
mod edges;
mod frames;
mod occlusion;
mod silhouette;
mod types;

pub use build::{
    EntityInput, PatchInput, PreparedEntity, ViewSettings, build_entity_view, build_views,
    footprint,
};
pub use classify::Sampling;
pub use edges::boundary_polylines;
pub use frames::{plan_north, projections};
pub use occlusion::Occluder;
pub use silhouette::{NormalGrid, SurfacePoint, silhouettes};
pub use types::{EntityView, LineKind, Projection, View, ViewKind, ViewLine};
