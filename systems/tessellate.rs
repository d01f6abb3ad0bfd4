//! Tessellate stage: mesh every patch whose surface or region changed (or every
//! patch when the tessellation options changed) with the error-bounded
//! constrained-Delaunay mesher, in parallel with rayon.

use std::collections::HashMap;
use std::sync::Arc;

use bevy_ecs::entity::Entity;
use bevy_ecs::query::QueryState;
use bevy_ecs::resource::Resource;
use bevy_ecs::world::World;
use rayon::prelude::*;

use super::DirtyPatches;
use super::{ModelErrors, WorkCounters};
use crate::components::{PatchMesh, PatchSurface};
use crate::design::RuleViolation;
use crate::mesh::cdt::{Region, mesh_patch_region};
use crate::mesh::{PackedMesh, TessellationOptions};
use crate::parts::Patch;

/// The tessellation options every patch is meshed with.
#[derive(Resource, Clone, Copy, Debug, PartialEq)]
pub struct Tessellation(pub TessellationOptions);

/// Meshes every patch whose surface or region changed, within the region laid
/// out in this run (every patch when the tessellation options changed: then
/// every region was laid out again).
pub fn remesh_dirty_patches(world: &mut World, surfaces: &mut QueryState<&PatchSurface>) {
    let options = world.resource::<Tessellation>().0;
    let lists = world.resource::<DirtyPatches>();
    let laid: HashMap<Entity, &Arc<Region>> = lists.laid_out.iter().map(|(e, r)| (*e, r)).collect();
    let mut dirty: Vec<Entity> = if world.is_resource_changed::<Tessellation>() {
        laid.keys().copied().collect()
    } else {
        // Surface or region written in this run (see `DirtyPatches`).
        lists
            .surfaces
            .iter()
            .chain(&lists.regions)
            .copied()
            .collect()
    };
    dirty.sort_unstable();
    dirty.dedup();
    let work: Vec<(Entity, Arc<Patch>, Arc<Region>)> = dirty
        .into_iter()
        .filter_map(|e| {
            // A patch whose region could not be laid out has its error already.
            let region = (*laid.get(&e)?).clone();
            Some((e, surfaces.get(world, e).ok()?.0.clone(), region))
        })
        .collect();
    if work.is_empty() {
        return;
    }
    let meshes: Vec<_> = work
        .par_iter()
        .map(|(e, p, r)| {
            // Kept for the model's lifetime: packed (exact positions, 4-byte
            // normals, narrow indices, no growth slack).
            let result = mesh_patch_region(p, r, &options)
                .map(|(mesh, stats)| (PackedMesh::pack(&mesh), stats));
            (*e, result)
        })
        .collect();
    let mut triangles = 0u64;
    let mut failures = 0u64;
    for (e, result) in meshes {
        match result {
            Ok((mesh, _stats)) => {
                triangles += mesh.triangle_count() as u64;
                world.entity_mut(e).insert(PatchMesh(Arc::new(mesh)));
                world.resource_mut::<DirtyPatches>().meshes.push(e);
            }
            Err(err) => {
                failures += 1;
                world.resource_mut::<ModelErrors>().0.push((
                    format!("{e}"),
                    vec![RuleViolation {
                        path: String::new(),
                        entity: format!("{e}"),
                        field: "mesh".into(),
                        value: String::new(),
                        rule: err.to_string(),
                    }],
                ));
            }
        }
    }
    let mut counters = world.resource_mut::<WorkCounters>();
    counters.meshes_rebuilt += work.len() as u64;
    counters.triangles_meshed += triangles;
    counters.failures += failures;
}
