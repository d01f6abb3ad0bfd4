//! Tessellate stage: mesh every patch whose surface or region changed (or every
//! patch when the tessellation options changed) with the error-bounded
//! constrained-Delaunay mesher, in parallel with rayon. A patch equal to one
//! whose mesh is in use (same surface, region and options, by content) shares
//! that mesh instead of being meshed again. A patch with openings keeps the
//! cavities its meshing triangulated round them ([`PatchCavities`]), and its next
//! meshing takes those whose inputs come out the same.

use crate::components::{Instances, Tessellation};
use std::sync::Arc;

use bevy_ecs::entity::Entity;
use bevy_ecs::query::QueryState;
use bevy_ecs::world::World;
use rayon::prelude::*;
use rustc_hash::FxHashMap;

use super::biggest_first::map_biggest_first;
use super::labels::{build_failure, patch_name};
use crate::components::DirtyPatches;
use crate::components::{BuildCause, ModelErrors, WorkCounters};
use crate::components::{PatchCavities, PatchMesh, PatchSurface};
use crate::mesh::cdt::{CdtError, KeptCavities, MeshPath, Region, mesh_patch_region_keeping};
use crate::mesh::{PackedMesh, mesh_key_of, surface_key};
use crate::parts::Patch;

/// One patch meshed: its mesh, the cavities it met (none: `None`) and how many
/// of them it took from its last meshing.
struct Meshed {
    mesh: Arc<PackedMesh>,
    cavities: Option<Arc<KeptCavities>>,
    reused: u64,
    path: MeshPath,
}

/// Meshes every patch whose surface or region changed, within the region laid
/// out in this run (every patch when the tessellation options changed: then
/// every region was laid out again).
pub fn remesh_dirty_patches(world: &mut World, surfaces: &mut QueryState<&PatchSurface>) {
    let options = world.resource::<Tessellation>().0;
    let lists = world.resource::<DirtyPatches>();
    let mut laid: FxHashMap<Entity, (&Arc<Region>, u128)> = FxHashMap::default();
    laid.reserve(lists.laid_out.len());
    laid.extend(lists.laid_out.iter().map(|(e, r, f)| (*e, (r, *f))));
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
    // Read in parallel: after a full build's layout these lists hold every
    // patch of the plant, and a serial pass over them was a good part of the
    // stage's wall time on two threads.
    surfaces.update_archetypes(world);
    let surfaces = &*surfaces;
    let work: Vec<(Entity, Arc<Patch>, Arc<Region>, u128)> = dirty
        .par_iter()
        .filter_map(|&e| {
            // A patch whose region could not be laid out has its error already.
            let (region, fingerprint) = *laid.get(&e)?;
            let surface = surfaces.get_manual(world, e).ok()?.0.clone();
            Some((e, surface, region.clone(), fingerprint))
        })
        .collect();
    // The cavities each patch's last meshing met.
    let kept: Vec<Option<Arc<KeptCavities>>> = work
        .par_iter()
        .map(|(e, ..)| world.get::<PatchCavities>(*e).map(|c| c.0.clone()))
        .collect();
    if work.is_empty() {
        return;
    }
    // Patches equal to one whose mesh is in use, or to an earlier one of this
    // batch, share its mesh; each distinct patch is meshed once.
    let surface_keys: Vec<u128> = work
        .par_iter()
        .map(|(_, p, ..)| surface_key(p, &options))
        .collect();
    let keys: Vec<u128> = (work.iter().zip(&surface_keys))
        .map(|((.., fingerprint), &surface)| mesh_key_of(surface, *fingerprint))
        .collect();
    let instances = &world.resource::<Instances>().0;
    let in_use: Vec<Option<Arc<PackedMesh>>> = keys.par_iter().map(|&k| instances.get(k)).collect();
    let mut first: FxHashMap<u128, usize> = FxHashMap::default();
    let to_mesh: Vec<usize> = (0..work.len())
        .filter(|&i| in_use[i].is_none() && *first.entry(keys[i]).or_insert(i) == i)
        .collect();
    // Biggest first, by the triangles of the patch's mesh before this run (a
    // new patch counts as small): see `biggest_first`.
    let previous = |&i: &usize| {
        world
            .get::<PatchMesh>(work[i].0)
            .map_or(0, |m| m.0.triangle_count() as u64)
    };
    let meshed: FxHashMap<u128, Result<Meshed, CdtError>> =
        map_biggest_first(&to_mesh, previous, |&i| {
            let (_, p, r, _) = &work[i];
            // Kept for the model's lifetime: packed (exact positions, 4-byte
            // normals, narrow indices, no growth slack).
            let result =
                mesh_patch_region_keeping(p, r, &options, kept[i].as_deref(), surface_keys[i]).map(
                    |(out, cavities)| Meshed {
                        mesh: Arc::new(PackedMesh::pack_marked(&out.mesh, &out.on_loops)),
                        cavities: (!cavities.is_empty()).then(|| Arc::new(cavities)),
                        reused: out.stats.cavities_reused as u64,
                        path: out.stats.path,
                    },
                );
            (keys[i], result)
        })
        .into_iter()
        .collect();
    let ok = || meshed.values().filter_map(|m| m.as_ref().ok());
    let triangles: u64 = ok().map(|m| m.mesh.triangle_count() as u64).sum();
    let cavities_reused: u64 = ok().map(|m| m.reused).sum();
    let mut by_path = [0u64; 3];
    for m in ok() {
        by_path[match m.path {
            MeshPath::Sector => 0,
            MeshPath::Structured => 1,
            MeshPath::General => 2,
        }] += 1;
    }
    {
        let mut instances = world.resource_mut::<Instances>();
        for (&key, meshed) in &meshed {
            if let Ok(meshed) = meshed {
                instances.0.insert(key, &meshed.mesh);
            }
        }
    }
    let mut failures = 0u64;
    // Components new to their entity are inserted in batches (one archetype
    // lookup per run of entities alike, not one per entity: a full build's
    // patches all get their first mesh here); existing ones are overwritten.
    let mut new_meshes: Vec<(Entity, PatchMesh)> = Vec::new();
    let mut new_cavities: Vec<(Entity, PatchCavities)> = Vec::new();
    let mut written = Vec::with_capacity(work.len());
    for (((e, ..), key), held) in work.iter().zip(&keys).zip(in_use) {
        let e = *e;
        // A mesh in use elsewhere is shared with its cavities left as they were.
        // Every key not in use was meshed (`to_mesh` holds its first patch).
        let result = match held {
            Some(mesh) => Ok((mesh, None)),
            None => match &meshed[key] {
                Ok(m) => Ok((m.mesh.clone(), Some(m.cavities.clone()))),
                Err(e) => Err(e.clone()),
            },
        };
        match result {
            Ok((mesh, cavities)) => {
                match world.get_mut::<PatchMesh>(e) {
                    Some(mut held) => held.0 = mesh,
                    None => new_meshes.push((e, PatchMesh(mesh))),
                }
                match cavities {
                    Some(Some(c)) => match world.get_mut::<PatchCavities>(e) {
                        Some(mut held) => held.0 = c,
                        None => new_cavities.push((e, PatchCavities(c))),
                    },
                    Some(None) if world.get::<PatchCavities>(e).is_some() => {
                        world.entity_mut(e).remove::<PatchCavities>();
                    }
                    Some(None) | None => {}
                }
                written.push(e);
            }
            Err(source) => {
                failures += 1;
                // No stale mesh stands for the patch: the failed update is
                // undone, and what is built again meshes it afresh.
                if world.get::<PatchMesh>(e).is_some() {
                    world.entity_mut(e).remove::<(PatchMesh, PatchCavities)>();
                }
                let cause = BuildCause::Mesh {
                    patch: patch_name(world, e),
                    source,
                };
                let failure = build_failure(world, e, cause);
                world.resource_mut::<ModelErrors>().0.push(failure);
            }
        }
    }
    world.insert_batch(new_meshes);
    world.insert_batch(new_cavities);
    world.resource_mut::<DirtyPatches>().meshes.extend(written);
    let mut counters = world.resource_mut::<WorkCounters>();
    counters.meshes_rebuilt += work.len() as u64;
    counters.meshes_shared += (work.len() - to_mesh.len()) as u64;
    counters.triangles_meshed += triangles;
    counters.cavities_reused += cavities_reused;
    for (n, m) in counters.meshed_by_path.iter_mut().zip(by_path) {
        *n += m;
    }
    counters.failures += failures;
}
