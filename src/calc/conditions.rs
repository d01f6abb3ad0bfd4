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
    /// Design pressure at the top, MPa gauge; 0 for a vessel designed for
    /// vacuum or external pressure only ([`Conditions::vacuum_only`]).
    pub pressure: f64,
    /// Design temperature, °C.
    pub temperature: f64,
    /// Corrosion allowance, mm.
    pub corrosion_allowance: f64,
    /// Joint efficiency E.
    pub joint_efficiency: f64,
    /// Whether E is the default rather than the design's.
    pub joint_efficiency_default: bool,
    /// The code the figures follow: `ASME VIII-1` or `API 650` (then `stress` is
    /// the product design stress Sd and `stress_test` the hydrostatic test stress St).
    pub code: &'static str,
    /// Material specification as the table names it.
    pub material: String,
    /// Allowable stress at the design temperature, MPa.
    pub stress: f64,
    /// Allowable stress at [`TEST_TEMPERATURE`], MPa.
    pub stress_test: f64,
    /// Where the allowable stress comes from.
    pub stress_source: String,
    /// The material's ASME B16.5 group, taken for the nozzle flanges (forgings of
    /// the vessel's material family), when the table gives one.
    pub flange_group: Option<String>,
    /// The material's Fig. UCS-66 curve letter, when it is a Part UCS material.
    pub ucs66_curve: Option<String>,
    /// The material's API 650 Table 4.4a group, for a tank (5.5.1).
    pub api650_group: Option<String>,
    /// External design pressure, MPa (0 when the design gives none).
    pub external_pressure: f64,
    /// Specified minimum yield strength, MPa (the elastic limit of UG-28).
    pub yield_strength: f64,
    /// Modulus of elasticity, MPa (UG-28's B = A·E/2).
    pub modulus: f64,
}

impl Conditions {
    /// A vessel designed for external pressure (vacuum) only: no internal design
    /// pressure. Its walls are checked by UG-28 / UG-33, its internal formulas see
    /// only the static head, and its test is UG-99(f)'s.
    pub fn vacuum_only(&self) -> bool {
        self.pressure == 0.0 && self.external_pressure > 0.0
    }
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
        return tank_conditions(design, table);
    }
    let pressure = design
        .pressure
        .ok_or("design.pressure: not given; no pressure calculation")?;
    let external = design.external_pressure.unwrap_or(0.0);
    if pressure < 0.0 || (pressure == 0.0 && external <= 0.0) {
        return Err(format!(
            "design.pressure: {pressure} kPa(g) is not an internal pressure; give a vacuum or \
             external design pressure as design.external_pressure (kPa) with design.pressure 0"
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
        flange_group: material.b16_5_group.as_ref().map(|g| g.value.clone()),
        ucs66_curve: material.ucs66_curve.as_ref().map(|g| g.value.clone()),
        api650_group: None,
        external_pressure: external * 1e-3,
        yield_strength: material.yield_strength.value,
        modulus: material.modulus.value,
        code: code_of(kind),
    })
}

/// Highest design temperature of API 650 without Annex M, °C (1.1.1: 93 °C).
pub const API650_MAX_TEMPERATURE: f64 = 93.0;

/// A storage tank's conditions under API 650: Sd and St from the material's
/// specified minimums by 5.6.2.1 / 5.6.2.2; the design pressure (atmospheric up
/// to Annex F) does not enter the one-foot method.
fn tank_conditions(design: &DesignConditions, table: &MaterialTable) -> Result<Conditions, String> {
    let name = design
        .material
        .as_deref()
        .ok_or("design.material: not given; API 650's Sd and St need it")?;
    let material = table
        .get(name)
        .map_err(|e| format!("design.material: {e}"))?;
    let temperature = design.temperature.unwrap_or(TEST_TEMPERATURE);
    if temperature > API650_MAX_TEMPERATURE {
        return Err(format!(
            "design.temperature: {temperature} °C exceeds API 650's {API650_MAX_TEMPERATURE} °C; \
             Annex M (elevated temperature) is not computed"
        ));
    }
    let (sd, st) = super::api650::allowable_stresses(
        material.yield_strength.value,
        material.tensile_strength.value,
    );
    Ok(Conditions {
        pressure: design.pressure.unwrap_or(0.0) * 1e-3,
        temperature,
        corrosion_allowance: design.corrosion_allowance.unwrap_or(0.0),
        joint_efficiency: 1.0,
        joint_efficiency_default: design.joint_efficiency.is_none(),
        material: material.name.clone(),
        stress: sd,
        stress_test: st,
        stress_source: format!(
            "API 650 5.6.2.1/5.6.2.2 from {}'s Sy = {} and Su = {} MPa: Sd = min(2/3·Sy, 2/5·Su), \
             St = min(3/4·Sy, 3/7·Su), rounded to 1 MPa as Table 5-2a",
            material.name, material.yield_strength.value, material.tensile_strength.value
        ),
        flange_group: None,
        ucs66_curve: None,
        api650_group: material.api650_group.as_ref().map(|g| g.value.clone()),
        external_pressure: 0.0,
        yield_strength: material.yield_strength.value,
        modulus: material.modulus.value,
        code: "API 650",
    })
}
