//! Process plans kept live: while the model has `ProcessPlanning` (its shop
//! rules), every vessel carries a `VesselProcessPlan` — BOM, weld map and
//! operations in levels, `fab::process_plan` of its design.
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
    VesselProcessPlan, VesselSpec, WorkCounters,
};
use crate::constraints::resolve_vessel;
use crate::fab::process_plan;

type VesselRow<'a> = (
    Entity,
    &'a VesselSpec,
    &'a DesignOrder,
    Option<&'a Children>,
    Option<&'a VesselProcessPlan>,
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
    for (entity, spec, order, children, plan) in &vessels {
        let resolved = pending.0.iter().find(|(e, _)| *e == entity).map(|(_, r)| r);
        if !(all || plan.is_none() || resolved.is_some()) {
            continue;
        }
        let design = read_vessel(spec, children, &parts, &nozzles, &notes);
        jobs.push((entity, design, order.0, resolved, plan));
    }
    if jobs.is_empty() {
        return;
    }
    counters.process_plans += jobs.len() as u64;
    let rules = &planning.0;
    let results: Vec<_> = jobs
        .into_par_iter()
        .map(|(entity, design, order, resolved, old)| {
            let plan = match resolved {
                Some(r) => process_plan(&design, r, rules).map_err(|e| e.to_string()),
                None => match resolve_vessel(&design, order as usize) {
                    Ok(r) => process_plan(&design, &r, rules).map_err(|e| e.to_string()),
                    Err(v) => Err(format!("{} broken rules", v.len())),
                },
            };
            (entity, plan.map(Arc::new), old)
        })
        .collect();
    for (entity, plan, old) in results {
        let new = VesselProcessPlan(plan);
        if old != Some(&new) {
            commands.entity(entity).insert(new);
        }
    }
}
