//! Operations of a fabrication plan and their precedence. The items of a vessel
//! are read from the model and its weld map — courses, cones, heads, skirt,
//! the circumferential joints, nozzles, boots, pads, supports and the vessel
//! itself — and every operation kind of the shop rules applies to the items of
//! its kinds. Each precedence rule adds an edge from each operation of a
//! `before` kind to each operation of its `after` kind whose items stand in the
//! rule's relation. Levels come from `levels` (1 + the deepest predecessor);
//! operations are listed by level, ties by their stable id `kind:item`.

use serde::Serialize;

use super::levels::levels;
use super::plan_error::PlanError;
use super::shop_rules::{Relation, ShopRules};

/// One item the plan makes operations for.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Item {
    /// Part id, nozzle mark, `mark/pad`, `A+B` (a circumferential joint) or the
    /// vessel tag.
    pub id: String,
    /// Item kind (`shop_rules::ITEM_KINDS` or `vessel`).
    pub kind: &'static str,
    /// The part it is mounted on (nozzles, boots, pads, supports).
    pub host: Option<String>,
    /// The two parts a circumferential joint joins.
    pub joins: Vec<String>,
    /// A pad's nozzle.
    pub nozzle: Option<String>,
}

impl Item {
    /// An item of `kind` named `id`.
    pub fn new(id: impl Into<String>, kind: &'static str) -> Item {
        Item {
            id: id.into(),
            kind,
            host: None,
            joins: Vec::new(),
            nozzle: None,
        }
    }
}

/// One operation, placed.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Operation {
    /// Stable id, `kind:item`.
    pub id: String,
    /// Operation kind (the rule's id).
    pub kind: String,
    /// Name on the traveler.
    pub name: String,
    /// Item id.
    pub item: String,
    /// Machine or method.
    pub method: String,
    /// Precedence level, from 1.
    pub level: u32,
    /// Ids of the operations that must be done first.
    pub after: Vec<String>,
    /// Inputs from the model (plate size, weld length, rolling radius, …).
    pub inputs: String,
}

/// Whether `p` relates to `q` as `relation` says (p the predecessor's item).
fn related(relation: Relation, p: &Item, q: &Item) -> bool {
    match relation {
        Relation::Same => p.id == q.id,
        Relation::Joined => q.joins.contains(&p.id),
        Relation::Host => q.host.as_deref() == Some(p.id.as_str()),
        Relation::HostJoints => q
            .host
            .as_ref()
            .is_some_and(|h| p.kind == "circ_joint" && p.joins.contains(h)),
        Relation::Nozzle => q.nozzle.as_deref() == Some(p.id.as_str()),
        Relation::Any => true,
    }
}

/// The operations of `items` (of vessel `vessel`) under `rules`, leveled and
/// sorted by (level, id). `pwht`: whether PWHT is required; `inputs` gives an
/// operation's inputs from its kind and item.
///
/// # Errors
///
/// [`PlanError::Cycle`] naming the operations of a precedence cycle.
pub fn plan_operations(
    vessel: &str,
    items: &[Item],
    rules: &ShopRules,
    pwht: bool,
    inputs: impl Fn(&str, &Item) -> String,
) -> Result<Vec<Operation>, PlanError> {
    let mut ops: Vec<(&str, &Item)> = Vec::new();
    for rule in &rules.operations {
        if rule.when.as_deref() == Some("pwht_required") && !pwht {
            continue;
        }
        for item in items {
            if rule.items.iter().any(|k| k == item.kind) {
                ops.push((rule.id.as_str(), item));
            }
        }
    }
    let mut edges = Vec::new();
    for rule in &rules.precedence {
        for (j, (kind, item)) in ops.iter().enumerate() {
            if *kind != rule.after {
                continue;
            }
            for (i, (pk, pi)) in ops.iter().enumerate() {
                if i != j && rule.before.iter().any(|b| b == pk) && related(rule.relation, pi, item)
                {
                    edges.push((i, j));
                }
            }
        }
    }
    edges.sort_unstable();
    edges.dedup();
    let id = |(kind, item): &(&str, &Item)| format!("{kind}:{}", item.id);
    let level = levels(ops.len(), &edges).map_err(|cycle| PlanError::Cycle {
        vessel: vessel.to_string(),
        cycle: cycle.iter().map(|&i| id(&ops[i])).collect(),
    })?;
    let mut out: Vec<Operation> = ops
        .iter()
        .enumerate()
        .map(|(j, op)| {
            let rule = rules.operation(op.0);
            let mut after: Vec<String> = edges
                .iter()
                .filter(|e| e.1 == j)
                .map(|e| id(&ops[e.0]))
                .collect();
            after.sort();
            Operation {
                id: id(op),
                kind: op.0.to_string(),
                name: rule.map(|r| r.name.clone()).unwrap_or_default(),
                item: op.1.id.clone(),
                method: rule.map(|r| r.method.clone()).unwrap_or_default(),
                level: level[j],
                after,
                inputs: inputs(op.0, op.1),
            }
        })
        .collect();
    out.sort_by(|a, b| (a.level, &a.id).cmp(&(b.level, &b.id)));
    Ok(out)
}
