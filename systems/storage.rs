//! The options the patches are meshed to: those asked for
//! ([`RequestedTessellation`]) with the tolerance less the `f32` rounding of
//! the plant's largest part, so that the stored meshes (glTF `f32` metres) hold
//! the tolerance asked for (see [`storage_options`]). The largest extent is a
//! running maximum ([`StorageExtents`]) kept from the patches rebuilt or removed
//! in each run, so an edit reads the extents of what it changed, not the plant's.
//! The rounding bound changes only when the largest part crosses a power of two
//! in metres above the floor (`mesh::storage::STORAGE_FLOOR_EXTENT`); then the
//! options change and every patch is laid out and meshed again, as after
//! [`Model::set_tessellation`](crate::model::Model::set_tessellation).
//! `build_scene` budgets the same way from the same patches, so a full build
//! and an incremental one agree.

use bevy_ecs::entity::Entity;
use bevy_ecs::query::{QueryState, With};
use bevy_ecs::world::World;

use crate::components::{
    DirtyPatches, RequestedTessellation, StorageExtents, Tessellation, WorkCounters,
};
use crate::components::{PatchOf, PatchSurface};
use crate::mesh::{patch_extent, storage_options};

/// Sets [`Tessellation`] from [`RequestedTessellation`] and the largest
/// coordinate of any part or nozzle patch in its part's frame (pads lie on
/// their hosts). Reads the extents of the patches whose surface this run
/// rebuilt (counted in [`WorkCounters::storage_extents_read`]) and forgets the
/// removed ones; writes the options only when they differ.
pub fn budget_storage_precision(
    world: &mut World,
    patches: &mut QueryState<&PatchSurface, With<PatchOf>>,
) {
    let removed: Vec<Entity> = world.removed::<PatchSurface>().collect();
    let read: Vec<(Entity, f64)> = world
        .resource::<DirtyPatches>()
        .surfaces
        .iter()
        .filter_map(|&e| Some((e, patch_extent(&patches.get(world, e).ok()?.0))))
        .collect();
    let mut extents = world.resource_mut::<StorageExtents>();
    for e in removed {
        extents.remove(e);
    }
    for &(e, extent) in &read {
        extents.insert(e, extent);
    }
    let largest = extents.largest();
    world.resource_mut::<WorkCounters>().storage_extents_read += read.len() as u64;
    let options = storage_options(&world.resource::<RequestedTessellation>().0, largest);
    if world.resource::<Tessellation>().0 != options {
        world.resource_mut::<Tessellation>().0 = options;
    }
}
