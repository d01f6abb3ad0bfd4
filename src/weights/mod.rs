//! One weight model: the figures `vesselcad info`, the sheet's design data and
//! the calculation report all print. Metal of every part — the envelope's walls
//! exactly ([`crate::operating::weight`]), supports, boot, nozzles, flanges and pads by
//! [`metal`] — at the vessel's metal density; liquid at its level; the
//! test weight full of water. Each weight comes with its centre of gravity.

pub mod metal;

use glam::DVec3;

use metal::{MetalItem, items};
use serde::Serialize;

use crate::constraints::ResolvedVessel;
use crate::constraints::stack_of;
use crate::design::{OperatingDesign, VesselDesign, WATER_DENSITY};
use crate::operating::{OperatingError, metal_density, operating_state};

/// A vessel's weights, kg, and centres of gravity, plant frame, mm.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Weights {
    /// Metal density used, kg/m³.
    pub metal_density: f64,
    /// Walls of the pressure envelope (courses, reducers, heads).
    pub walls: f64,
    /// Every other metal item (supports, boot, nozzles with flanges, pads).
    pub items: Vec<MetalItem>,
    /// Empty: all metal.
    pub empty: f64,
    /// Liquid at the operating level.
    pub liquid: f64,
    /// Operating: empty + liquid.
    pub operating: f64,
    /// Test: empty + water filling the interior.
    pub test: f64,
    /// Capacity: the inside volume, m³.
    pub capacity: f64,
    /// Centre of gravity, empty.
    pub cog_empty: [f64; 3],
    /// Centre of gravity, operating.
    pub cog_operating: [f64; 3],
    /// Centre of gravity, test.
    pub cog_test: [f64; 3],
}

/// The weights of vessel `design` resolved as `resolved`.
///
/// # Errors
///
/// As [`operating_state`]: a wall too thick for its part, an eccentric reducer in
/// a horizontal vessel, a level outside the interior, a density out of range.
pub fn weights(
    design: &VesselDesign,
    resolved: &ResolvedVessel,
) -> Result<Weights, OperatingError> {
    let density = metal_density(&design.design);
    let stack = stack_of(design, resolved);
    let state =
        |operating| operating_state(design.kind, resolved.frame, &stack, density, operating);
    let empty_walls = state(None)?;
    let operating = state(design.operating)?;
    let full = state(Some(OperatingDesign {
        liquid_level: empty_walls.interior_height,
        liquid_density: Some(WATER_DENSITY),
    }))?;
    let items = items(design, &resolved.parts, &resolved.nozzles, density);
    let item_mass: f64 = items.iter().map(|i| i.mass).sum();
    let item_moment: DVec3 = items
        .iter()
        .map(|i| resolved.frame.transform_point3(i.centre) * i.mass)
        .sum();
    let walls = empty_walls.metal_mass;
    let with = |base_mass: f64, base_cog: DVec3| -> (f64, [f64; 3]) {
        let total = base_mass + item_mass;
        let cog = if total > 0.0 {
            (base_cog * base_mass + item_moment) / total
        } else {
            base_cog
        };
        (total, cog.to_array())
    };
    let (empty, cog_empty) = with(walls, empty_walls.centre_of_gravity);
    let (operating_mass, cog_operating) =
        with(operating.operating_mass, operating.centre_of_gravity);
    let (test, cog_test) = with(full.operating_mass, full.centre_of_gravity);
    Ok(Weights {
        metal_density: density,
        walls,
        items,
        empty,
        liquid: operating.liquid_mass,
        operating: operating_mass,
        test,
        capacity: empty_walls.interior_volume,
        cog_empty,
        cog_operating,
        cog_test,
    })
}
