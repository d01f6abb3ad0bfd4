//! Validate stage: find the vessels whose parameters changed and resolve them.
//!
//! A vessel is dirty when its own parameters changed or any of its parts, nozzles
//! or notes did (the model also marks it when it adds or removes children). Each
//! dirty vessel is read back into its design form and resolved by the constraint
//! rules, in parallel, unless `Model::apply` already resolved exactly that design
//! when it checked the edit ([`CheckedResolutions`]). A vessel that fails (only possible if the world was edited
//! around `Model::apply`) keeps its derived data and its violations are recorded.

use crate::components::{
    CheckedResolutions, EditedVessels, ModelErrors, ModelFailure, PendingResolutions,
};
use bevy_ecs::change_detection::Ref;
use bevy_ecs::entity::Entity;
use bevy_ecs::hierarchy::Children;
use bevy_ecs::system::{Query, ResMut};
use rayon::prelude::*;

use crate::components::WorkCounters;
use crate::components::{DesignOrder, NoteSpec, NozzleSpec, PartSpec, VesselSpec, same_in_order};
use crate::constraints::resolve_vessel;
use crate::design::VesselDesign;

/// Reads a vessel entity and its children back into the design form, children in
/// design order.
pub(crate) fn read_vessel(
    spec: &VesselSpec,
    children: Option<&Children>,
    parts: &Query<(&PartSpec, &DesignOrder)>,
    nozzles: &Query<(&NozzleSpec, &DesignOrder)>,
    notes: &Query<(&NoteSpec, &DesignOrder)>,
) -> VesselDesign {
    let kids: &[Entity] = children.map_or(&[], |c| c);
    let mut p: Vec<_> = kids.iter().filter_map(|&e| parts.get(e).ok()).collect();
    p.sort_by_key(|(_, o)| **o);
    let mut n: Vec<_> = kids.iter().filter_map(|&e| nozzles.get(e).ok()).collect();
    n.sort_by_key(|(_, o)| **o);
    let mut t: Vec<_> = kids.iter().filter_map(|&e| notes.get(e).ok()).collect();
    t.sort_by_key(|(_, o)| **o);
    VesselDesign {
        tag: spec.tag.clone(),
        kind: spec.kind,
        placement: spec.placement,
        design: spec.design.clone(),
        drawing: spec.drawing.clone(),
        parts: p.into_iter().map(|(s, _)| s.0.clone()).collect(),
        nozzles: n.into_iter().map(|(s, _)| s.0.clone()).collect(),
        notes: t.into_iter().map(|(s, _)| s.0.clone()).collect(),
        operating: None,
    }
}

/// Whether the vessel entity (its spec and children) holds exactly `design`
/// (operating data aside, as `read_vessel` reads it), compared in place.
fn holds(
    spec: &VesselSpec,
    children: Option<&Children>,
    parts: &Query<(&PartSpec, &DesignOrder)>,
    nozzles: &Query<(&NozzleSpec, &DesignOrder)>,
    notes: &Query<(&NoteSpec, &DesignOrder)>,
    design: &VesselDesign,
) -> bool {
    let kids: &[Entity] = children.map_or(&[], |c| c);
    spec.holds(design)
        && design.operating.is_none()
        && same(kids, parts, |p| &p.0, &design.parts)
        && same(kids, nozzles, |n| &n.0, &design.nozzles)
        && same(kids, notes, |n| &n.0, &design.notes)
}

/// Whether the children `kids` carrying `T`, in design order, hold exactly
/// `wanted` (as `inner` reads them).
fn same<T: bevy_ecs::component::Component, D: PartialEq>(
    kids: &[Entity],
    query: &Query<(&T, &DesignOrder)>,
    inner: impl Fn(&T) -> &D,
    wanted: &[D],
) -> bool {
    let found = kids.iter().filter_map(|&e| query.get(e).ok());
    same_in_order(found.map(|(t, o)| (inner(t), *o)), wanted)
}

/// Resolves every vessel whose parameters (or whose children's) changed.
#[expect(clippy::too_many_arguments, reason = "one query per parameter kind")]
pub fn resolve_dirty_vessels(
    vessels: Query<(Entity, Ref<VesselSpec>, &DesignOrder, Option<&Children>)>,
    mut edited: ResMut<EditedVessels>,
    parts: Query<(&PartSpec, &DesignOrder)>,
    nozzles: Query<(&NozzleSpec, &DesignOrder)>,
    notes: Query<(&NoteSpec, &DesignOrder)>,
    mut pending: ResMut<PendingResolutions>,
    mut checked: ResMut<CheckedResolutions>,
    mut errors: ResMut<ModelErrors>,
    mut counters: ResMut<WorkCounters>,
) {
    let mut checked = std::mem::take(&mut checked.0);
    let mut dirty: Vec<Entity> = std::mem::take(&mut edited.0);
    dirty.sort_unstable();
    dirty.dedup();
    let vessels_found: Vec<_> = dirty.iter().filter_map(|&e| vessels.get(e).ok()).collect();
    counters.vessels_resolved += vessels_found.len() as u64;
    // Each vessel's resolution from the edit's check when the world holds the
    // design it was checked on (compared in place, in parallel); the others
    // read back and resolved here.
    let work: Vec<_> = vessels_found
        .into_iter()
        .map(|(e, spec, order, kids)| (e, spec, order.0, kids, checked.remove(&e)))
        .collect();
    let results: Vec<_> = work
        .into_par_iter()
        .map(|(e, spec, order, kids, known)| {
            let known = known
                .filter(|(o, d, _)| *o == order && holds(&spec, kids, &parts, &nozzles, &notes, d));
            match known {
                Some((_, _, resolved)) => (e, None, Ok(resolved), true),
                None => {
                    let design = read_vessel(&spec, kids, &parts, &nozzles, &notes);
                    let result = resolve_vessel(&design, order as usize);
                    (e, Some(design.tag), result, false)
                }
            }
        })
        .collect();
    counters.resolutions_reused += results.iter().filter(|r| r.3).count() as u64;
    for (e, tag, result, _) in results {
        match result {
            Ok(resolved) => pending.0.push((e, resolved)),
            Err(violations) => errors
                .0
                .push(ModelFailure::Rules(tag.unwrap_or_default(), violations)),
        }
    }
}
