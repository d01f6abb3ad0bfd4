//! Names the model's errors give entities: the stable id a user wrote
//! (`tag/id` of a part or nozzle) and, for a patch, that id with the patch's
//! name, instead of an ECS entity number that means nothing outside the process;
//! and the JSON path (`vessels[0].nozzles[2]`) of the part or nozzle in the
//! design file, so that a geometry failure names what the user wrote.

use bevy_ecs::entity::Entity;
use bevy_ecs::hierarchy::ChildOf;
use bevy_ecs::query::With;
use bevy_ecs::world::World;

use crate::components::{
    BuildCause, BuildFailure, DesignOrder, ModelFailure, NozzleSpec, PadOf, PartSpec, PatchOf,
    PatchSurface, VesselSpec,
};

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

/// A patch's name within its part (`crown`, or `leg 2` for the second of
/// several same-named patches); the entity where it has no surface.
pub(crate) fn patch_name(world: &World, patch: Entity) -> String {
    match world.get::<PatchSurface>(patch) {
        Some(s) if s.0.index == 0 => s.0.name.to_string(),
        Some(s) => format!("{} {}", s.0.name, s.0.index),
        None => format!("{patch}"),
    }
}

/// The failure of `entity` (a part, nozzle or boot, or one of their patches,
/// which is named by its owner) from `cause`: its design path and stable id.
pub(crate) fn build_failure(world: &World, entity: Entity, cause: BuildCause) -> ModelFailure {
    let owner = patch_owner(world, entity).unwrap_or(entity);
    ModelFailure::Build(BuildFailure {
        path: json_path(world, owner),
        entity: stable_id(world, owner),
        cause,
    })
}

/// The part or nozzle a patch belongs to: its `PatchOf`, or for a reinforcing
/// pad (which is no patch of the nozzle's own) its `PadOf`.
pub(crate) fn patch_owner(world: &World, patch: Entity) -> Option<Entity> {
    world
        .get::<PatchOf>(patch)
        .map(|p| p.0)
        .or_else(|| world.get::<PadOf>(patch).map(|p| p.0))
}

/// The JSON path of a part or nozzle in the design file (`vessels[1].parts[3]`,
/// `vessels[0].nozzles[2]`), of a patch's owner for a patch; empty when the
/// entity belongs to no vessel. Only errors ask for it: it counts siblings.
pub(crate) fn json_path(world: &World, entity: Entity) -> String {
    let entity = patch_owner(world, entity).unwrap_or(entity);
    let Some(vessel) = world.get::<ChildOf>(entity).map(ChildOf::parent) else {
        return String::new();
    };
    let Some(order) = world.get::<DesignOrder>(vessel).map(|o| o.0) else {
        return String::new();
    };
    // The design lists vessels by their order, which may have gaps; a part's or
    // nozzle's order is its index in its own list.
    let index = world
        .try_query_filtered::<&DesignOrder, With<VesselSpec>>()
        .map_or(0, |mut q| q.iter(world).filter(|o| o.0 < order).count());
    let own = world.get::<DesignOrder>(entity).map_or(0, |o| o.0);
    if world.get::<PartSpec>(entity).is_some() {
        format!("vessels[{index}].parts[{own}]")
    } else if world.get::<NozzleSpec>(entity).is_some() {
        format!("vessels[{index}].nozzles[{own}]")
    } else {
        format!("vessels[{index}]")
    }
}
