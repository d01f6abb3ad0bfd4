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

use std::collections::{BTreeMap, HashMap};

use bevy_ecs::entity::Entity;
use bevy_ecs::query::{QueryState, With};
use bevy_ecs::resource::Resource;
use bevy_ecs::world::World;

use super::{DirtyPatches, Tessellation, WorkCounters};
use crate::components::{PatchOf, PatchSurface};
use crate::mesh::{TessellationOptions, patch_extent, storage_options};

/// The tessellation options asked for (the model's [`Tessellation`] is what
/// the patches are meshed to).
#[derive(Resource, Clone, Copy, Debug, PartialEq)]
pub struct RequestedTessellation(pub TessellationOptions);

/// The extent (largest coordinate in its part's frame, mm) of every part and
/// nozzle patch, and how many patches have each extent: the largest is the last
/// key. Kept up to date from the patches each run rebuilds or removes.
#[derive(Resource, Default, Debug)]
pub struct StorageExtents {
    /// Extent of each patch, as `f64` bits (positive, so ordered as numbers).
    by_patch: HashMap<Entity, u64>,
    /// Patches by extent bits.
    counts: BTreeMap<u64, usize>,
}

impl StorageExtents {
    /// Forgets `patch`'s extent, if it had one.
    fn remove(&mut self, patch: Entity) {
        let Some(bits) = self.by_patch.remove(&patch) else {
            return;
        };
        if let Some(n) = self.counts.get_mut(&bits) {
            *n -= 1;
            if *n == 0 {
                self.counts.remove(&bits);
            }
        }
    }

    /// Records `patch`'s extent (replacing the one it had).
    fn insert(&mut self, patch: Entity, extent: f64) {
        self.remove(patch);
        let bits = extent.max(0.0).to_bits();
        self.by_patch.insert(patch, bits);
        *self.counts.entry(bits).or_default() += 1;
    }

    /// The largest extent of any patch, mm (0 without patches).
    pub fn largest(&self) -> f64 {
        self.counts
            .last_key_value()
            .map_or(0.0, |(&bits, _)| f64::from_bits(bits))
    }
}

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
