//! Tessellate stage: re-mesh every patch whose surface changed (or every patch
//! when the tessellation options changed), in parallel with rayon.

use std::sync::Arc;

use bevy_ecs::entity::Entity;
use bevy_ecs::query::{Changed, QueryState};
use bevy_ecs::resource::Resource;
use bevy_ecs::world::World;
use rayon::prelude::*;

use super::WorkCounters;
use crate::components::{PatchMesh, PatchSurface};
use crate::mesh::{TessellationOptions, tessellate};
use crate::parts::Patch;

/// The tessellation options every patch is meshed with.
#[derive(Resource, Clone, Copy, Debug, PartialEq)]
pub struct Tessellation(pub TessellationOptions);

/// Meshes every patch whose [`PatchSurface`] changed.
pub fn remesh_dirty_patches(
    world: &mut World,
    dirty: &mut QueryState<(Entity, &PatchSurface), Changed<PatchSurface>>,
    all: &mut QueryState<(Entity, &PatchSurface)>,
) {
    let options = world.resource::<Tessellation>().0;
    let work: Vec<(Entity, Arc<Patch>)> = if world.is_resource_changed::<Tessellation>() {
        all.iter(world).map(|(e, s)| (e, s.0.clone())).collect()
    } else {
        dirty.iter(world).map(|(e, s)| (e, s.0.clone())).collect()
    };
    if work.is_empty() {
        return;
    }
    let meshes: Vec<_> = work
        .par_iter()
        .map(|(e, p)| (*e, tessellate(&p.surface, &options)))
        .collect();
    let mut triangles = 0u64;
    for (e, mesh) in meshes {
        triangles += mesh.triangle_count() as u64;
        world.entity_mut(e).insert(PatchMesh(Arc::new(mesh)));
    }
    let mut counters = world.resource_mut::<WorkCounters>();
    counters.meshes_rebuilt += work.len() as u64;
    counters.triangles_meshed += triangles;
}
