//! Pressure-vessel calculations to ASME Section VIII Division 1: the materials
//! table, the internal-pressure formulas of UG-27, UG-32, UG-34 and Appendix 1-4,
//! and the vessel-level figures (MAWP, UG-99 hydrotest, UG-16(b) minimum).
//!
//! Units inside are SI: pressure and stress in MPa, lengths in mm, temperature in
//! °C (the design file's kPa(g) is converted by the caller). Every result is a
//! [`Formula`] carrying its code paragraph and the formula's text, so a report can
//! show what was computed. Internal-pressure results are hot and corroded: the
//! inside dimensions grow by the corrosion allowance and the thickness shrinks by
//! it ([`Shape::corroded`]). This is a pure library: no ECS wiring.

mod error;
pub mod heads;
pub mod materials;
mod shape;
pub mod shells;
pub mod vessel;

pub use error::CalcError;
pub use materials::{Material, MaterialTable};
pub use shape::{Formula, Shape, Strength, mawp, required_thickness};
