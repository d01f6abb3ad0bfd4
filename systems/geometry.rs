//! Geometry stage: rebuild the exact patches of every part and nozzle whose
//! resolved shape changed, in parallel with rayon.
//!
//! Patches are entities `PatchOf` their part, in the part's local frame, so a frame
//! change never reaches this stage. Existing patch entities are reused in order and
//! their surfaces written only where they differ; extra ones are despawned, missing
//! ones spawned.

use std::sync::Arc;

use bevy_ecs::entity::Entity;
use bevy_ecs::world::World;
use rayon::prelude::*;

use super::labels::build_failure;
use crate::components::unique;
use crate::components::{BuildCause, ModelErrors, WorkCounters};
use crate::components::{DirtyParts, DirtyPatches};
use crate::components::{PatchOf, PatchSurface, Patches, Shape};
use crate::parts::{PartError, Patch};

/// The patches of a shape in its local frame.
pub(crate) fn shape_patches(shape: &Shape) -> Result<Vec<Patch>, PartError> {
    match shape {
        Shape::Part(p) => p.patches(),
        Shape::Nozzle(n, _) => n.patches(),
    }
}

/// A rebuilt patch (put on the heap in the parallel pass) and whether it
/// differs from the one in its place (or there is none).
type Compared = (Arc<Patch>, bool);

/// Rebuilds the patches of every entity whose [`Shape`] changed (listed by the
/// Constrain stage in [`DirtyParts`]).
pub fn rebuild_dirty_patches(world: &mut World) {
    let reshaped = unique(world.resource::<DirtyParts>().shapes.iter().copied());
    let work: Vec<(Entity, Shape)> = reshaped
        .into_iter()
        .filter_map(|e| Some((e, world.get::<Shape>(e)?.clone())))
        .collect();
    if work.is_empty() {
        return;
    }
    // Built and compared with the patches in place in parallel: comparing reads
    // every number of both surfaces. Each new patch comes with whether it
    // differs from the one it replaces (or there is none).
    let world_ref = &*world;
    let built: Vec<(Entity, Result<Vec<Compared>, PartError>)> = work
        .par_iter()
        .map(|(e, s)| {
            let existing = world_ref.get::<Patches>(*e).map(Patches::entities);
            let compared = shape_patches(s).map(|patches| {
                patches
                    .into_iter()
                    .enumerate()
                    .map(|(k, patch)| {
                        let current = existing
                            .and_then(|x| x.get(k))
                            .and_then(|&pe| world_ref.get::<PatchSurface>(pe));
                        let differs = current.is_none_or(|c| *c.0 != patch);
                        (Arc::new(patch), differs)
                    })
                    .collect()
            });
            (*e, compared)
        })
        .collect();
    let mut rebuilt = 0u64;
    // New patches are spawned in one batch after the loop (one archetype
    // lookup for all: a full build spawns every patch of the plant here).
    let mut new_patches: Vec<(PatchOf, PatchSurface)> = Vec::new();
    for (entity, result) in built {
        let patches = match result {
            Ok(p) => p,
            Err(e) => {
                // Only reachable if the world was edited around `Model::apply`.
                let failure = build_failure(world, entity, BuildCause::Shape(e));
                world.resource_mut::<ModelErrors>().0.push(failure);
                continue;
            }
        };
        let existing: Vec<Entity> = world
            .get::<Patches>(entity)
            .map(|p| p.entities().to_vec())
            .unwrap_or_default();
        let count = patches.len();
        for (k, (patch, differs)) in patches.into_iter().enumerate() {
            match existing.get(k) {
                Some(&pe) => {
                    if differs && let Some(mut current) = world.get_mut::<PatchSurface>(pe) {
                        current.0 = patch;
                        rebuilt += 1;
                        world.resource_mut::<DirtyPatches>().surfaces.push(pe);
                    }
                }
                None => new_patches.push((PatchOf(entity), PatchSurface(patch))),
            }
        }
        for &extra in existing.iter().skip(count) {
            world.despawn(extra);
        }
    }
    rebuilt += new_patches.len() as u64;
    let spawned: Vec<Entity> = world.spawn_batch(new_patches).collect();
    world
        .resource_mut::<DirtyPatches>()
        .surfaces
        .extend(spawned);
    let mut counters = world.resource_mut::<WorkCounters>();
    counters.patches_rebuilt += rebuilt;
    counters.shapes_rebuilt += work.len() as u64;
}
