//! Fabrication levels on the main export's scene: each part and nozzle node of
//! a vessel with a process plan gets `fab: {level, operations}` in its extras,
//! so a viewer of the main GLB can step through fabrication by level (show a
//! node once the viewer's level reaches its `level`).
//!
//! `operations` are the ids (`kind:item`) of the plan's operations made on the
//! node's item — a part id, a nozzle mark, and a nozzle's pad (`mark/pad`) —
//! in plan order (by level, ties by id). `level` is the level at which the
//! item joins the vessel: a nozzle's or boot's "fit and weld nozzle", a
//! support's or skirt's "weld support", a course's, cone's or head's first
//! fit-up with a neighbour; an item with none of these (a lone part) is placed
//! at the last level of its own operations. Nodes whose item has no
//! operation are left as they are.

use serde_json::{Value, json};

use super::process::ProcessPlan;
use crate::export::Scene;

/// Sets `fab: {level, operations}` on every part and nozzle node of the
/// vessels of `scene` that have a plan in `plans` (matched by tag).
pub fn annotate_scene(scene: &mut Scene, plans: &[&ProcessPlan]) {
    for vessel in &mut scene.vessels {
        let Some(plan) = plans.iter().find(|p| p.vessel == vessel.tag) else {
            continue;
        };
        for node in &mut vessel.nodes {
            if let Some(fab) = node_fab(plan, &node.id)
                && let Value::Object(map) = &mut node.extras
            {
                map.insert("fab".into(), fab);
            }
        }
    }
}

/// `{level, operations}` of item `id` in `plan`, or `None` when no operation
/// is made on it.
pub fn node_fab(plan: &ProcessPlan, id: &str) -> Option<Value> {
    let pad = format!("{id}/pad");
    let own: Vec<_> = plan
        .operations
        .iter()
        .filter(|o| o.item == id || o.item == pad)
        .collect();
    if own.is_empty() {
        return None;
    }
    let level_of = |op: &str| plan.operations.iter().find(|o| o.id == op).map(|o| o.level);
    let joined = level_of(&format!("fit_weld_nozzle:{id}"))
        .or_else(|| level_of(&format!("weld_support:{id}")))
        .or_else(|| {
            let joints: Vec<&str> = plan
                .items
                .iter()
                .filter(|i| i.joins.iter().any(|j| j == id))
                .map(|i| i.id.as_str())
                .collect();
            plan.operations
                .iter()
                .filter(|o| o.kind == "fit_up" && joints.contains(&o.item.as_str()))
                .map(|o| o.level)
                .min()
        });
    let level = joined.or_else(|| own.iter().map(|o| o.level).max());
    let operations: Vec<&str> = own.iter().map(|o| o.id.as_str()).collect();
    Some(json!({ "level": level, "operations": operations }))
}
