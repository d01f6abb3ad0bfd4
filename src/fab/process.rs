//! The process plan of one vessel: its bill of materials, weld map, PWHT
//! decision and operations in precedence levels — what `vesselcad fab`
//! writes, the live model keeps (`components::ProcessPlans`) and the server
//! serves as a traveler.
//!
//! PWHT: the vessel's material falls in a group of the shop rules (`pwht`);
//! the nominal thickness is, as UW-40(f) defines it for the vessel, the
//! thickest pressure weld (a weld with a UW-3 category); PWHT is required when
//! it exceeds the group's `required_above` (UCS-56 for P-No. 1: 38 mm).

use std::collections::BTreeMap;

use serde::Serialize;

use super::bom::{Bom, BomLine, bom};
use super::develop::boot_head_id;
use super::operations::{Item, Operation, plan_operations};
use super::plan_error::PlanError;
use super::shop_rules::{ShopRules, VESSEL_ITEM};
use super::vessel_plan::FabPlan;
use super::welds::{Weld, WeldKind, weld_map};
use crate::constraints::{PartGeometry, ResolvedVessel};
use crate::design::VesselDesign;

/// Whether the vessel needs PWHT, and why.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Pwht {
    /// Required.
    pub required: bool,
    /// The material group.
    pub group: String,
    /// Governing (nominal) thickness, mm.
    pub thickness: f64,
    /// The weld that governs.
    pub governing_weld: Option<String>,
    /// The code rule.
    pub rule: String,
}

/// A vessel's fabrication plan.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct ProcessPlan {
    /// Vessel tag.
    pub vessel: String,
    /// Bill of materials.
    pub bom: Bom,
    /// Every weld.
    pub welds: Vec<Weld>,
    /// PWHT decision.
    pub pwht: Pwht,
    /// The items operations are made on.
    pub items: Vec<Item>,
    /// Operations by level, ties by id.
    pub operations: Vec<Operation>,
}

impl ProcessPlan {
    /// Number of levels.
    pub fn level_count(&self) -> u32 {
        self.operations.iter().map(|o| o.level).max().unwrap_or(0)
    }
}

/// The PWHT decision for `design` with `welds`.
fn pwht(design: &VesselDesign, welds: &[Weld], rules: &ShopRules) -> Pwht {
    let governing = welds
        .iter()
        .filter(|w| w.category.is_some())
        .max_by(|a, b| a.thickness.total_cmp(&b.thickness).then(b.id.cmp(&a.id)));
    let thickness = governing.map_or(0.0, |w| w.thickness);
    let group = rules.pwht_group(design.design.material.as_deref());
    Pwht {
        required: group
            .and_then(|g| g.required_above)
            .is_some_and(|limit| thickness > limit),
        group: group.map_or_else(|| "no group".into(), |g| g.group.clone()),
        thickness,
        governing_weld: governing.map(|w| w.id.clone()),
        rule: group.map_or_else(
            || "no PWHT rule covers this material".into(),
            |g| g.rule.clone(),
        ),
    }
}

/// The items of a vessel, from its parts, nozzles and weld map.
fn items(resolved: &ResolvedVessel, welds: &[Weld]) -> Vec<Item> {
    let support_host: BTreeMap<&str, &str> = welds
        .iter()
        .filter(|w| matches!(w.kind, WeldKind::Support))
        .map(|w| (w.joins[0].as_str(), w.joins[1].as_str()))
        .collect();
    let mut out = Vec::new();
    for p in &resolved.parts {
        let kind = match p.geometry {
            PartGeometry::Shell(_) => "course",
            PartGeometry::Reducer(_) => "cone",
            PartGeometry::Head(_) => "head",
            PartGeometry::Skirt(_) => "skirt",
            PartGeometry::Boot(_) => "boot",
            PartGeometry::Saddle(_) | PartGeometry::Legs(_) | PartGeometry::Lugs(_) => "support",
        };
        let mut item = Item::new(p.id.clone(), kind);
        item.host = match p.host {
            Some(h) => resolved.parts.get(h).map(|h| h.id.clone()),
            None => support_host.get(p.id.as_str()).map(|h| (*h).to_string()),
        };
        out.push(item);
        if kind == "boot" {
            // Its head, formed like the vessel's and joined by a circ seam.
            out.push(Item::new(boot_head_id(&p.id), "head"));
        }
    }
    for w in welds.iter().filter(|w| w.kind == WeldKind::CircSeam) {
        let mut item = Item::new(w.item.clone(), "circ_joint");
        item.joins = w.joins.to_vec();
        out.push(item);
    }
    for n in &resolved.nozzles {
        let host = resolved.parts.get(n.host).map(|h| h.id.clone());
        let mut item = Item::new(n.mark.clone(), "nozzle");
        item.host.clone_from(&host);
        out.push(item);
        if n.pad.is_some() {
            let mut pad = Item::new(format!("{}/pad", n.mark), "pad");
            pad.host = host;
            pad.nozzle = Some(n.mark.clone());
            out.push(pad);
        }
    }
    out.push(Item::new(resolved.tag.clone(), VESSEL_ITEM));
    out
}

/// What an operation takes from the model, as the traveler prints it.
fn inputs(kind: &str, item: &Item, plan: &(Bom, Vec<Weld>, Pwht)) -> String {
    let (bom, welds, pwht) = plan;
    let lines: Vec<&BomLine> = bom
        .lines
        .iter()
        .filter(|l| l.item == item.id || (l.kind == "plate" && l.part == item.id))
        .collect();
    let line = lines.first().copied();
    let weld = |k: WeldKind| -> Vec<&Weld> {
        welds
            .iter()
            .filter(|w| w.kind == k && (w.item == item.id || w.joins[0] == item.id))
            .collect()
    };
    let weld_text = |ws: Vec<&Weld>| match ws.as_slice() {
        [] => String::new(),
        [w] => format!(
            "weld {} {:.0} mm, t {:.1} mm, {} ({}), {:.2} L metal",
            w.id,
            w.length,
            w.thickness,
            w.joint,
            w.prep,
            w.volume * 1e-6
        ),
        [w, ..] => format!(
            "{} welds {}…, {:.0} mm in all, t {:.1} mm, {} ({}), {:.2} L metal",
            ws.len(),
            w.id,
            ws.iter().map(|w| w.length).sum::<f64>(),
            w.thickness,
            w.joint,
            w.prep,
            ws.iter().map(|w| w.volume).sum::<f64>() * 1e-6
        ),
    };
    let plate = || {
        let sizes: Vec<String> = lines
            .iter()
            .map(|l| {
                if l.item == item.id {
                    l.size.clone()
                } else {
                    format!("{} {}", l.item, l.size)
                }
            })
            .collect();
        line.map_or(String::new(), |l| {
            format!(
                "{} {} t {} mm, {}",
                l.material,
                l.description,
                l.thickness.map_or("—".into(), |t| format!("{t:.1}")),
                sizes.join("; ")
            )
        })
    };
    match kind {
        "cut_plate" | "form_head" => plate(),
        "bevel" => weld_text(weld(WeldKind::LongSeam)),
        "roll" => line
            .and_then(|l| l.developed.as_ref())
            .and_then(|d| d.rolling_radius())
            .map_or(String::new(), |r| {
                format!("rolling radius {r:.1} mm (mid-thickness)")
            }),
        "weld_long_seam" => weld_text(weld(WeldKind::LongSeam)),
        "fit_up" | "weld_circ_seam" => weld_text(weld(WeldKind::CircSeam)),
        "cut_opening" | "fit_weld_nozzle" => weld_text(weld(WeldKind::Nozzle)),
        "cut_neck" => line.map_or(String::new(), |l| format!("{}, {}", l.description, l.size)),
        "weld_flange" => weld_text(weld(WeldKind::Flange)),
        "weld_pad" => [WeldKind::PadInner, WeldKind::PadOuter]
            .into_iter()
            .map(|k| weld_text(weld(k)))
            .collect::<Vec<_>>()
            .join("; "),
        "weld_support" => weld_text(weld(WeldKind::Support)),
        "pwht" => format!(
            "{}: nominal thickness {:.1} mm ({}); {}",
            pwht.group,
            pwht.thickness,
            pwht.governing_weld.as_deref().unwrap_or("—"),
            pwht.rule
        ),
        "hydrotest" => format!(
            "{} pressure welds, {:.0} mm of weld",
            welds.iter().filter(|w| w.category.is_some()).count(),
            welds
                .iter()
                .filter(|w| w.category.is_some())
                .map(|w| w.length)
                .sum::<f64>()
        ),
        "coat" => format!(
            "{:.1} m² of plate",
            bom.lines.iter().filter_map(|l| l.area).sum::<f64>()
        ),
        _ => plate(),
    }
}

/// The process plan of the vessel whose plate layout is `fab` (planned
/// with `rules.plates`).
///
/// # Errors
///
/// [`PlanError::Model`] for an opening that cannot be cut; [`PlanError::Cycle`]
/// when the rules' precedence has a cycle.
pub fn process_plan(fab: &FabPlan, rules: &ShopRules) -> Result<ProcessPlan, PlanError> {
    let (design, resolved) = (&fab.vessel, &fab.resolved);
    let welds = weld_map(fab, rules)?;
    let bom = bom(fab);
    let pwht = pwht(design, &welds, rules);
    let items = items(resolved, &welds);
    let context = (bom, welds, pwht);
    let operations = plan_operations(&resolved.tag, &items, rules, context.2.required, |k, i| {
        inputs(k, i, &context)
    })?;
    let (bom, welds, pwht) = context;
    Ok(ProcessPlan {
        vessel: resolved.tag.clone(),
        bom,
        welds,
        pwht,
        items,
        operations,
    })
}

/// Plans vessel `tag` of `design` with `rules` (plates by `rules.plates`):
/// its plate layout and its process plan.
///
/// # Errors
///
/// As [`super::plan`] and [`process_plan`].
pub fn plan_process(
    design: &crate::design::Design,
    tag: &str,
    rules: &ShopRules,
) -> Result<(FabPlan, ProcessPlan), super::FabError> {
    let fab = super::vessel_plan::plan(design, tag, &rules.plates)?;
    let process = process_plan(&fab, rules)?;
    Ok((fab, process))
}
