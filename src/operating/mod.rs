//! Operating state of a vessel: liquid volume at its level, operating weight
//! (metal + liquid) and centre of gravity.
//!
//! A branch of the data flow beside geometry: from a vessel's resolved stack
//! (courses, reducers, heads with their frames) and its wall thicknesses,
//! [`profile`] builds the exact meridian of the inside surface and of the wall's
//! mid-surface; [`liquid`] integrates the liquid below the level (vertical and
//! horizontal vessels, every head kind); [`weight`] integrates the walls. The ECS
//! system `systems::update_operating_states` keeps these [`OperatingFigures`] on
//! every vessel (`components::OperatingState`), redone only when the vessel was
//! resolved again or its `OperatingSpec` (level, liquid density) changed. The
//! figures of a resolved vessel are `constraints::state_of_design`.
//!
//! Units: inputs mm and kg/m³; outputs m³, kg and mm (plant frame).

pub mod liquid;
pub mod profile;
mod state;
pub mod weight;

pub use state::{
    CARBON_STEEL_DENSITY, MAX_DENSITY, OperatingFigures, STAINLESS_DENSITY, metal_density,
    operating_state, thickness,
};

use thiserror::Error;

/// Why the operating figures of a vessel cannot be computed.
#[derive(Debug, Error, Clone, PartialEq)]
pub enum OperatingError {
    /// A wall is as thick as (or thicker than) a size of its part's shape.
    #[error(
        "part {part}: the wall thickness {thickness} mm must be smaller than its {what} ({size} mm) to have an inside"
    )]
    ThickWall {
        /// Part id.
        part: String,
        /// Which size (`knuckle radius`, `depth`, …).
        what: &'static str,
        /// That size, mm.
        size: f64,
        /// The wall thickness, mm.
        thickness: f64,
    },
    /// An eccentric reducer in a horizontal vessel (cross-sections off the axis).
    #[error(
        "part {part}: liquid volumes of horizontal vessels with an eccentric reducer are not supported"
    )]
    Eccentric {
        /// Part id.
        part: String,
    },
    /// The liquid level is negative, not finite or above the top of the interior.
    #[error(
        "liquid level {level} mm must lie between 0 (empty) and the interior's height {height} mm"
    )]
    Level {
        /// The level given, mm.
        level: f64,
        /// Height of the interior, mm.
        height: f64,
    },
    /// A density is not a finite positive number in range.
    #[error("{what} {value} kg/m³ must be a finite number in (0, {max}] kg/m³")]
    Density {
        /// `liquid_density` or `metal_density`.
        what: &'static str,
        /// The value given.
        value: f64,
        /// Largest accepted value.
        max: f64,
    },
}
