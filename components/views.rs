//! Derived view components: each part's and nozzle's lines in the four views, and
//! each vessel's view state (projections, sampling, the footprints the incremental
//! rebuild compares against). Written only by the Project stage.

use std::collections::HashMap;
use std::sync::Arc;

use bevy_ecs::component::Component;
use bevy_ecs::entity::Entity;
use bevy_ecs::resource::Resource;
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

/// Whether the Project stage keeps views. Drawings and live sessions need them; a
/// plant build, simulation or benchmark that never draws should not pay for them
/// (a view rebuild costs more than the re-meshing an edit causes).
#[derive(Resource, Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Views {
    /// Every vessel's views follow every edit (the default).
    #[default]
    Kept,
    /// No views are built. Turning them back on builds, on the next update, the
    /// views of every entity that has none or changed since the stage last ran.
    Off,
}
