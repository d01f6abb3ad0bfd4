//! The shop rules of a fabrication plan as data (`data/shop_rules.json`,
//! format `vesselcad-shop/1`, or a user file of the same format): which
//! operations each kind of item gets, the precedence rules between operations,
//! the weld preparations that give weld-metal volumes, and when post-weld heat
//! treatment is required. Loading checks every name a rule uses, so a plan is
//! never built on a rule that names an operation, relation or preparation that
//! does not exist; each problem is a [`PlanError::Rule`] naming the file, the
//! JSON path, the value and the rule.

use std::collections::BTreeSet;
use std::path::Path;

use serde::{Deserialize, Serialize};

use super::plan_error::PlanError;
use super::shop::Shop;

/// The format tag of a shop-rules file.
pub const SHOP_RULES_FORMAT: &str = "vesselcad-shop/1";

/// The built-in rules' text.
const BUILTIN: &str = super::shop::BUILTIN_RULES;

/// Kinds of item the plan makes operations for.
pub const ITEM_KINDS: [&str; 9] = [
    "course",
    "cone",
    "head",
    "skirt",
    "circ_joint",
    "nozzle",
    "boot",
    "pad",
    "support",
];

/// The whole vessel (hydrotest, PWHT, coating).
pub const VESSEL_ITEM: &str = "vessel";

/// One operation kind.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct OperationRule {
    /// Stable id, e.g. `roll`.
    pub id: String,
    /// Name on the traveler.
    pub name: String,
    /// Kinds of item it applies to ([`ITEM_KINDS`] or `vessel`).
    pub items: Vec<String>,
    /// Machine or method.
    pub method: String,
    /// A condition: `pwht_required` (the only one).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub when: Option<String>,
}

/// How the item of a predecessor relates to the item of its successor.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Relation {
    /// The same item.
    Same,
    /// One of the two parts a circumferential joint joins.
    Joined,
    /// The part the item is mounted on (a nozzle's, boot's or support's host).
    Host,
    /// A circumferential joint of the item's host.
    HostJoints,
    /// The nozzle a pad belongs to.
    Nozzle,
    /// Any item of the vessel.
    Any,
}

/// One precedence rule: every operation of a kind in `before` on a related
/// item comes before the operation `after`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PrecedenceRule {
    /// Predecessor operation kinds.
    pub before: Vec<String>,
    /// Successor operation kind.
    pub after: String,
    /// Which items' predecessors count.
    pub relation: Relation,
}

/// The cross-section of a weld preparation.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum PrepKind {
    /// Double-V butt, symmetric.
    DoubleV,
    /// Single-V butt.
    SingleV,
    /// Single bevel (set-in branch) with a cover fillet.
    SingleBevel,
    /// Fillet.
    Fillet,
}

/// One weld preparation (see [`super::weld_prep`] for its cross-section area).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Prep {
    /// Stable id, e.g. `DV60`.
    pub id: String,
    /// Joint type as the weld map prints it.
    pub joint: String,
    /// Cross-section.
    pub kind: PrepKind,
    /// Included angle, degrees (a bevel's angle for `single_bevel`).
    #[serde(default)]
    pub included_angle: f64,
    /// Root gap, mm.
    #[serde(default)]
    pub root_gap: f64,
    /// Root face, mm.
    #[serde(default)]
    pub root_face: f64,
    /// Leg of the cover fillet of a `single_bevel`, mm.
    #[serde(default)]
    pub cover_fillet: f64,
    /// Fillet throat over the thinner part's thickness.
    #[serde(default)]
    pub throat_ratio: f64,
    /// Where it is used.
    #[serde(default)]
    pub note: String,
}

/// The preparation of one weld family by thickness.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PrepChoice {
    /// Below `thick_from`.
    pub thin: String,
    /// From `thick_from`.
    pub thick: String,
    /// Thickness from which `thick` applies, mm.
    pub thick_from: f64,
}

/// Preparations per weld family.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PrepFor {
    /// Longitudinal seams.
    pub long_seam: PrepChoice,
    /// Circumferential seams.
    pub circ_seam: PrepChoice,
    /// Nozzle and boot to shell or head.
    pub nozzle: PrepChoice,
    /// Flange to neck.
    pub flange: PrepChoice,
    /// Pads and supports.
    pub attachment: PrepChoice,
}

/// When a material group needs post-weld heat treatment.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PwhtRule {
    /// Group name, e.g. `P-No. 1 carbon steel`.
    pub group: String,
    /// Material specifications in the group.
    pub materials: Vec<String>,
    /// Whether a vessel without a material (or with one no group lists) falls
    /// in this group.
    #[serde(default)]
    pub default: bool,
    /// Nominal thickness above which PWHT is required, mm; `None`: never.
    pub required_above: Option<f64>,
    /// The code rule, as the traveler cites it.
    pub rule: String,
}

/// A shop-rules file.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ShopRules {
    /// [`SHOP_RULES_FORMAT`].
    pub format: String,
    /// Free text.
    #[serde(default)]
    pub note: String,
    /// Plate sizes, seam rules and stock sheets of the flat patterns; a
    /// file's `plates` may leave out any field (the built-in value stands).
    #[serde(default = "Shop::default", deserialize_with = "plates_over_builtin")]
    pub plates: Shop,
    /// Operation kinds, in traveler order.
    pub operations: Vec<OperationRule>,
    /// Precedence rules.
    pub precedence: Vec<PrecedenceRule>,
    /// Weld preparations.
    pub preps: Vec<Prep>,
    /// Which preparation each weld family takes.
    pub prep_for: PrepFor,
    /// PWHT by material group.
    pub pwht: Vec<PwhtRule>,
}

/// A rules file's `plates`: the fields it gives over the built-in shop data.
fn plates_over_builtin<'de, D: serde::Deserializer<'de>>(d: D) -> Result<Shop, D::Error> {
    let value = serde_json::Value::deserialize(d)?;
    Shop::from_json("plates", &value.to_string(), Some(Shop::default()))
        .map_err(serde::de::Error::custom)
}

impl ShopRules {
    /// The built-in rules (`data/shop_rules.json`).
    pub fn builtin() -> ShopRules {
        ShopRules::from_json("data/shop_rules.json", BUILTIN)
            .unwrap_or_else(|e| panic!("the built-in shop rules are valid: {e}"))
    }

    /// Reads and checks a rules file.
    ///
    /// # Errors
    ///
    /// [`PlanError::Io`] when it cannot be read; as [`ShopRules::from_json`].
    pub fn from_path(path: &Path) -> Result<ShopRules, PlanError> {
        let text = std::fs::read_to_string(path).map_err(|e| PlanError::Io {
            path: path.display().to_string(),
            message: e.to_string(),
        })?;
        ShopRules::from_json(&path.display().to_string(), &text)
    }

    /// Parses and checks rules from `text` (`file` names it in errors).
    ///
    /// # Errors
    ///
    /// [`PlanError::Rule`] naming the JSON path of a value that does not parse,
    /// or of a name no operation, preparation or item kind has.
    pub fn from_json(file: &str, text: &str) -> Result<ShopRules, PlanError> {
        let de = &mut serde_json::Deserializer::from_str(text);
        let rules: ShopRules = serde_path_to_error::deserialize(de)
            .map_err(|e| PlanError::rule(file, e.path().to_string(), "", e.inner().to_string()))?;
        rules.check(file)?;
        Ok(rules)
    }

    /// The operation kind `id`.
    pub fn operation(&self, id: &str) -> Option<&OperationRule> {
        self.operations.iter().find(|o| o.id == id)
    }

    /// The preparation `id`.
    pub fn prep(&self, id: &str) -> Option<&Prep> {
        self.preps.iter().find(|p| p.id == id)
    }

    /// Every name used is defined.
    fn check(&self, file: &str) -> Result<(), PlanError> {
        let bad = |path: String, value: &str, rule: &str| {
            Err(PlanError::rule(file, path, value, rule.to_string()))
        };
        if self.format != SHOP_RULES_FORMAT {
            return bad(
                "format".into(),
                &self.format,
                "must be \"vesselcad-shop/1\"",
            );
        }
        let mut ids = BTreeSet::new();
        for (i, op) in self.operations.iter().enumerate() {
            if !ids.insert(op.id.as_str()) {
                return bad(
                    format!("operations[{i}].id"),
                    &op.id,
                    "operation ids must be unique",
                );
            }
            for (j, item) in op.items.iter().enumerate() {
                if !ITEM_KINDS.contains(&item.as_str()) && item != VESSEL_ITEM {
                    return bad(
                        format!("operations[{i}].items[{j}]"),
                        item,
                        "must be an item kind: course, cone, head, skirt, circ_joint, nozzle, boot, pad, support or vessel",
                    );
                }
            }
            if let Some(w) = &op.when
                && w != "pwht_required"
            {
                return bad(
                    format!("operations[{i}].when"),
                    w,
                    "the only condition is \"pwht_required\"",
                );
            }
        }
        for (i, rule) in self.precedence.iter().enumerate() {
            if !ids.contains(rule.after.as_str()) {
                return bad(
                    format!("precedence[{i}].after"),
                    &rule.after,
                    "must be the id of an operation",
                );
            }
            for (j, b) in rule.before.iter().enumerate() {
                if !ids.contains(b.as_str()) {
                    return bad(
                        format!("precedence[{i}].before[{j}]"),
                        b,
                        "must be the id of an operation",
                    );
                }
            }
        }
        let preps: BTreeSet<&str> = self.preps.iter().map(|p| p.id.as_str()).collect();
        for (i, p) in self.preps.iter().enumerate() {
            let finite = [
                ("included_angle", p.included_angle, 0.0, 120.0),
                ("root_gap", p.root_gap, 0.0, 50.0),
                ("root_face", p.root_face, 0.0, 50.0),
                ("cover_fillet", p.cover_fillet, 0.0, 50.0),
                ("throat_ratio", p.throat_ratio, 0.0, 2.0),
            ];
            for (field, v, lo, hi) in finite {
                if !(v.is_finite() && (lo..=hi).contains(&v)) {
                    return bad(
                        format!("preps[{i}].{field}"),
                        &v.to_string(),
                        &format!("must be a number from {lo} to {hi}"),
                    );
                }
            }
        }
        let choices = [
            ("long_seam", &self.prep_for.long_seam),
            ("circ_seam", &self.prep_for.circ_seam),
            ("nozzle", &self.prep_for.nozzle),
            ("flange", &self.prep_for.flange),
            ("attachment", &self.prep_for.attachment),
        ];
        for (family, c) in choices {
            for (field, id) in [("thin", &c.thin), ("thick", &c.thick)] {
                if !preps.contains(id.as_str()) {
                    return bad(
                        format!("prep_for.{family}.{field}"),
                        id,
                        "must be the id of a preparation in preps",
                    );
                }
            }
        }
        for (i, p) in self.pwht.iter().enumerate() {
            if let Some(t) = p.required_above
                && !(t.is_finite() && t >= 0.0)
            {
                return bad(
                    format!("pwht[{i}].required_above"),
                    &t.to_string(),
                    "must be a thickness ≥ 0 mm or null",
                );
            }
        }
        Ok(())
    }

    /// The PWHT group of a material (by name, case and spacing ignored; the
    /// default group when none lists it).
    pub fn pwht_group(&self, material: Option<&str>) -> Option<&PwhtRule> {
        let norm = |s: &str| {
            s.chars()
                .filter(|c| c.is_ascii_alphanumeric())
                .collect::<String>()
                .to_ascii_uppercase()
        };
        material
            .and_then(|m| {
                let m = norm(m);
                self.pwht
                    .iter()
                    .find(|g| g.materials.iter().any(|x| norm(x) == m))
            })
            .or_else(|| self.pwht.iter().find(|g| g.default))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn builtin_rules_load() {
        let r = ShopRules::builtin();
        assert!(r.operation("roll").is_some());
        assert_eq!(
            r.pwht_group(Some("sa 516-70")).map(|g| g.required_above),
            Some(Some(38.0))
        );
        assert_eq!(
            r.pwht_group(Some("SA-240-316L")).map(|g| g.required_above),
            Some(None)
        );
    }

    #[test]
    fn an_unknown_operation_in_a_rule_is_named() {
        let text = BUILTIN.replace(
            "{ \"before\": [\"hydrotest\"], \"after\": \"coat\"",
            "{ \"before\": [\"hydrotset\"], \"after\": \"coat\"",
        );
        let e = ShopRules::from_json("mine.json", &text)
            .unwrap_err()
            .to_string();
        assert!(e.contains("mine.json"), "{e}");
        assert!(e.contains("precedence[16].before[0]"), "{e}");
        assert!(e.contains("hydrotset"), "{e}");
    }
}
