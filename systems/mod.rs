//! ECS systems and the schedule: Validate → Constrain → Geometry → Tessellate →
//! Project → Export, each a `SystemSet` in a chain.
//!
//! Every stage reads what changed upstream and writes downstream only when the value
//! really differs (`set_if_neq`), so untouched entities cost nothing but the
//! change-detection scan. The heavy stages (Geometry, Tessellate) collect their
//! dirty entities and process them in parallel with rayon. The components and
//! resources they read and write live in [`crate::components`].

mod biggest_first;
mod calculate;
mod clock;
mod constrain;
mod export;
mod geometry;
mod labels;
mod openings;
mod operating;
mod process;
mod project;
mod regions;
mod storage;
mod tessellate;
mod validate;

pub use calculate::update_calculations;
pub use clock::stamp_stage;
pub use constrain::apply_resolutions;
pub use export::collect_changes;
pub use geometry::rebuild_dirty_patches;
pub use openings::cut_openings;
pub use operating::update_operating_states;
pub use process::{process_plans_kept, update_process_plans};
pub use project::{entity_input, project_dirty_views, views_kept};
pub use regions::lay_out_regions;
pub use storage::budget_storage_precision;
pub use tessellate::remesh_dirty_patches;
pub use validate::resolve_dirty_vessels;

/// What [`Model::update`](crate::model::Model::update) returns and the length of
/// [`Model::stage_times`](crate::model::Model::stage_times), named here as well
/// as in [`crate::components`] for the library's users.
pub use crate::components::{STAGES, WorkCounters};

use bevy_ecs::schedule::{IntoScheduleConfigs, Schedule, SystemSet};

/// The pipeline stages, run in this order.
#[derive(SystemSet, Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Stage {
    /// Resolve and check vessels whose parameters changed.
    Validate,
    /// Write resolved frames, shapes, relations and note anchors.
    Constrain,
    /// Rebuild the exact patches of parts whose shape changed.
    Geometry,
    /// Re-mesh patches whose surface changed.
    Tessellate,
    /// Rebuild the drawing views of entities that changed or whose visibility did.
    Project,
    /// Record what changed for exporters and viewers.
    Export,
}

/// The model's schedule: every system in its stage, stages chained.
pub fn build_schedule() -> Schedule {
    let mut schedule = Schedule::default();
    schedule.configure_sets(
        (
            Stage::Validate,
            Stage::Constrain,
            Stage::Geometry,
            Stage::Tessellate,
            Stage::Project,
            Stage::Export,
        )
            .chain(),
    );
    schedule.add_systems((
        (
            resolve_dirty_vessels,
            update_operating_states,
            update_process_plans.run_if(process_plans_kept),
        )
            .chain()
            .in_set(Stage::Validate),
        apply_resolutions.in_set(Stage::Constrain),
        (
            rebuild_dirty_patches,
            budget_storage_precision,
            cut_openings,
            update_calculations,
        )
            .chain()
            .in_set(Stage::Geometry),
        (lay_out_regions, remesh_dirty_patches)
            .chain()
            .in_set(Stage::Tessellate),
        project_dirty_views
            .run_if(views_kept)
            .in_set(Stage::Project),
        collect_changes.in_set(Stage::Export),
    ));
    schedule.add_systems((
        stamp_stage::<0>.before(Stage::Validate),
        stamp_stage::<1>
            .after(Stage::Validate)
            .before(Stage::Constrain),
        stamp_stage::<2>
            .after(Stage::Constrain)
            .before(Stage::Geometry),
        stamp_stage::<3>
            .after(Stage::Geometry)
            .before(Stage::Tessellate),
        stamp_stage::<4>
            .after(Stage::Tessellate)
            .before(Stage::Project),
        stamp_stage::<5>.after(Stage::Project).before(Stage::Export),
        stamp_stage::<6>.after(Stage::Export),
    ));
    schedule
}
