//! The materials table: density, allowable stress at temperature, yield, modulus
//! and ASME B16.5 material group of each specification, every value with its source.
//!
//! The built-in table (`data/materials.json`, embedded at compile time) holds ASTM
//! specified minimums and allowable stresses at temperature derived from them by
//! the published ASME II-D rule (Mandatory Appendix 1, with the public Tables Y-1
//! and U trend ratios) below the creep range, and Table 1A values as publicly
//! reproduced where the rule cannot reach, because Section II-D's own tables are
//! licensed; each table says where and why it stops (`limit`). A user points at
//! a licensed table in the same format with [`MaterialTable::from_path`]. Allowable
//! stress is interpolated linearly in temperature between the table's points and is
//! an error outside them: a calculation never extrapolates a stress.

use std::path::Path;

use serde::Deserialize;

use super::CalcError;

/// The built-in table's text, `data/materials.json`.
pub const BUILTIN_JSON: &str = include_str!("../../data/materials.json");

/// The format tag a materials file must carry.
pub const FORMAT: &str = "vesselcad-materials/1";

/// One value with the sentence saying where it comes from.
#[derive(Clone, Debug, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Sourced<T> {
    /// The value (SI: MPa, kg/m³, or a label).
    pub value: T,
    /// Where the value comes from, or by which rule it was derived.
    pub source: String,
}

/// Allowable stress S against temperature, with its source.
#[derive(Clone, Debug, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct StressTable {
    /// `[temperature °C, S MPa]`, temperatures strictly increasing.
    pub points: Vec<[f64; 2]>,
    /// Where the values come from.
    pub source: String,
    /// Why the table stops where it does (the Code's temperature limit of the
    /// material, or the end of the range a derivation is valid in); an error
    /// above the table's last point quotes it.
    #[serde(default)]
    pub limit: Option<String>,
}

/// One material specification.
#[derive(Clone, Debug, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Material {
    /// Specification name, e.g. `SA-516-70`.
    pub name: String,
    /// Other spellings that name the same material, e.g. `A516-70`.
    #[serde(default)]
    pub aliases: Vec<String>,
    /// Specified minimum tensile strength, MPa.
    pub tensile_strength: Sourced<f64>,
    /// Specified minimum yield strength, MPa.
    pub yield_strength: Sourced<f64>,
    /// Density, kg/m³.
    pub density: Sourced<f64>,
    /// Modulus of elasticity at room temperature, MPa.
    pub modulus: Sourced<f64>,
    /// ASME B16.5 material group (e.g. `1.1`), when the specification has one.
    #[serde(default)]
    pub b16_5_group: Option<Sourced<String>>,
    /// ASME VIII-1 Fig. UCS-66 impact-test exemption curve (`A`–`D`) of a Part
    /// UCS material; none for materials outside Part UCS.
    #[serde(default)]
    pub ucs66_curve: Option<Sourced<String>>,
    /// API 650 Table 4.4a material group (`I`, `II`, `III`, `IIIA`, `IV`, `IVA`,
    /// `V`, `VI`) of a tank plate material; it decides whether a tank's bottom
    /// needs annular plates (5.5.1).
    #[serde(default)]
    pub api650_group: Option<Sourced<String>>,
    /// Allowable stress S at temperature, MPa.
    pub allowable_stress: StressTable,
}

impl Material {
    /// The allowable stress S at `temperature` °C, MPa, interpolated linearly
    /// between the table's points; an error outside the table's range.
    pub fn allowable_stress(&self, temperature: f64) -> Result<f64, CalcError> {
        let points = &self.allowable_stress.points;
        let (Some(first), Some(last)) = (points.first(), points.last()) else {
            return Err(self.out_of_range(temperature));
        };
        if !temperature.is_finite() || temperature < first[0] || temperature > last[0] {
            return Err(self.out_of_range(temperature));
        }
        for pair in points.windows(2) {
            let ([t0, s0], [t1, s1]) = (pair[0], pair[1]);
            if temperature <= t1 {
                let f = (temperature - t0) / (t1 - t0);
                return Ok(s0 + f * (s1 - s0));
            }
        }
        Ok(first[1])
    }

    fn out_of_range(&self, temperature: f64) -> CalcError {
        let points = &self.allowable_stress.points;
        let range = match (points.first(), points.last()) {
            (Some(a), Some(b)) => format!("{} to {} °C", a[0], b[0]),
            _ => "no points".to_string(),
        };
        let above = points.last().is_some_and(|p| temperature > p[0]);
        let rule = match &self.allowable_stress.limit {
            Some(limit) if above => format!(
                "the allowable stress table of {} covers {range}: {limit}",
                self.name
            ),
            _ => format!(
                "the allowable stress table of {} covers {range}; give a licensed table with the \
                 temperature (see MaterialTable::from_path)",
                self.name
            ),
        };
        CalcError::Input {
            entity: self.name.clone(),
            field: "temperature".into(),
            value: temperature,
            rule,
        }
    }

    /// True when `name` is this material's name or one of its aliases, ignoring
    /// case, spaces, hyphens and the `S` prefix of ASME specifications.
    pub fn is_named(&self, name: &str) -> bool {
        let key = normalise(name);
        std::iter::once(&self.name)
            .chain(&self.aliases)
            .any(|n| normalise(n) == key)
    }
}

fn normalise(name: &str) -> String {
    let flat: String = name
        .chars()
        .filter(|c| c.is_ascii_alphanumeric())
        .map(|c| c.to_ascii_uppercase())
        .collect();
    match flat.strip_prefix('S') {
        Some(rest) if rest.starts_with('A') => rest.to_string(),
        _ => flat,
    }
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct TableFile {
    format: String,
    #[serde(default)]
    #[expect(dead_code, reason = "a free-text note for the table's reader")]
    note: Option<String>,
    materials: Vec<Material>,
}

/// A set of materials looked up by name.
#[derive(Clone, Debug, PartialEq)]
pub struct MaterialTable {
    /// The materials, in the file's order.
    pub materials: Vec<Material>,
}

impl MaterialTable {
    /// The built-in table (`data/materials.json`).
    pub fn builtin() -> MaterialTable {
        match MaterialTable::from_json("data/materials.json", BUILTIN_JSON) {
            Ok(table) => table,
            Err(e) => unreachable!("the built-in materials table is checked by tests: {e}"),
        }
    }

    /// A user's table read from `path`, in the built-in table's format.
    pub fn from_path(path: &Path) -> Result<MaterialTable, CalcError> {
        let text = std::fs::read_to_string(path).map_err(|e| CalcError::Table {
            path: path.display().to_string(),
            message: e.to_string(),
        })?;
        MaterialTable::from_json(&path.display().to_string(), &text)
    }

    /// A table parsed from JSON text; `path` names it in errors.
    pub fn from_json(path: &str, text: &str) -> Result<MaterialTable, CalcError> {
        let err = |message: String| CalcError::Table {
            path: path.to_string(),
            message,
        };
        let de = &mut serde_json::Deserializer::from_str(text);
        let file: TableFile = serde_path_to_error::deserialize(de)
            .map_err(|e| err(format!("{}: {}", e.path(), e.inner())))?;
        if file.format != FORMAT {
            return Err(err(format!(
                "format: expected \"{FORMAT}\", got \"{}\"",
                file.format
            )));
        }
        for (i, m) in file.materials.iter().enumerate() {
            let at = format!("materials[{i}] ({})", m.name);
            let pts = &m.allowable_stress.points;
            if pts.is_empty() {
                return Err(err(format!(
                    "{at}.allowable_stress.points: at least one point"
                )));
            }
            for (j, p) in pts.iter().enumerate() {
                if !(p[0].is_finite() && p[1].is_finite() && p[1] > 0.0) {
                    return Err(err(format!(
                        "{at}.allowable_stress.points[{j}]: {p:?} must be finite with S > 0"
                    )));
                }
                if j > 0 && p[0] <= pts[j - 1][0] {
                    return Err(err(format!(
                        "{at}.allowable_stress.points[{j}]: temperature {} must exceed the previous {}",
                        p[0],
                        pts[j - 1][0]
                    )));
                }
            }
            for (field, v) in [
                ("tensile_strength", m.tensile_strength.value),
                ("yield_strength", m.yield_strength.value),
                ("density", m.density.value),
                ("modulus", m.modulus.value),
            ] {
                if !(v.is_finite() && v > 0.0) {
                    return Err(err(format!("{at}.{field}: {v} must be finite and > 0")));
                }
            }
        }
        Ok(MaterialTable {
            materials: file.materials,
        })
    }

    /// The material called `name` (or one of its aliases); an error naming the
    /// known materials otherwise.
    pub fn get(&self, name: &str) -> Result<&Material, CalcError> {
        self.materials
            .iter()
            .find(|m| m.is_named(name))
            .ok_or_else(|| CalcError::UnknownMaterial {
                name: name.to_string(),
                known: self
                    .materials
                    .iter()
                    .map(|m| m.name.as_str())
                    .collect::<Vec<_>>()
                    .join(", "),
            })
    }
}
