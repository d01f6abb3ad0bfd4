//! Vessel-level figures: static head of the liquid, the vessel's MAWP (the least
//! over its parts of the part's MAWP less the static head on it, i.e. referred to
//! the top), the UG-99(b) hydrostatic test pressure, and the UG-16(b) minimum
//! thickness.

use super::error::{non_negative, positive};
use super::{CalcError, Formula};

/// Standard gravity, m/s².
pub const GRAVITY: f64 = 9.806_65;

/// UG-16(b) minimum thickness of shells and heads, 1/16 in, taken as 1.5 mm (the
/// code's SI value), corrosion allowance excluded.
pub const UG16_MINIMUM: f64 = 1.5;

/// Pressure of a liquid column of `density` kg/m³ and `height` mm, MPa.
pub fn static_head(density: f64, height: f64) -> Result<f64, CalcError> {
    non_negative("liquid", "density", density)?;
    non_negative("liquid", "height", height)?;
    Ok(density * GRAVITY * height * 1e-3 * 1e-6)
}

/// A part's MAWP at its own elevation and the static head on it.
#[derive(Clone, Debug, PartialEq)]
pub struct PartPressure {
    /// The part's id, e.g. `V-101/S1`.
    pub id: String,
    /// The part's MAWP, hot and corroded, MPa.
    pub mawp: f64,
    /// Static head of the liquid on the part's lowest point, MPa.
    pub static_head: f64,
}

/// The vessel's MAWP at its top: the least of each part's MAWP less its static
/// head (UG-98), with the id of the governing part.
pub fn vessel_mawp(parts: &[PartPressure]) -> Result<(f64, String), CalcError> {
    let mut best: Option<(f64, &str)> = None;
    for p in parts {
        positive(&p.id, "mawp", p.mawp)?;
        non_negative(&p.id, "static_head", p.static_head)?;
        let at_top = p.mawp - p.static_head;
        if best.is_none_or(|(b, _)| at_top < b) {
            best = Some((at_top, &p.id));
        }
    }
    match best {
        Some((v, id)) => Ok((v, id.to_string())),
        None => Err(CalcError::Input {
            entity: "vessel".into(),
            field: "parts".into(),
            value: 0.0,
            rule: "a vessel MAWP needs at least one pressure part".into(),
        }),
    }
}

/// UG-99(b) hydrostatic test pressure at the top: 1.3 × MAWP × the lowest ratio
/// of the allowable stress at test temperature to that at design temperature,
/// over the pressure parts' materials (`ratios` as `(S_test, S_design)` pairs).
pub fn hydrotest_pressure(mawp: f64, ratios: &[(f64, f64)]) -> Result<Formula, CalcError> {
    positive("vessel", "mawp", mawp)?;
    let mut lowest = f64::INFINITY;
    for &(test, design) in ratios {
        positive("vessel", "stress_at_test_temperature", test)?;
        positive("vessel", "stress_at_design_temperature", design)?;
        lowest = lowest.min(test / design);
    }
    if !lowest.is_finite() {
        lowest = 1.0;
    }
    Ok(Formula {
        value: 1.3 * mawp * lowest,
        paragraph: "UG-99(b)",
        formula: "P_test = 1.3 · MAWP · (S_test / S_design), lowest ratio",
    })
}

/// UG-16(b): the least thickness a shell or head may have, 1.5 mm plus the
/// corrosion allowance.
pub fn minimum_thickness(corrosion_allowance: f64) -> Result<Formula, CalcError> {
    non_negative("part", "corrosion_allowance", corrosion_allowance)?;
    Ok(Formula {
        value: UG16_MINIMUM + corrosion_allowance,
        paragraph: "UG-16(b)",
        formula: "t_min = 1.5 mm (1/16 in) + corrosion allowance",
    })
}
