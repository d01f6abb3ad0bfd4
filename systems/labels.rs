//! Names the model's errors give entities: the stable id a user wrote
//! (`tag/id` of a part or nozzle) and, for a patch, that id with the patch's
//! name, instead of an ECS entity number that means nothing outside the process.

use bevy_ecs::entity::Entity;
use bevy_ecs::hierarchy::ChildOf;
use bevy_ecs::world::World;

use crate::components::{NozzleSpec, PartSpec, PatchOf, PatchSurface, VesselSpec};

/// The stable id (`tag/id`) of a part or nozzle, or the entity where it has none.
pub(crate) fn stable_id(world: &World, entity: Entity) -> String {
    let id = world
        .get::<PartSpec>(entity)
        .map(|p| p.0.id().to_string())
        .or_else(|| world.get::<NozzleSpec>(entity).map(|n| n.0.mark.clone()));
    let tag = world
        .get::<ChildOf>(entity)
        .and_then(|c| world.get::<VesselSpec>(c.parent()))
        .map(|v| v.tag.clone());
    match (tag, id) {
        (Some(tag), Some(id)) => format!("{tag}/{id}"),
        _ => format!("{entity}"),
    }
}

/// A patch as `tag/id patch-name` (e.g. `V-101/S1 shell`), from the part or
/// nozzle it belongs to; the entity where that is unknown.
pub(crate) fn patch_label(world: &World, patch: Entity) -> String {
    let owner = world.get::<PatchOf>(patch).map(|p| stable_id(world, p.0));
    let name = world.get::<PatchSurface>(patch).map(|s| {
        if s.0.index == 0 {
            s.0.name.to_string()
        } else {
            format!("{} {}", s.0.name, s.0.index)
        }
    });
    match (owner, name) {
        (Some(owner), Some(name)) => format!("{owner} {name}"),
        (Some(owner), None) => owner,
        _ => format!("{patch}"),
    }
}
