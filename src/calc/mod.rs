//! Pressure-vessel calculations to ASME Section VIII Division 1: the materials
//! table, the internal-pressure formulas of UG-27, UG-32, UG-34 and Appendix 1-4,
//! and the vessel-level figures (MAWP, UG-99 hydrotest, UG-16(b) minimum).
//!
//! Units inside are SI: pressure and stress in MPa, lengths in mm, temperature in
//! °C (the design file's kPa(g) is converted by the caller). Every result is a
//! [`Formula`] carrying its code paragraph and the formula's text, so a report can
//! show what was computed. Internal-pressure results are hot and corroded: the
//! inside dimensions grow by the corrosion allowance and the thickness shrinks by
//! it ([`Shape::corroded`]).
//!
//! On top of the formulas: a vessel's design conditions in calculation units
//! ([`conditions`]), one pressure part ([`part_calc`]), UG-45 for a nozzle neck
//! with UG-37 reinforcement ([`mod@reinforcement`]) and the B16.5 flange rating
//! ([`flange`]) ([`nozzle_calc`]), the supports of a vessel (Zick's saddle
//! stresses, [`saddles`]), the UCS-66 MDMT ([`mdmt`], on the curves of [`ucs66`]) and a
//! whole vessel ([`calculate`]). The ECS system
//! `systems::update_calculations` keeps the same figures live as components.

pub mod annular;
pub mod api650;
mod conditions;
mod deficiency;
mod error;
pub mod external;
pub mod flange;
pub mod heads;
pub mod html;
pub mod lateral;
pub mod legs;
pub mod materials;
pub mod mdmt;
mod nozzle;
mod part;
pub mod reinforcement;
mod report_supports;
mod report_tables;
pub mod saddles;
pub mod seismic;
mod shape;
pub mod shells;
pub mod skirt;
mod summary;
pub mod ucs66;
pub mod vessel;
pub mod wind;
pub mod zick;

pub use conditions::{Conditions, DEFAULT_JOINT_EFFICIENCY, TEST_TEMPERATURE, code_of, conditions};
pub use deficiency::{Deficiency, deficiencies_by_item};
pub use error::CalcError;
pub use flange::FlangeRating;
pub use materials::{Material, MaterialTable};
pub use mdmt::Mdmt;
pub use nozzle::{NozzleCalc, PIPE_UNDERTOLERANCE, nozzle_calc};
pub use part::{Input, PartCalc, part_calc, pressure_shape};
pub use reinforcement::{Opening, Reinforcement, reinforcement, reinforcement_external};
pub use shape::{Formula, Shape, Strength, mawp, required_thickness};
pub use summary::{
    Calculation, LateralFigures, Liquid, VesselCalc, calculate, has_calculated_supports,
    support_calcs,
};
pub use vessel::GRAVITY;
