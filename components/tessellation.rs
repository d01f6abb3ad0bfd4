//! The tessellation options of the model: those asked for and those the
//! patches are meshed to (less the storage rounding, set by
//! `systems::budget_storage_precision`).

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
