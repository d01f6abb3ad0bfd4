//! The code calculations kept live: after the Geometry stage, recompute only what
//! an edit touched. A part is recalculated when its parameters, shape or span
//! changed, when a nozzle mounted on it changed (or was added or removed), or
//! when its vessel's design conditions, operating data or liquid surface did; a
//! nozzle when it changed or its host's result did; a vessel's figures when any
//! of its parts or nozzles got a new result, or its own design changed (an edit
//! of its wind or earthquake alone recalculates its figures and supports, no
//! part). Results are written only where they
//! differ. The figures are those of `calc::calculate`, part by part.

use std::sync::{Arc, OnceLock};

use bevy_ecs::change_detection::{DetectChanges, Ref};
use bevy_ecs::entity::Entity;
use bevy_ecs::hierarchy::{ChildOf, Children};
use bevy_ecs::system::{Commands, Query, Res, ResMut};
use rustc_hash::{FxHashMap, FxHashSet};

use super::WorkCounters;
use crate::calc::{
    Conditions, Liquid, MaterialTable, NozzleCalc, PartCalc, VesselCalc, conditions,
    has_calculated_supports, nozzle_calc, part_calc, support_calcs,
};
use crate::components::{
    DesignOrder, Materials, MountedOn, Mounts, NozzleCalculation, NozzleSpec, OperatingSpec,
    PartCalculation, PartSpan, PartSpec, Shape, VesselCalculation, VesselSpec,
};
use crate::constraints::resolve_vessel;
use crate::design::{PartDesign, VesselDesign};
use crate::operating::thickness;

fn builtin() -> &'static Arc<MaterialTable> {
    static TABLE: OnceLock<Arc<MaterialTable>> = OnceLock::new();
    TABLE.get_or_init(|| Arc::new(MaterialTable::builtin()))
}

type PartRow<'a> = (
    Entity,
    Ref<'a, PartSpec>,
    Option<Ref<'a, Shape>>,
    Option<Ref<'a, PartSpan>>,
    Option<Ref<'a, Mounts>>,
    &'a ChildOf,
    &'a DesignOrder,
    Option<&'a PartCalculation>,
);

type VesselRow<'a> = (
    Entity,
    Ref<'a, VesselSpec>,
    Ref<'a, OperatingSpec>,
    Option<&'a Children>,
    Option<&'a VesselCalculation>,
);

type NozzleRow<'a> = (
    Entity,
    Ref<'a, NozzleSpec>,
    Option<Ref<'a, Shape>>,
    Option<Ref<'a, MountedOn>>,
    &'a ChildOf,
    &'a DesignOrder,
    Option<&'a NozzleCalculation>,
);

/// Recomputes the calculations an edit touched (see the module documentation).
pub fn update_calculations(
    materials: Option<Res<Materials>>,
    vessels: Query<VesselRow>,
    parts: Query<PartRow>,
    nozzles: Query<NozzleRow>,
    mut commands: Commands,
    mut counters: ResMut<WorkCounters>,
    mut dirty_parts: bevy_ecs::system::Local<FxHashSet<Entity>>,
) {
    let table: &MaterialTable = materials.as_ref().map_or(builtin(), |m| &m.0);
    // Vessels whose own inputs changed.
    let mut touched: FxHashSet<Entity> = vessels
        .iter()
        .filter(|(_, spec, op, _, calc)| spec.is_changed() || op.is_changed() || calc.is_none())
        .map(|(e, ..)| e)
        .collect();
    // Parts and nozzles whose own inputs changed.
    dirty_parts.clear();
    for (e, spec, shape, span, mounts, parent, ..) in &parts {
        if spec.is_changed()
            || shape.is_some_and(|s| s.is_changed())
            || span.is_some_and(|s| s.is_changed())
            || mounts.is_some_and(|m| m.is_changed())
        {
            dirty_parts.insert(e);
            touched.insert(parent.parent());
        }
    }
    let mut dirty_nozzles: FxHashSet<Entity> = FxHashSet::default();
    for (e, spec, shape, host, parent, ..) in &nozzles {
        if spec.is_changed()
            || shape.is_some_and(|s| s.is_changed())
            || host.as_ref().is_some_and(|h| h.is_changed())
        {
            dirty_nozzles.insert(e);
            if let Some(h) = host {
                dirty_parts.insert(h.0);
            }
            touched.insert(parent.parent());
        }
    }
    if touched.is_empty() {
        return;
    }
    // Conditions and liquid of every vessel with something to do; a vessel whose
    // conditions or liquid changed has all its parts recalculated.
    let mut state: FxHashMap<Entity, (Result<Conditions, String>, Option<Liquid>)> =
        FxHashMap::default();
    let mut all: Vec<Entity> = touched.iter().copied().collect();
    all.sort();
    for &v in &all {
        let Ok((_, spec, op, children, calc)) = vessels.get(v) else {
            continue;
        };
        let kind = spec.kind;
        let stack = children.into_iter().flatten().filter_map(|&c| {
            let (_, spec, shape, span, ..) = parts.get(c).ok()?;
            let Some(Shape::Part(g)) = shape.as_deref() else {
                return None;
            };
            Liquid::bounds(kind, g).then_some(())?;
            Some((span.map(|s| (s.0, s.1))?, thickness(&spec.0).unwrap_or(0.0)))
        });
        let liquid = Liquid::of(spec.kind, op.0, stack);
        let conds = conditions(&spec.design, spec.kind, table);
        // The parts read only the conditions and the liquid: an edit of the
        // vessel that leaves both as they were (its wind, earthquake, placement)
        // recalculates its supports only.
        let whole = op.is_changed()
            || calc.is_none_or(|c| {
                c.liquid != liquid || c.calc.conditions.as_ref() != conds.as_ref().ok()
            });
        if whole {
            for &c in children.into_iter().flatten() {
                if parts.contains(c) {
                    dirty_parts.insert(c);
                }
                if nozzles.contains(c) {
                    dirty_nozzles.insert(c);
                }
            }
        }
        state.insert(v, (conds, liquid));
    }
    // Parts.
    let mut new_parts: FxHashMap<Entity, Option<Result<PartCalc, String>>> = FxHashMap::default();
    let mut order: Vec<Entity> = dirty_parts.iter().copied().collect();
    order.sort();
    for e in order {
        let Ok((_, spec, shape, span, mounts, parent, _, old)) = parts.get(e) else {
            continue;
        };
        let Some((conds, liquid)) = state.get(&parent.parent()) else {
            continue;
        };
        counters.parts_calculated += 1;
        let result = match (conds, shape.as_deref(), span) {
            (Ok(c), Some(Shape::Part(g)), Some(span)) => {
                let mut openings: Vec<(DesignOrder, String)> = mounts
                    .iter()
                    .flat_map(|m| m.entities().iter().copied())
                    .filter_map(|n| nozzles.get(n).ok())
                    .map(|(_, spec, _, _, _, o, _)| (*o, spec.0.mark.clone()))
                    .collect();
                openings.sort();
                let head = liquid.map_or(0.0, |l| l.head_at(span.0));
                let openings = openings.into_iter().map(|(_, m)| m).collect();
                part_calc(
                    spec.0.id(),
                    g,
                    thickness(&spec.0),
                    head,
                    liquid.as_ref(),
                    openings,
                    c,
                )
                .transpose()
            }
            _ => None,
        };
        if old.map(|o| &o.0) != result.as_ref() {
            match &result {
                Some(r) => commands.entity(e).insert(PartCalculation(r.clone())),
                None => commands.entity(e).remove::<PartCalculation>(),
            };
            touched.insert(parent.parent());
            for &n in mounts.iter().flat_map(|m| m.entities()) {
                if nozzles.contains(n) {
                    dirty_nozzles.insert(n);
                }
            }
        }
        new_parts.insert(e, result);
    }
    let part_result = |e: Entity| -> Option<Result<PartCalc, String>> {
        match new_parts.get(&e) {
            Some(r) => r.clone(),
            None => parts.get(e).ok()?.7.map(|c| c.0.clone()),
        }
    };
    // Nozzles.
    let mut new_nozzles: FxHashMap<Entity, Option<Result<NozzleCalc, String>>> =
        FxHashMap::default();
    let mut order: Vec<Entity> = dirty_nozzles.into_iter().collect();
    order.sort();
    for e in order {
        let Ok((_, spec, shape, host, parent, _, old)) = nozzles.get(e) else {
            continue;
        };
        let Some((conds, _)) = state.get(&parent.parent()) else {
            continue;
        };
        counters.nozzles_calculated += 1;
        let host_calc = host.and_then(|h| part_result(h.0));
        let result = match (conds, shape.as_deref(), host_calc) {
            (Ok(c), Some(Shape::Nozzle(n, pad)), Some(Ok(h))) => {
                Some(nozzle_calc(&spec.0.mark, n, *pad, &h, c))
            }
            _ => None,
        };
        if old.map(|o| &o.0) != result.as_ref() {
            match &result {
                Some(r) => commands.entity(e).insert(NozzleCalculation(r.clone())),
                None => commands.entity(e).remove::<NozzleCalculation>(),
            };
        }
        new_nozzles.insert(e, result);
    }
    // Vessels: gather from their children (new results where recomputed).
    let mut all: Vec<Entity> = touched.into_iter().collect();
    all.sort();
    for v in all {
        let Ok((_, spec, op, children, old)) = vessels.get(v) else {
            continue;
        };
        let Some((conds, liquid)) = state.remove(&v) else {
            continue;
        };
        counters.vessels_calculated += 1;
        let mut part_calcs: Vec<(DesignOrder, PartCalc)> = Vec::new();
        let mut nozzle_calcs: Vec<(DesignOrder, NozzleCalc)> = Vec::new();
        let mut problems: Vec<(DesignOrder, String)> = Vec::new();
        for &c in children.into_iter().flatten() {
            if let Ok(row) = parts.get(c) {
                match part_result(c) {
                    Some(Ok(p)) => part_calcs.push((*row.6, p)),
                    Some(Err(e)) => problems.push((*row.6, e)),
                    None => {}
                }
            } else if let Ok(row) = nozzles.get(c) {
                let r = match new_nozzles.get(&c) {
                    Some(r) => r.clone(),
                    None => row.6.map(|n| n.0.clone()),
                };
                match r {
                    Some(Ok(n)) => nozzle_calcs.push((*row.5, n)),
                    Some(Err(e)) => problems.push((DesignOrder(u32::MAX), e)),
                    None => {}
                }
            }
        }
        part_calcs.sort_by_key(|(o, _)| *o);
        nozzle_calcs.sort_by_key(|(o, _)| *o);
        problems.sort_by_key(|(o, _)| *o);
        let mut calc = VesselCalc::gather(
            &spec.tag,
            spec.kind,
            conds,
            &part_calcs.iter().map(|(_, p)| p).collect::<Vec<_>>(),
            &nozzle_calcs.iter().map(|(_, n)| n).collect::<Vec<_>>(),
            problems.into_iter().map(|(_, p)| p).collect(),
        );
        if let Some(design) = supported_design(&spec, &op, children, &parts, &nozzles) {
            counters.supports_calculated += 1;
            match resolve_vessel(&design, 0) {
                Ok(resolved) => support_calcs(&design, &resolved, table, &mut calc),
                Err(v) => calc.problems.push(format!(
                    "supports: the vessel does not resolve ({} rule(s) broken)",
                    v.len()
                )),
            }
        }
        let new = VesselCalculation { calc, liquid };
        if old != Some(&new) {
            commands.entity(v).insert(new);
        }
    }
}

/// The design of a vessel with calculated supports (a horizontal one on saddles,
/// a vertical one on a skirt, legs or lugs) as its entities hold it (parts and
/// nozzles in design order; notes left out: the supports' calculation does not
/// read them), for the weights the supports carry; `None` for any other
/// vessel, whose supports are not calculated.
fn supported_design(
    spec: &VesselSpec,
    op: &OperatingSpec,
    children: Option<&Children>,
    parts: &Query<PartRow>,
    nozzles: &Query<NozzleRow>,
) -> Option<VesselDesign> {
    let mut part_list: Vec<(DesignOrder, PartDesign)> = Vec::new();
    let mut nozzle_list = Vec::new();
    for &c in children.into_iter().flatten() {
        if let Ok(row) = parts.get(c) {
            part_list.push((*row.6, row.1.0.clone()));
        } else if let Ok(row) = nozzles.get(c) {
            nozzle_list.push((*row.5, row.1.0.clone()));
        }
    }
    if !has_calculated_supports(
        spec.kind,
        &part_list.iter().map(|(_, p)| p).collect::<Vec<_>>(),
    ) {
        return None;
    }
    part_list.sort_by_key(|(o, _)| *o);
    nozzle_list.sort_by_key(|(o, _)| *o);
    Some(VesselDesign {
        tag: spec.tag.clone(),
        kind: spec.kind,
        placement: spec.placement,
        design: spec.design.clone(),
        drawing: spec.drawing.clone(),
        parts: part_list.into_iter().map(|(_, p)| p).collect(),
        nozzles: nozzle_list.into_iter().map(|(_, n)| n).collect(),
        notes: Vec::new(),
        operating: op.0,
    })
}
