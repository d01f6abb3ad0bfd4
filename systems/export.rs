//! Export stage: record the stable ids (`tag` or `tag/id`) of what changed in this
//! run — vessels whose frame changed, parts and nozzles whose frame or meshes
//! changed — so exporters and viewers can send only those.

use std::collections::BTreeSet;

use bevy_ecs::entity::Entity;
use bevy_ecs::hierarchy::ChildOf;
use bevy_ecs::query::{Changed, Or};
use bevy_ecs::resource::Resource;
use bevy_ecs::system::{Query, ResMut};

use super::DirtyPatches;

use crate::components::{NozzleSpec, PadOf, PartFrame, PartSpec, PatchOf, VesselFrame, VesselSpec};

/// Stable ids changed and removed since the log was last drained.
#[derive(Resource, Default, Debug, Clone, PartialEq, Eq)]
pub struct ChangeLog {
    /// Ids of vessels, parts and nozzles whose frame or geometry changed.
    pub changed: BTreeSet<String>,
    /// Ids of entities that were removed.
    pub removed: BTreeSet<String>,
}

/// Part or nozzle identity: its vessel and its spec.
type Owner<'a> = (&'a ChildOf, Option<&'a PartSpec>, Option<&'a NozzleSpec>);
/// A part or nozzle whose frame or shape changed.
type MovedFilter = Or<(Changed<PartFrame>, Changed<crate::components::Shape>)>;

/// Records what changed in this run into the [`ChangeLog`].
pub fn collect_changes(
    vessels: Query<&VesselSpec, Changed<VesselFrame>>,
    moved: Query<Owner, MovedFilter>,
    patches: Query<(Option<&PatchOf>, Option<&PadOf>)>,
    owners: Query<Owner>,
    tags: Query<&VesselSpec>,
    mut log: ResMut<ChangeLog>,
    mut dirty: ResMut<DirtyPatches>,
) {
    for v in &vessels {
        log.changed.insert(v.tag.clone());
    }
    let id_of =
        |child: &ChildOf, part: Option<&PartSpec>, nozzle: Option<&NozzleSpec>| -> Option<String> {
            let tag = &tags.get(child.parent()).ok()?.tag;
            let id = part
                .map(|p| p.0.id().to_string())
                .or_else(|| nozzle.map(|n| n.0.mark.clone()))?;
            Some(format!("{tag}/{id}"))
        };
    for (c, p, n) in &moved {
        if let Some(id) = id_of(c, p, n) {
            log.changed.insert(id);
        }
    }
    let owner_ids: Vec<Entity> = dirty
        .meshes
        .iter()
        .filter_map(|&e| patches.get(e).ok())
        .filter_map(|(patch, pad)| patch.map(|p| p.0).or(pad.map(|p| p.0)))
        .collect();
    dirty.clear();
    for owner in owner_ids {
        if let Ok((c, p, n)) = owners.get(owner)
            && let Some(id) = id_of(c, p, n)
        {
            log.changed.insert(id);
        }
    }
}
