//! Shop data: the limits and allowances of the fabricator that the flat
//! patterns, seams and nesting follow. They are the `plates` object of the
//! shop rules (`data/shop_rules.json`, embedded at compile time; see
//! [`super::shop_rules`]); a user rules file may leave out any field, and a
//! file given with `--shop` (the same object alone) replaces any of them.
//! Every value is checked: a bad one is a [`FabError::Shop`] naming the file,
//! the field, the value and the rule.

use std::path::Path;
use std::sync::LazyLock;

use serde::{Deserialize, Serialize};

use super::error::FabError;

/// The built-in shop rules' text (`data/shop_rules.json`), whose `plates`
/// are the built-in shop data.
pub(super) const BUILTIN_RULES: &str = include_str!("../../data/shop_rules.json");

/// Where the built-in shop data is, as errors name it.
pub const BUILTIN_NAME: &str = "data/shop_rules.json plates";

/// The built-in shop data: the `plates` object of the built-in rules.
fn builtin_json() -> String {
    let rules: serde_json::Value =
        serde_json::from_str(BUILTIN_RULES).expect("the built-in shop rules are JSON (tested)");
    rules["plates"].to_string()
}

/// How a nozzle neck is attached to its host, which sets the opening's size.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Attachment {
    /// The neck passes through the host: the hole is the neck's outside
    /// diameter plus the bevel allowance on the radius.
    SetIn,
    /// The neck sits on the host: the hole is the neck's bore.
    SetOn,
}

/// The fabricator's limits and allowances, mm.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Shop {
    /// Largest plate width: the axial height of a rolled course, mm.
    pub max_plate_width: f64,
    /// Largest plate length: the developed arc of one plate of a course, mm.
    pub max_plate_length: f64,
    /// Smallest stagger of longitudinal seams of adjacent courses, mm; the rule
    /// is at least max(5·t, this).
    pub min_stagger: f64,
    /// Clearance of seams from openings and pads, mm; `null`: max(50, 2.5·t).
    pub clearance: Option<f64>,
    /// Radial gap added to a set-in opening for the weld bevel, mm.
    pub bevel_allowance: f64,
    /// How necks are attached.
    pub attachment: Attachment,
    /// Stock sheet width, mm.
    pub sheet_width: f64,
    /// Stock sheet length, mm.
    pub sheet_length: f64,
    /// Gap kept between nested pieces and from the sheet edge, mm.
    pub nest_gap: f64,
    /// Largest distance between a developed curve and the polyline that cuts
    /// it, mm.
    pub chord_tolerance: f64,
}

/// A partial shop file: the fields it sets.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct ShopPatch {
    max_plate_width: Option<f64>,
    max_plate_length: Option<f64>,
    min_stagger: Option<f64>,
    #[serde(default, deserialize_with = "some_option")]
    clearance: Option<Option<f64>>,
    bevel_allowance: Option<f64>,
    attachment: Option<Attachment>,
    sheet_width: Option<f64>,
    sheet_length: Option<f64>,
    nest_gap: Option<f64>,
    chord_tolerance: Option<f64>,
}

/// Tells a field given as `null` (`Some(None)`) from a missing one (`None`).
fn some_option<'de, D: serde::Deserializer<'de>>(d: D) -> Result<Option<Option<f64>>, D::Error> {
    Option::<f64>::deserialize(d).map(Some)
}

/// The built-in shop data, parsed once.
static BUILTIN: LazyLock<Shop> = LazyLock::new(|| {
    Shop::from_json(BUILTIN_NAME, &builtin_json(), None)
        .expect("the built-in shop data is valid (tested)")
});

impl Default for Shop {
    fn default() -> Self {
        BUILTIN.clone()
    }
}

impl Shop {
    /// Radius of the cutting cylinder of a neck of outside diameter `od` and
    /// wall `wall`: the neck's outside plus the bevel allowance (set-in) or
    /// its bore (set-on), mm.
    pub fn cut_radius(&self, od: f64, wall: f64) -> f64 {
        match self.attachment {
            Attachment::SetIn => 0.5 * od + self.bevel_allowance,
            Attachment::SetOn => 0.5 * od - wall,
        }
    }

    /// The clearance of seams from openings and pads on a plate `thickness`
    /// mm thick.
    pub fn clearance_for(&self, thickness: f64) -> f64 {
        self.clearance.unwrap_or((2.5 * thickness).max(50.0))
    }

    /// The smallest stagger of longitudinal seams between courses of which the
    /// thicker is `thickness` mm.
    pub fn stagger_for(&self, thickness: f64) -> f64 {
        (5.0 * thickness).max(self.min_stagger)
    }

    /// Reads a shop file over the built-in defaults.
    ///
    /// # Errors
    ///
    /// [`FabError::Io`] when the file cannot be read, [`FabError::Shop`] for
    /// bad JSON, an unknown field or a value out of range.
    pub fn load(path: &Path) -> Result<Shop, FabError> {
        Shop::load_over(path, Shop::default())
    }

    /// Reads a shop file over `base`: the fields it leaves out keep `base`'s
    /// values.
    ///
    /// # Errors
    ///
    /// As [`Shop::load`].
    pub fn load_over(path: &Path, base: Shop) -> Result<Shop, FabError> {
        let text = std::fs::read_to_string(path).map_err(|source| FabError::Io {
            path: path.to_path_buf(),
            source,
        })?;
        Shop::from_json(&path.display().to_string(), &text, Some(base))
    }

    /// Parses shop data named `name` from `text`, over `base`: a field the
    /// text leaves out keeps `base`'s value (with no base every field is
    /// required).
    ///
    /// # Errors
    ///
    /// [`FabError::Shop`] for bad JSON, an unknown or missing field or a value
    /// out of range.
    pub fn from_json(name: &str, text: &str, base: Option<Shop>) -> Result<Shop, FabError> {
        let bad = |field: &str, value: String, rule: &str| FabError::Shop {
            file: name.to_string(),
            field: field.to_string(),
            value,
            rule: rule.to_string(),
        };
        let patch: ShopPatch = serde_json::from_str(text)
            .map_err(|e| bad("(file)", String::new(), &format!("not shop data: {e}")))?;
        let pick = |field: &str, given: Option<f64>, base: Option<f64>| {
            given
                .or(base)
                .ok_or_else(|| bad(field, "missing".into(), "required"))
        };
        let b = base.as_ref();
        let shop = Shop {
            max_plate_width: pick(
                "max_plate_width",
                patch.max_plate_width,
                b.map(|s| s.max_plate_width),
            )?,
            max_plate_length: pick(
                "max_plate_length",
                patch.max_plate_length,
                b.map(|s| s.max_plate_length),
            )?,
            min_stagger: pick("min_stagger", patch.min_stagger, b.map(|s| s.min_stagger))?,
            clearance: match patch.clearance {
                Some(c) => c,
                None => b.and_then(|s| s.clearance),
            },
            bevel_allowance: pick(
                "bevel_allowance",
                patch.bevel_allowance,
                b.map(|s| s.bevel_allowance),
            )?,
            attachment: patch
                .attachment
                .or(b.map(|s| s.attachment))
                .ok_or_else(|| bad("attachment", "missing".into(), "required"))?,
            sheet_width: pick("sheet_width", patch.sheet_width, b.map(|s| s.sheet_width))?,
            sheet_length: pick(
                "sheet_length",
                patch.sheet_length,
                b.map(|s| s.sheet_length),
            )?,
            nest_gap: pick("nest_gap", patch.nest_gap, b.map(|s| s.nest_gap))?,
            chord_tolerance: pick(
                "chord_tolerance",
                patch.chord_tolerance,
                b.map(|s| s.chord_tolerance),
            )?,
        };
        shop.check(name)?;
        Ok(shop)
    }

    /// Checks every value's range.
    fn check(&self, name: &str) -> Result<(), FabError> {
        let bad = |field: &str, value: f64, rule: &str| FabError::Shop {
            file: name.to_string(),
            field: field.to_string(),
            value: value.to_string(),
            rule: rule.to_string(),
        };
        let plates = [
            ("max_plate_width", self.max_plate_width),
            ("max_plate_length", self.max_plate_length),
            ("sheet_width", self.sheet_width),
            ("sheet_length", self.sheet_length),
        ];
        for (field, value) in plates {
            if !(value.is_finite() && (100.0..=1e5).contains(&value)) {
                return Err(bad(field, value, "a plate size in [100, 10^5] mm"));
            }
        }
        if !(self.chord_tolerance.is_finite() && self.chord_tolerance > 0.0) {
            return Err(bad(
                "chord_tolerance",
                self.chord_tolerance,
                "a length in (0, 1] mm",
            ));
        }
        let mut non_negative = vec![
            ("min_stagger", self.min_stagger),
            ("bevel_allowance", self.bevel_allowance),
            ("nest_gap", self.nest_gap),
        ];
        if let Some(c) = self.clearance {
            non_negative.push(("clearance", c));
        }
        for (field, value) in non_negative {
            if !(value.is_finite() && (0.0..=1e5).contains(&value)) {
                return Err(bad(field, value, "a length in [0, 10^5] mm"));
            }
        }
        if self.chord_tolerance > 1.0 {
            return Err(bad(
                "chord_tolerance",
                self.chord_tolerance,
                "at most 1 mm (a cutting file)",
            ));
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn builtin_is_valid_and_user_file_overrides_fields() {
        let shop = Shop::default();
        assert_eq!(shop.attachment, Attachment::SetIn);
        assert_eq!(shop.clearance_for(12.0), 50.0);
        assert_eq!(shop.clearance_for(30.0), 75.0);
        let user = Shop::from_json(
            "u.json",
            r#"{"max_plate_width": 2000, "clearance": 80}"#,
            Some(shop.clone()),
        )
        .unwrap();
        assert_eq!(user.max_plate_width, 2000.0);
        assert_eq!(user.clearance_for(12.0), 80.0);
        assert_eq!(user.max_plate_length, shop.max_plate_length);
    }

    #[test]
    fn bad_values_name_file_field_value_and_rule() {
        let e = Shop::from_json("u.json", r#"{"sheet_width": -5}"#, Some(Shop::default()))
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("u.json") && e.contains("sheet_width") && e.contains("-5"),
            "{e}"
        );
        let e = Shop::from_json("u.json", r#"{"plate": 5}"#, Some(Shop::default()))
            .unwrap_err()
            .to_string();
        assert!(e.contains("u.json") && e.contains("plate"), "{e}");
    }
}
