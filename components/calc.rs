//! Derived components of the code calculations (ASME VIII-1): a pressure part's
//! calculation, a nozzle's UG-45 check, and the vessel's figures (MAWP,
//! hydrotest, deficiencies). Written by `systems::update_calculations` only,
//! when their value changes.

use bevy_ecs::component::Component;

use crate::calc::{Liquid, NozzleCalc, PartCalc, VesselCalc};

/// A pressure part's calculation, or why its formula could not be applied.
#[derive(Component, Clone, Debug, PartialEq)]
pub struct PartCalculation(pub Result<PartCalc, String>);

/// A nozzle's UG-45 check, or why it could not be made.
#[derive(Component, Clone, Debug, PartialEq)]
pub struct NozzleCalculation(pub Result<NozzleCalc, String>);

/// A vessel's figures, with the liquid its static heads were taken from.
#[derive(Component, Clone, Debug, PartialEq)]
pub struct VesselCalculation {
    /// MAWP, hydrotest, deficiencies, problems.
    pub calc: VesselCalc,
    /// The liquid the parts' static heads came from (`None`: empty).
    pub liquid: Option<Liquid>,
}
