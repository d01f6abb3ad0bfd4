//! The tessellation options of the model: those asked for and those the
//! patches are meshed to (less the storage rounding, set by
//! `systems::budget_storage_precision`).

use std::collections::{BTreeMap, HashMap};

use bevy_ecs::entity::Entity;
use bevy_ecs::resource::Resource;

use crate::mesh::TessellationOptions;

/// The tessellation options asked for (the model's [`Tessellation`] is what
/// the patches are meshed to).
#[derive(Resource, Clone, Copy, Debug, PartialEq)]
pub struct RequestedTessellation(pub TessellationOptions);

/// The tessellation options every patch is meshed with: the requested ones
/// ([`RequestedTessellation`]) less the storage
/// rounding (see `budget_storage_precision`).
#[derive(Resource, Clone, Copy, Debug, PartialEq)]
pub struct Tessellation(pub TessellationOptions);

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
    pub(crate) fn remove(&mut self, patch: Entity) {
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
    pub(crate) fn insert(&mut self, patch: Entity, extent: f64) {
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
