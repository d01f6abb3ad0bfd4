//! Dirty lists: the parts whose frame, shape or host, and the patches whose
//! surface, region or mesh was written in this run, handed from stage to stage so
//! that every stage costs what changed, not what exists.
//!
//! A plant of 10 000 vessels holds over a million patch entities; a
//! `Changed<PatchSurface>` filter still visits every one of them in every run
//! (about a millisecond per filter at that size). The systems that write a
//! patch's surface (`rebuild_dirty_patches`, `cut_openings` for pads), region
//! (`lay_out_regions`) or mesh (`remesh_dirty_patches`) push its entity here;
//! the next stage reads the list instead of scanning; `collect_changes` clears
//! it at the end of the run. [`DirtyParts`] does the same one level up: the
//! Constrain stage (`apply_resolutions`, the only writer of frames, shapes and
//! hosts) lists the vessels, parts and nozzles it wrote, and `cut_openings`
//! the nozzles whose opening it wrote, for the Geometry, Tessellate and Export
//! stages (their `Changed<…>` filters visited every part of the plant in every
//! run: a third of a millisecond at 10 000 vessels).

use std::sync::Arc;

use bevy_ecs::entity::Entity;
use bevy_ecs::resource::Resource;

use crate::mesh::cdt::Region;

/// Regions laid out beyond which [`DirtyPatches::clear`] drops them in parallel.
const PARALLEL_DROP: usize = 4096;

/// Patches written in the current run of the schedule.
#[derive(Resource, Default, Debug)]
pub struct DirtyPatches {
    /// Patches whose `PatchSurface` was inserted or changed.
    pub surfaces: Vec<Entity>,
    /// Patches whose `PatchRegion` was inserted or changed.
    pub regions: Vec<Entity>,
    /// Patches whose `PatchMesh` was inserted or replaced.
    pub meshes: Vec<Entity>,
    /// Every region laid out in this run, changed or not, with its fingerprint:
    /// what the Tessellate stage meshes within (`PatchRegion` keeps only the
    /// fingerprint unless views are kept), and keys its mesh by (hashed once,
    /// by the layout).
    pub laid_out: Vec<(Entity, Arc<Region>, u128)>,
}

impl DirtyPatches {
    /// Empties every list (keeping their capacity). The regions laid out are
    /// dropped in parallel when there are many (after a full build, every
    /// patch's: most of them held only here).
    pub fn clear(&mut self) {
        self.surfaces.clear();
        self.regions.clear();
        self.meshes.clear();
        if self.laid_out.len() >= PARALLEL_DROP {
            use rayon::prelude::*;
            self.laid_out.par_drain(..).for_each(drop);
        } else {
            self.laid_out.clear();
        }
    }
}

/// Vessels, parts and nozzles written in the current run of the schedule.
#[derive(Resource, Default, Debug)]
pub struct DirtyParts {
    /// Vessels whose `VesselFrame` was inserted or changed.
    pub vessel_frames: Vec<Entity>,
    /// Parts and nozzles whose `PartFrame` was inserted or changed.
    pub frames: Vec<Entity>,
    /// Parts and nozzles whose `Shape` was inserted or changed.
    pub shapes: Vec<Entity>,
    /// Parts and nozzles whose `MountedOn` was inserted or changed.
    pub mounts: Vec<Entity>,
    /// Nozzles (and boots) whose `Opening` was inserted or changed.
    pub openings: Vec<Entity>,
}

impl DirtyParts {
    /// Parts and nozzles whose frame or shape was written, each once, in entity
    /// order.
    pub fn moved_or_reshaped(&self) -> Vec<Entity> {
        unique(self.frames.iter().chain(&self.shapes).copied())
    }

    /// Empties every list (keeping their capacity).
    pub fn clear(&mut self) {
        self.vessel_frames.clear();
        self.frames.clear();
        self.shapes.clear();
        self.mounts.clear();
        self.openings.clear();
    }
}

/// The entities of a dirty list, each once, in entity order.
pub fn unique(entities: impl IntoIterator<Item = Entity>) -> Vec<Entity> {
    let mut out: Vec<Entity> = entities.into_iter().collect();
    out.sort_unstable();
    out.dedup();
    out
}

/// Vessels whose own or whose children's parameters were written (or whose
/// children were added or removed) since the last update: pushed by the model's
/// edit commit, the only writer of parameter components, and drained by
/// `systems::resolve_dirty_vessels`. A list instead of `Changed<…>` filters, which
/// visit every part, nozzle and note of the plant on every update (0.3 ms at
/// 10 000 vessels).
#[derive(Resource, Default, Debug)]
pub struct EditedVessels(pub Vec<Entity>);
