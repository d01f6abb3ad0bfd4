//! Dirty-patch lists: the patches whose surface, region or mesh was written in
//! this run, handed from stage to stage so that the patch stages cost what
//! changed, not what exists.
//!
//! A plant of 10 000 vessels holds over a million patch entities; a
//! `Changed<PatchSurface>` filter still visits every one of them in every run
//! (about a millisecond per filter at that size). The systems that write a
//! patch's surface (`rebuild_dirty_patches`, `cut_openings` for pads), region
//! (`lay_out_regions`) or mesh (`remesh_dirty_patches`) push its entity here;
//! the next stage reads the list instead of scanning; `collect_changes` clears
//! it at the end of the run.

use std::sync::Arc;

use bevy_ecs::entity::Entity;
use bevy_ecs::resource::Resource;

use crate::mesh::cdt::Region;

/// Patches written in the current run of the schedule.
#[derive(Resource, Default, Debug)]
pub struct DirtyPatches {
    /// Patches whose `PatchSurface` was inserted or changed.
    pub surfaces: Vec<Entity>,
    /// Patches whose `PatchRegion` was inserted or changed.
    pub regions: Vec<Entity>,
    /// Patches whose `PatchMesh` was inserted or replaced.
    pub meshes: Vec<Entity>,
    /// Every region laid out in this run, changed or not: what the Tessellate
    /// stage meshes within (`PatchRegion` keeps only a fingerprint unless views
    /// are kept).
    pub laid_out: Vec<(Entity, Arc<Region>)>,
}

impl DirtyPatches {
    /// Empties every list (keeping their capacity).
    pub fn clear(&mut self) {
        self.surfaces.clear();
        self.regions.clear();
        self.meshes.clear();
        self.laid_out.clear();
    }
}
