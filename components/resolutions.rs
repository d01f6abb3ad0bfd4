//! Resolutions handed between the model and the Validate and Constrain stages.

use bevy_ecs::entity::Entity;
use bevy_ecs::resource::Resource;
use rustc_hash::FxHashMap;

use crate::constraints::ResolvedVessel;
use crate::format::VesselDesign;

/// Vessels resolved by the Validate stage, waiting for the Constrain stage.
#[derive(Resource, Default)]
pub struct PendingResolutions(pub Vec<(Entity, ResolvedVessel)>);

/// Resolutions `Model::apply` computed when it checked an edit, by vessel, each
/// with the order and design (operating data left out, as `read_vessel` reads
/// it) it was computed from. `systems::resolve_dirty_vessels` takes a dirty vessel's
/// resolution from here instead of resolving it a second time when the world
/// still holds exactly that design, and drops the rest: resolving is a pure
/// function of the design and its order, and the operating data only adds checks.
#[derive(Resource, Default)]
pub struct CheckedResolutions(pub FxHashMap<Entity, (u32, VesselDesign, ResolvedVessel)>);
