//! Derived view components: each part's and nozzle's lines in the four views, and
//! each vessel's view state (projections, sampling, the footprints the incremental
//! rebuild compares against). Written only by the Project stage.

use std::collections::HashMap;
use std::sync::Arc;

use bevy_ecs::component::Component;
use bevy_ecs::entity::Entity;
use glam::DVec2;

use crate::project::{EntityView, Projection, ViewSettings};

/// Bounds `(min, max)` of an entity's meshes in one view, view coordinates.
pub type Footprint = Option<(DVec2, DVec2)>;

/// A part's or nozzle's lines in each view, in [`ViewKind::ALL`](crate::project::ViewKind::ALL) order
/// (`crate::project::ViewKind`).
#[derive(Component, Clone, Debug)]
pub struct EntityViews(pub [Arc<EntityView>; 4]);

/// A vessel's view state.
#[derive(Component, Clone, Debug)]
pub struct VesselViews {
    /// The four projections.
    pub projections: [Projection; 4],
    /// How lines were sampled.
    pub settings: ViewSettings,
    /// Footprint of every member entity in each view, as of its last rebuild.
    pub footprints: HashMap<Entity, [Footprint; 4]>,
}
