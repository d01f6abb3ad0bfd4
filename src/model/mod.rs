//! The model: a bevy_ecs `World` holding the plant as entities, the schedule that
//! keeps derived data consistent, and transactional edits.
//!
//! This is the engine's front door. `Model::from_design` spawns the entities of a
//! design; [`Model::apply`] checks an [`Edit`] against every rule before writing
//! anything (a rejected edit leaves the world exactly as it was), and
//! [`Model::apply_each`] applies many, checking those on distinct vessels in
//! parallel; [`Model::update`] runs the schedule, which redoes only the work that
//! depends on what changed, and returns the [`WorkCounters`] of that run.
//!
//! The edits applied between two updates and the update that builds them are one
//! transaction over geometry too: when the run cannot cut or mesh what they
//! changed, every vessel they touched is put back as the last update that built
//! left it ([`Model::try_update`] returns [`ModelError::Geometry`];
//! [`Model::update`] keeps the failures in [`Model::errors`]). New tessellation
//! options are part of the same transaction: options that some patch cannot be
//! meshed to are put back with the edits. So no patch ever keeps a mesh of
//! another design or other options as if it were current: a patch that fails
//! to mesh loses its mesh, and the update that put it back meshes it again.
//! A failure is a [`BuildFailure`] (design path, stable id, stage and typed
//! cause), not a design rule. [`Model::edit`] is one edit and its update.

mod edit;
mod memory;
mod read;
mod staging;
mod sync;
mod undo;
#[cfg(test)]
mod world_writes;

pub use edit::Edit;
pub use memory::MemoryBreakdown;

use std::collections::HashSet;
use std::sync::Arc;

use bevy_ecs::change_detection::DetectChangesMut;
use bevy_ecs::query::{QueryState, ReadOnlyQueryData};
use bevy_ecs::schedule::Schedule;
use bevy_ecs::world::World;
use rayon::prelude::*;
use thiserror::Error;

pub use crate::components::Views;
pub use crate::components::{BuildCause, BuildFailure, ModelFailure};
use crate::components::{
    ChangeLog, CheckedResolutions, CutTable, DirtyParts, DirtyPatches, EditedVessels, Instances,
    ModelErrors, OpeningHosts, PendingResolutions, RequestedTessellation, StageTimes,
    StorageExtents, Tessellation, VesselIndex, WorkCounters,
};
use crate::design::{Design, DesignError};
use crate::export::Scene;
use crate::mesh::{OptionsError, TessellationOptions, check_storable};
use crate::systems::build_schedule;

/// Why an edit or model construction was refused. The model is unchanged.
#[derive(Debug, Error)]
pub enum ModelError {
    /// The edit would break design rules (every violation listed) or is malformed.
    #[error(transparent)]
    Design(#[from] DesignError),
    /// Tessellation options are invalid.
    #[error(transparent)]
    Options(#[from] OptionsError),
    /// The edit passes every rule but its geometry cannot be built: each failed
    /// part or nozzle is listed with its JSON path, stable id, the stage that
    /// failed (`shape`, `opening`, `region`, `mesh`) and the typed cause. The
    /// edit (and new tessellation options) were undone.
    #[error("the geometry cannot be built, nothing changed: {} failure(s):\n{}", .0.len(), .0.iter().map(|v| format!("  - {v}")).collect::<Vec<_>>().join("\n"))]
    Geometry(Vec<BuildFailure>),
    /// The edit names a vessel that does not exist.
    #[error("no vessel has the tag {tag:?}")]
    UnknownVessel {
        /// The tag given.
        tag: String,
    },
    /// The edit names a part, nozzle or note that does not exist in the vessel.
    #[error("vessel {vessel} has no {kind} {id:?}")]
    UnknownEntity {
        /// Vessel tag.
        vessel: String,
        /// `"part"`, `"nozzle"` or `"note"`.
        kind: &'static str,
        /// The id given.
        id: String,
    },
}

/// The plant model: world, schedule and edit API.
pub struct Model {
    world: World,
    schedule: Schedule,
    /// The vessels the edits applied since the last update touched, as that
    /// update left them: what a failed update puts back.
    undo: undo::Undo,
    /// The change log as it was before the first of those edits (the world's log
    /// then holds only theirs and the next run's): put back if the update fails,
    /// merged with the world's once it builds.
    log_before: Option<ChangeLog>,
    /// The tessellation options asked for before the first
    /// [`set_tessellation`](Self::set_tessellation) since the last update that
    /// built: put back with the edits if the update fails.
    options_before: Option<TessellationOptions>,
    /// Schedule runs since the model was made.
    runs: u64,
}

impl Model {
    /// An empty model meshing with `options`.
    pub fn new(options: TessellationOptions) -> Result<Self, ModelError> {
        options.validate()?;
        check_storable(&options, None)?;
        let mut world = World::new();
        // The patches are meshed to the options less the storage rounding
        // (`budget_storage_precision`), set on the first update.
        world.insert_resource(RequestedTessellation(options));
        world.insert_resource(Tessellation(options));
        world.init_resource::<WorkCounters>();
        world.init_resource::<StorageExtents>();
        world.init_resource::<Instances>();
        world.init_resource::<PendingResolutions>();
        world.init_resource::<ModelErrors>();
        world.init_resource::<ChangeLog>();
        world.init_resource::<VesselIndex>();
        world.init_resource::<OpeningHosts>();
        world.init_resource::<CutTable>();
        world.init_resource::<DirtyPatches>();
        world.init_resource::<DirtyParts>();
        world.init_resource::<Views>();
        world.init_resource::<StageTimes>();
        world.init_resource::<EditedVessels>();
        world.init_resource::<CheckedResolutions>();
        Ok(Self {
            world,
            schedule: build_schedule(),
            undo: undo::Undo::default(),
            log_before: None,
            options_before: None,
            runs: 0,
        })
    }

    /// A model holding `design` (checked first), fully built, views included.
    ///
    /// # Errors
    ///
    /// [`ModelError::Design`] for a design that breaks a rule,
    /// [`ModelError::Geometry`] for one whose geometry cannot be built (every
    /// failed part or nozzle listed).
    pub fn from_design(design: &Design, options: TessellationOptions) -> Result<Self, ModelError> {
        Self::from_design_with(design, options, Views::Kept)
    }

    /// [`from_design`](Self::from_design), keeping drawing views or not.
    pub fn from_design_with(
        design: &Design,
        options: TessellationOptions,
        views: Views,
    ) -> Result<Self, ModelError> {
        let mut model = Self::new(options)?;
        model.set_views(views);
        model.apply(Edit::ReplaceDesign(design.clone()))?;
        model.try_update()?;
        Ok(model)
    }

    /// Whether the Project stage keeps drawing views from the next update on.
    pub fn set_views(&mut self, views: Views) {
        // Only a real change counts: turning views on lays every region out again.
        self.world.resource_mut::<Views>().set_if_neq(views);
    }

    /// Checks `edit` against every rule and, if it passes, writes it into the
    /// world. Derived data follows on the next [`update`](Self::update), which
    /// puts the edit back if its geometry cannot be built.
    pub fn apply(&mut self, edit: Edit) -> Result<(), ModelError> {
        let staged = staging::stage(&self.world, edit)?;
        self.commit(staged);
        Ok(())
    }

    /// Writes a checked edit, recording first what it overwrites.
    fn commit(&mut self, staged: staging::Staged) {
        if self.log_before.is_none() {
            self.log_before = Some(std::mem::take(&mut *self.world.resource_mut::<ChangeLog>()));
        }
        self.undo.record(&self.world, &staged);
        sync::commit(&mut self.world, staged);
    }

    /// Applies `edits` in order, each as [`apply`](Self::apply) would after the
    /// ones before it, and returns each one's outcome: a refused edit leaves the
    /// world as it was and the next ones go on. Derived data follows on the next
    /// [`update`](Self::update).
    ///
    /// Runs of edits that each change one existing vessel, no two the same
    /// ([`Edit::vessel_tag`]), are checked in parallel and then written in
    /// order. Checking one reads only its own vessel, which the others do not
    /// write, so the outcome is that of applying them one by one.
    pub fn apply_each(&mut self, edits: Vec<Edit>) -> Vec<Result<(), ModelError>> {
        let mut out = Vec::with_capacity(edits.len());
        let mut edits = edits.into_iter().peekable();
        while edits.peek().is_some() {
            let mut run = Vec::new();
            let mut tags = HashSet::new();
            while let Some(tag) = edits.peek().and_then(Edit::vessel_tag) {
                if !tags.insert(tag.to_string()) {
                    break;
                }
                run.extend(edits.next());
            }
            if run.is_empty() {
                out.extend(edits.next().map(|edit| self.apply(edit)));
                continue;
            }
            let world = &self.world;
            let staged: Vec<_> = run
                .into_par_iter()
                .map(|edit| staging::stage(world, edit))
                .collect();
            for staged in staged {
                out.push(staged.map(|staged| self.commit(staged)));
            }
        }
        out
    }

    /// Runs the schedule once and returns the work it did.
    ///
    /// Transactional like [`try_update`](Self::try_update): when the run cannot
    /// build what the edits applied since the last update changed, those edits
    /// are undone (the model is as the last update that built left it) and the
    /// failures are kept in [`errors`](Self::errors) and counted in the returned
    /// counters' `failures`.
    pub fn update(&mut self) -> WorkCounters {
        match self.try_update_inner() {
            Ok(work) => work,
            Err(failed) => {
                let (work, failed) = *failed;
                self.world.resource_mut::<ModelErrors>().0 = failed;
                work
            }
        }
    }

    /// Runs the schedule once and returns the work it did, or, when the run
    /// cannot build what the edits applied since the last update changed (a
    /// patch that cannot be meshed, an opening that cannot be cut), undoes those
    /// edits and returns [`ModelError::Geometry`] naming each failure. Undone:
    /// every vessel they touched is put back and built again, and the change log
    /// is as it was, so the model is as the last update that built left it.
    /// Failures with no edit to undo (new tessellation options) are returned
    /// too, the model keeping what it could build.
    ///
    /// # Errors
    ///
    /// [`ModelError::Geometry`] with every [`BuildFailure`];
    /// [`ModelError::Design`] if the run found broken rules in the world (only
    /// possible when it was written around the edit checks).
    pub fn try_update(&mut self) -> Result<WorkCounters, ModelError> {
        self.try_update_inner().map_err(|failed| {
            let (_, failed) = *failed;
            let mut violations = Vec::new();
            let mut build = Vec::new();
            for f in failed {
                match f {
                    ModelFailure::Rules(_, v) => violations.extend(v),
                    ModelFailure::Build(b) => build.push(b),
                }
            }
            if violations.is_empty() {
                ModelError::Geometry(build)
            } else {
                ModelError::Design(DesignError::Invalid(violations))
            }
        })
    }

    /// [`try_update`](Self::try_update), failures kept by entity with the
    /// counters of the failed run.
    fn try_update_inner(&mut self) -> Result<WorkCounters, Box<(WorkCounters, Vec<ModelFailure>)>> {
        let undo = std::mem::take(&mut self.undo);
        let options_before = self.options_before.take();
        let work = self.run();
        let failed = std::mem::take(&mut self.world.resource_mut::<ModelErrors>().0);
        if failed.is_empty() {
            self.merge_log();
            return Ok(work);
        }
        if !undo.is_empty() || options_before.is_some() {
            if let Some(options) = options_before {
                self.world.resource_mut::<RequestedTessellation>().0 = options;
            }
            sync::commit(&mut self.world, undo.staged());
            self.run();
            self.world.resource_mut::<ModelErrors>().0.clear();
            *self.world.resource_mut::<ChangeLog>() = self.log_before.take().unwrap_or_default();
        }
        Err(Box::new((work, failed)))
    }

    /// Puts the log kept before the transaction's first edit back under the
    /// world's: the smaller is merged into the larger, so the cost is that of
    /// the smaller (an edit's few ids, not the plant's).
    fn merge_log(&mut self) {
        let Some(mut before) = self.log_before.take() else {
            return;
        };
        let mut log = self.world.resource_mut::<ChangeLog>();
        let log = &mut *log;
        for (into, from) in [
            (&mut log.changed, &mut before.changed),
            (&mut log.removed, &mut before.removed),
        ] {
            if into.len() < from.len() {
                std::mem::swap(into, from);
            }
            into.append(from);
        }
    }

    /// Runs the schedule once.
    fn run(&mut self) -> WorkCounters {
        self.runs += 1;
        *self.world.resource_mut::<WorkCounters>() = WorkCounters::default();
        // Errors describe the last run only, like the counters.
        self.world.resource_mut::<ModelErrors>().0.clear();
        // The whole run on a worker of rayon's pool: the stages' parallel loops
        // then start as pushes onto that worker's own queue. Called from outside
        // the pool, each of them would hand its work over through a lock and
        // block the calling thread until a worker woke to take it.
        let (schedule, world) = (&mut self.schedule, &mut self.world);
        rayon::scope(|_| schedule.run(world));
        // Start the next run's removal messages afresh (the Tessellate stage reads
        // them to find openings that disappeared).
        self.world.clear_trackers();
        *self.world.resource::<WorkCounters>()
    }

    /// [`apply`](Self::apply) then [`try_update`](Self::try_update), as one
    /// transaction that covers the geometry too: when the update cannot build
    /// what the edit changed, the edit is undone — the touched vessels are put
    /// back and built again, the change log is as it was — and refused with
    /// [`ModelError::Geometry`], naming each failure. Edits applied before it and
    /// not yet updated are part of the same transaction.
    pub fn edit(&mut self, edit: Edit) -> Result<WorkCounters, ModelError> {
        self.apply(edit)?;
        self.try_update()
    }

    /// Changes the tessellation options; every patch is re-meshed on the next
    /// update. That update is transactional for them too: if some patch cannot
    /// be meshed to them, the options in force before are put back (with the
    /// edits applied since the last update) and the failure is reported.
    pub fn set_tessellation(&mut self, options: TessellationOptions) -> Result<(), ModelError> {
        options.validate()?;
        check_storable(&options, None)?;
        let mut t = self.world.resource_mut::<RequestedTessellation>();
        if t.0 != options {
            let before = std::mem::replace(&mut t.0, options);
            self.options_before.get_or_insert(before);
        }
        Ok(())
    }

    /// The current design, read back from the entities (canonical: mm).
    pub fn design(&self) -> Design {
        read::design(&self.world)
    }

    /// The code calculation of vessel `tag` as the last update left it (parts
    /// and nozzles in design order); `None` for an unknown tag or before the
    /// first update.
    pub fn calculation(&self, tag: &str) -> Option<crate::calc::Calculation> {
        let entity = *self.world.resource::<VesselIndex>().0.get(tag)?;
        read::calculation(&self.world, entity)
    }

    /// Keeps flat patterns with their seams and a process plan (BOM, weld
    /// map, operations in levels) on every vessel from the next update on,
    /// following `rules`; `None` stops and
    /// drops the plans at the next update's pass (see
    /// `systems::update_process_plans`).
    pub fn set_process_planning(&mut self, rules: Option<Arc<crate::fab::ShopRules>>) {
        match rules {
            Some(r) => {
                self.world
                    .insert_resource(crate::components::ProcessPlanning(r));
            }
            None => {
                self.world
                    .remove_resource::<crate::components::ProcessPlanning>();
            }
        }
    }

    /// The process plan of vessel `tag` as the last update left it, or why it
    /// could not be made; `None` for an unknown tag or while plans are not kept.
    pub fn process_plan(&self, tag: &str) -> Option<Result<Arc<crate::fab::ProcessPlan>, String>> {
        self.world
            .get_resource::<crate::components::ProcessPlanning>()?;
        let entity = *self.world.resource::<VesselIndex>().0.get(tag)?;
        self.world
            .get::<crate::components::VesselProcessPlan>(entity)
            .map(|p| p.0.clone())
    }

    /// The flat patterns and seam layout of vessel `tag` as the last update
    /// left them, or why they could not be made; `None` for an unknown tag or
    /// while plans are not kept (see [`Model::set_process_planning`]).
    pub fn fab_plan(&self, tag: &str) -> Option<Result<Arc<crate::fab::FabPlan>, String>> {
        self.world
            .get_resource::<crate::components::ProcessPlanning>()?;
        let entity = *self.world.resource::<VesselIndex>().0.get(tag)?;
        self.world
            .get::<crate::components::VesselFabPlan>(entity)
            .map(|p| p.0.clone())
    }

    /// The plant as a scene for the exporters (meshes as of the last update).
    pub fn scene(&self) -> Scene {
        read::scene(&self.world)
    }

    /// The scene of the vessels `tags` alone, in the order given (unknown tags
    /// are left out): what a viewer needs after an edit of those vessels,
    /// without reading the rest of the plant.
    pub fn vessels_scene<S: AsRef<str>>(&self, tags: &[S]) -> Scene {
        let index = &self.world.resource::<VesselIndex>().0;
        let entities = tags
            .iter()
            .filter_map(|t| index.get(t.as_ref()).copied())
            .collect();
        read::scene_of(&self.world, entities)
    }

    /// The design of vessel `tag` as the entities hold it (canonical: mm);
    /// `None` for an unknown tag.
    pub fn vessel_design(&self, tag: &str) -> Option<crate::design::VesselDesign> {
        let entity = *self.world.resource::<VesselIndex>().0.get(tag)?;
        read::vessel(&self.world, entity)
    }

    /// How many times the schedule ran since the model was made (an update
    /// that fails and is undone runs it twice): what a caller that must build
    /// once, such as a session replaying its journal, is checked by.
    pub fn runs(&self) -> u64 {
        self.runs
    }

    /// The ids changed and removed since the last call.
    pub fn take_changes(&mut self) -> ChangeLog {
        self.merge_log();
        std::mem::take(&mut *self.world.resource_mut::<ChangeLog>())
    }

    /// What the last update could not do (normally nothing): build failures
    /// and rule violations found in the world.
    pub fn errors(&self) -> &ModelErrors {
        self.world.resource::<ModelErrors>()
    }

    /// Bytes held by the patch meshes (positions, normals and indices): the
    /// bulk of a built model's memory.
    pub fn mesh_bytes(&self) -> usize {
        self.memory().meshes
    }

    /// How long each stage (Validate, Constrain, Geometry, Tessellate, Project,
    /// Export) took in the last update.
    pub fn stage_times(&self) -> [std::time::Duration; crate::systems::STAGES] {
        self.world.resource::<StageTimes>().durations()
    }

    /// Heap bytes of the derived data by kind (meshes, surfaces, regions,
    /// openings).
    pub fn memory(&self) -> MemoryBreakdown {
        memory::breakdown(&self.world)
    }

    /// The ECS world, to read. Nothing outside the model writes it: parameters
    /// change through [`apply`](Self::apply) and [`edit`](Self::edit), which check
    /// the edit and list what the next [`update`](Self::update) must redo (the
    /// dirty lists); a write past them would be missed by every stage. There is
    /// no mutable access:
    ///
    /// ```compile_fail,E0599
    /// # use vesselcad::mesh::TessellationOptions;
    /// # use vesselcad::model::Model;
    /// # let mut model = Model::new(TessellationOptions::DEFAULT).unwrap();
    /// let world = model.world_mut();
    /// ```
    pub fn world(&self) -> &World {
        &self.world
    }

    /// A read-only query over the model's entities (building a query state
    /// registers its components, which needs the model mutably):
    ///
    /// ```
    /// # use vesselcad::components::PatchMesh;
    /// # use vesselcad::mesh::TessellationOptions;
    /// # use vesselcad::model::Model;
    /// # let mut model = Model::new(TessellationOptions::DEFAULT).unwrap();
    /// let mut meshes = model.query::<&PatchMesh>();
    /// let triangles: usize = meshes
    ///     .iter(model.world())
    ///     .map(|m| m.0.triangle_count())
    ///     .sum();
    /// # assert_eq!(triangles, 0);
    /// ```
    ///
    /// Components cannot be written through it:
    ///
    /// ```compile_fail,E0277
    /// # use vesselcad::components::NozzleSpec;
    /// # use vesselcad::mesh::TessellationOptions;
    /// # use vesselcad::model::Model;
    /// # let mut model = Model::new(TessellationOptions::DEFAULT).unwrap();
    /// let mut specs = model.query::<&mut NozzleSpec>();
    /// ```
    pub fn query<D: ReadOnlyQueryData>(&mut self) -> QueryState<D> {
        self.world.query::<D>()
    }
}
