//! Work counters: how much each stage did in the last run of the schedule. Tests
//! use them to prove that work is proportional to what changed.

use bevy_ecs::resource::Resource;

/// Work done by the last run of the schedule (reset before each run).
#[derive(Resource, Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct WorkCounters {
    /// Vessels resolved (constraint layout recomputed).
    pub vessels_resolved: u64,
    /// Of the resolved vessels, those whose resolution was the one `Model::apply`
    /// computed when it checked the edit (see `CheckedResolutions`), not computed
    /// again.
    pub resolutions_reused: u64,
    /// Part and nozzle frames that changed.
    pub frames_updated: u64,
    /// Parts and nozzles whose shape changed (their patches were rebuilt).
    pub shapes_rebuilt: u64,
    /// Nozzle openings (neck–host intersections) recomputed.
    pub openings_cut: u64,
    /// Of the recomputed openings, those in a straight course whose nozzle only
    /// moved along the course's axis: placed again from their kept canonical cut
    /// instead of marched (see `mesh::cut_opening_reusing`).
    pub openings_placed: u64,
    /// Openings whose host or nozzle moved or changed but whose inputs (patches,
    /// relative placement, pad, tolerance) came out bit for bit the same, so
    /// they were not cut again.
    pub openings_unchanged: u64,
    /// Patch regions laid out again.
    pub regions_laid_out: u64,
    /// Trimmed patches whose surface was the same and whose openings' loops
    /// read the same (u, v) as at their last layout, so they were not laid out
    /// again (their region would come out the same).
    pub regions_unchanged: u64,
    /// Patches rebuilt.
    pub patches_rebuilt: u64,
    /// Patches whose extent the storage budget read (those rebuilt in this
    /// run; see `budget_storage_precision`).
    pub storage_extents_read: u64,
    /// Patch meshes rebuilt (replaced).
    pub meshes_rebuilt: u64,
    /// Of the rebuilt meshes, those taken from another patch with the same
    /// surface, region and options instead of being meshed (see
    /// [`MeshInstances`](crate::mesh::MeshInstances)).
    pub meshes_shared: u64,
    /// Triangles the mesher produced (shared meshes not counted).
    pub triangles_meshed: u64,
    /// Cavities round openings whose triangles a meshing took from its patch's
    /// last meshing instead of triangulating them (see `PatchCavities`).
    pub cavities_reused: u64,
    /// Patch meshes the mesher made (shared ones not counted) by the path that
    /// made them: sector, structured, general (see `mesh::cdt::MeshPath`).
    pub meshed_by_path: [u64; 3],
    /// Entity views (one part or nozzle in one view) rebuilt by the Project stage.
    pub views_rebuilt: u64,
    /// Vessels whose operating figures (liquid, weight, centre of gravity) were
    /// recomputed.
    pub operating_updated: u64,
    /// Pressure parts whose code calculation was redone.
    pub parts_calculated: u64,
    /// Nozzles whose UG-45 check was redone.
    pub nozzles_calculated: u64,
    /// Vessels whose calculated figures (MAWP, hydrotest, deficiencies) were
    /// gathered again.
    pub vessels_calculated: u64,
    /// Vessels whose process plan (BOM, weld map, operations) was made again
    /// (only while the model keeps process plans).
    pub process_plans: u64,
    /// Of those vessels' flat patterns (`fab::plan_vessel`): rolled parts and
    /// heads developed again.
    pub fab_parts_developed: u64,
    /// Nozzle openings, pads and neck ends developed again.
    pub fab_openings_developed: u64,
    /// Courses whose seams were laid out and checked again.
    pub fab_courses_laid_out: u64,
    /// Plates cut again.
    pub fab_plates_cut: u64,
    /// Vessels whose supports were calculated again (Zick's saddle stresses
    /// from the weight model: any edit of a vessel on saddles changes its weights).
    pub supports_calculated: u64,
    /// Patches or openings that failed to mesh or cut (details in `ModelErrors`).
    pub failures: u64,
}
