//! Project stage: orthographic and isometric views of each vessel, in the vessel's
//! frame, as 2D polylines classified visible / hidden / centre, cached per entity
//! per view.
//!
//! Sits after Tessellate in the data flow: views read the exact patches (for
//! silhouettes of surfaces of revolution) and the meshes (for everything else), and
//! are read by the drawing sheet (`crate::drawing`). This file holds the types both
//! sides share; the view builders and the ECS cache live beside it.

mod types;

pub use types::{EntityView, LineKind, Projection, View, ViewKind, ViewLine};
