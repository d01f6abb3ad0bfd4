//! Derived components of the code calculations (ASME VIII-1): a pressure part's
//! calculation, a nozzle's UG-45 check, and the vessel's figures (MAWP,
//! hydrotest, deficiencies). Written by `systems::update_calculations` only,
//! when their value changes.

use std::sync::Arc;

use bevy_ecs::component::Component;
use bevy_ecs::resource::Resource;

use crate::calc::{Liquid, MaterialTable, NozzleCalc, PartCalc, VesselCalc};

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

/// The materials table the calculations use (the built-in one unless the
/// model was given another).
#[derive(Resource, Clone)]
pub struct Materials(pub Arc<MaterialTable>);
