//! Fabrication plans kept live: while the model has `ProcessPlanning` (its
//! shop rules), every vessel carries a `VesselFabPlan` — its flat patterns and
//! seams, `fab::plan_vessel` from its previous plan, so that moving a nozzle
//! develops that nozzle's opening and its plate(s) again and lays out the
//! seams of its part, and nothing else (the `fab_*` counters) — and a
//! `VesselProcessPlan` on that layout: BOM, weld map and operations in levels.
//!
//! The plans run in the Validate stage, beside the resolution they are made
//! from (the Constrain stage consumes it): they read the resolved vessel
//! only, none of the patches or meshes the later stages build.
//!
//! Runs in the Validate stage after the vessels an edit touched were resolved:
//! a vessel is planned again when it was resolved in this run (its parts,
//! nozzles, frame or conditions changed), when it has no plan yet, or when the
//! shop rules were replaced; a level change alone resolves nothing and plans
//! nothing (the plan does not depend on the liquid). Plans are made in parallel
//! and written only where they differ. A vessel without a resolution in this
//! run (planning just turned on) is resolved here from its specs.

use std::sync::Arc;

use bevy_ecs::change_detection::DetectChanges;
use bevy_ecs::entity::Entity;
use bevy_ecs::hierarchy::Children;
use bevy_ecs::system::{Commands, Query, Res, ResMut};
use rayon::prelude::*;

use super::validate::read_vessel;
use crate::components::{
    DesignOrder, NoteSpec, NozzleSpec, PartSpec, PendingResolutions, ProcessPlanning,
    VesselFabPlan, VesselProcessPlan, VesselSpec, WorkCounters,
};
use crate::constraints::resolve_vessel;
use crate::fab::{FabWork, plan_vessel, process_plan};

type VesselRow<'a> = (
    Entity,
    &'a VesselSpec,
    &'a DesignOrder,
    Option<&'a Children>,
    Option<&'a VesselProcessPlan>,
    Option<&'a VesselFabPlan>,
);

/// Whether the model keeps process plans.
pub fn process_plans_kept(planning: Option<Res<ProcessPlanning>>) -> bool {
    planning.is_some()
}

/// Plans the vessels an edit resolved again (see the module documentation).
#[expect(clippy::too_many_arguments, reason = "one query per parameter kind")]
pub fn update_process_plans(
    planning: Res<ProcessPlanning>,
    pending: Res<PendingResolutions>,
    vessels: Query<VesselRow>,
    parts: Query<(&PartSpec, &DesignOrder)>,
    nozzles: Query<(&NozzleSpec, &DesignOrder)>,
    notes: Query<(&NoteSpec, &DesignOrder)>,
    mut commands: Commands,
    mut counters: ResMut<WorkCounters>,
) {
    let all = planning.is_changed();
    let mut jobs = Vec::new();
    for (entity, spec, order, children, plan, fab) in &vessels {
        let resolved = pending.0.iter().find(|(e, _)| *e == entity).map(|(_, r)| r);
        if !(all || plan.is_none() || resolved.is_some()) {
            continue;
        }
        let design = read_vessel(spec, children, &parts, &nozzles, &notes);
        let previous = fab.and_then(|f| f.0.as_ref().ok()).map(Arc::clone);
        jobs.push((entity, design, order.0, resolved, plan, previous));
    }
    if jobs.is_empty() {
        return;
    }
    counters.process_plans += jobs.len() as u64;
    let rules = &planning.0;
    let results: Vec<_> =
        jobs.into_par_iter()
            .map(|(entity, design, order, resolved, old, previous)| {
                let index = order as usize;
                let resolved = match resolved {
                    Some(r) => Ok(r.clone()),
                    None => resolve_vessel(&design, index)
                        .map_err(|v| format!("{} broken rules", v.len())),
                };
                let fab = resolved.and_then(|r| {
                    plan_vessel(&design, index, &r, &rules.plates, previous.as_deref())
                        .map_err(|e| e.to_string())
                });
                let (fab, work) = match fab {
                    Ok((f, w)) => (Ok(Arc::new(f)), w),
                    Err(e) => (Err(e), FabWork::default()),
                };
                let plan = fab
                    .as_ref()
                    .map_err(Clone::clone)
                    .and_then(|f| process_plan(f, rules).map_err(|e| e.to_string()));
                (entity, VesselFabPlan(fab), plan.map(Arc::new), old, work)
            })
            .collect();
    for (entity, fab, plan, old, work) in results {
        counters.fab_parts_developed += work.parts as u64;
        counters.fab_openings_developed += work.openings as u64;
        counters.fab_courses_laid_out += work.courses as u64;
        counters.fab_plates_cut += work.plates as u64;
        let new = VesselProcessPlan(plan);
        let mut e = commands.entity(entity);
        e.insert(fab);
        if old != Some(&new) {
            e.insert(new);
        }
    }
}
