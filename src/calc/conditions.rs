//! A vessel's design conditions as the calculations take them: the design file's
//! kPa(g), °C, mm and material name turned into MPa, the allowable stress at the
//! design temperature and at the test temperature, the joint efficiency and the
//! code the vessel is calculated to. Anything missing or out of a formula's reach
//! is a sentence naming the field, not a panic.

use serde::Serialize;

use super::MaterialTable;
use crate::design::{DesignConditions, VesselKind};

/// Joint efficiency when the design gives none: spot radiography (UW-12 Table
/// UW-12, Type 1 joint, column (b)).
pub const DEFAULT_JOINT_EFFICIENCY: f64 = 0.85;

/// Metal temperature of the hydrostatic test, °C (the stress ratio of UG-99(b)
/// takes the allowable stress there).
pub const TEST_TEMPERATURE: f64 = 20.0;

/// The code a vessel of `kind` is calculated to.
pub fn code_of(kind: VesselKind) -> &'static str {
    match kind {
        VesselKind::Tank => "API 650",
        _ => "ASME VIII-1",
    }
}

/// Design conditions in calculation units.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Conditions {
    /// Design pressure at the top, MPa gauge.
    pub pressure: f64,
    /// Design temperature, °C.
    pub temperature: f64,
    /// Corrosion allowance, mm.
    pub corrosion_allowance: f64,
    /// Joint efficiency E.
    pub joint_efficiency: f64,
    /// Whether E is the default rather than the design's.
    pub joint_efficiency_default: bool,
    /// Material specification as the table names it.
    pub material: String,
    /// Allowable stress at the design temperature, MPa.
    pub stress: f64,
    /// Allowable stress at [`TEST_TEMPERATURE`], MPa.
    pub stress_test: f64,
    /// Where the allowable stress comes from.
    pub stress_source: String,
}

/// The calculation inputs of a vessel's design conditions, or the sentence saying
/// why the vessel cannot be calculated (a missing field, a material not in the
/// table, a temperature outside its stress table, a code not implemented yet).
pub fn conditions(
    design: &DesignConditions,
    kind: VesselKind,
    table: &MaterialTable,
) -> Result<Conditions, String> {
    if kind == VesselKind::Tank {
        return Err(
            "storage tank: API 650 (one-foot method) is not computed yet; ASME VIII-1 does not \
             apply"
                .into(),
        );
    }
    let pressure = design
        .pressure
        .ok_or("design.pressure: not given; no pressure calculation")?;
    if pressure <= 0.0 {
        return Err(format!(
            "design.pressure: {pressure} kPa(g) is not an internal pressure; external \
             pressure (UG-28) is not computed yet"
        ));
    }
    let temperature = design
        .temperature
        .ok_or("design.temperature: not given; the allowable stress needs it")?;
    let name = design
        .material
        .as_deref()
        .ok_or("design.material: not given; the allowable stress needs it")?;
    let material = table
        .get(name)
        .map_err(|e| format!("design.material: {e}"))?;
    let stress = material
        .allowable_stress(temperature)
        .map_err(|e| format!("design.temperature: {e}"))?;
    let stress_test = material
        .allowable_stress(TEST_TEMPERATURE)
        .map_err(|e| format!("hydrotest temperature: {e}"))?;
    Ok(Conditions {
        pressure: pressure * 1e-3,
        temperature,
        corrosion_allowance: design.corrosion_allowance.unwrap_or(0.0),
        joint_efficiency: design.joint_efficiency.unwrap_or(DEFAULT_JOINT_EFFICIENCY),
        joint_efficiency_default: design.joint_efficiency.is_none(),
        material: material.name.clone(),
        stress,
        stress_test,
        stress_source: material.allowable_stress.source.clone(),
    })
}
