//! Export stage: record the stable ids (`tag` or `tag/id`) of what changed in this
//! run — vessels whose frame changed, parts and nozzles whose frame or meshes
//! changed — so exporters and viewers can send only those.

use crate::components::ChangeLog;

use bevy_ecs::entity::Entity;
use bevy_ecs::hierarchy::ChildOf;
use bevy_ecs::system::{Query, ResMut};

use rayon::prelude::*;

use crate::components::{DirtyParts, DirtyPatches};

use crate::components::{NozzleSpec, PadOf, PartSpec, PatchOf, VesselSpec};

/// Owners beyond which their ids are made in parallel.
const PARALLEL_IDS: usize = 4096;

/// Part or nozzle identity: its vessel and its spec.
type Owner<'a> = (&'a ChildOf, Option<&'a PartSpec>, Option<&'a NozzleSpec>);

/// Records what changed in this run into the [`ChangeLog`] (from the dirty
/// lists, which it then clears for the next run).
pub fn collect_changes(
    patches: Query<(Option<&PatchOf>, Option<&PadOf>)>,
    owners: Query<Owner>,
    tags: Query<&VesselSpec>,
    mut log: ResMut<ChangeLog>,
    mut dirty: ResMut<DirtyPatches>,
    mut parts: ResMut<DirtyParts>,
) {
    for &v in &parts.vessel_frames {
        if let Ok(spec) = tags.get(v) {
            log.changed.insert(spec.tag.clone());
        }
    }
    let id_of =
        |child: &ChildOf, part: Option<&PartSpec>, nozzle: Option<&NozzleSpec>| -> Option<String> {
            let tag = &tags.get(child.parent()).ok()?.tag;
            let id = part
                .map(|p| p.0.id().to_string())
                .or_else(|| nozzle.map(|n| n.0.mark.clone()))?;
            Some(format!("{tag}/{id}"))
        };
    // Parts and nozzles that moved or changed shape, and the owners of the
    // patches meshed again: each named once (a full build meshes some twenty
    // patches per owner).
    let mut owner_ids: Vec<Entity> = parts.moved_or_reshaped();
    parts.clear();
    let owner = |&e: &Entity| {
        let (patch, pad) = patches.get(e).ok()?;
        patch.map(|p| p.0).or(pad.map(|p| p.0))
    };
    // In parallel after a full build, which meshes every patch of the plant.
    if dirty.meshes.len() >= PARALLEL_IDS {
        owner_ids.par_extend(dirty.meshes.par_iter().filter_map(owner));
        owner_ids.par_sort_unstable();
    } else {
        owner_ids.extend(dirty.meshes.iter().filter_map(owner));
        owner_ids.sort_unstable();
    }
    owner_ids.dedup();
    dirty.clear();
    // Named in parallel and sorted before they go into the log: after a full
    // build this is every part and nozzle of the plant, and inserting them one
    // by one was a serial tail of the build.
    let name = |&owner: &Entity| {
        let (c, p, n) = owners.get(owner).ok()?;
        id_of(c, p, n)
    };
    let mut ids: Vec<String> = if owner_ids.len() >= PARALLEL_IDS {
        owner_ids.par_iter().filter_map(name).collect()
    } else {
        owner_ids.iter().filter_map(name).collect()
    };
    if log.changed.is_empty() {
        ids.par_sort_unstable();
        // Built in bulk from the sorted list.
        log.changed = ids.into_iter().collect();
    } else {
        log.changed.extend(ids);
    }
}
