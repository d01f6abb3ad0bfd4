//! A vessel's operating figures from its resolved stack: the pure function the
//! ECS system, `vesselcad info` and the tests share.

use glam::{DAffine3, DVec3};

use super::OperatingError;
use super::liquid::{self, Moments};
use super::profile::{StackPart, Surface, stack_profile};
use super::weight::walls;
use crate::format::{DesignConditions, OperatingDesign, PartDesign, VesselKind, WATER_DENSITY};

/// Density of carbon steel, the default metal, kg/m³.
pub const CARBON_STEEL_DENSITY: f64 = 7850.0;
/// Density of austenitic stainless steel, kg/m³.
pub const STAINLESS_DENSITY: f64 = 8000.0;
/// Largest density accepted for a metal or a liquid, kg/m³ (osmium is 22 590).
pub const MAX_DENSITY: f64 = 25_000.0;

/// mm³ → m³.
const MM3_TO_M3: f64 = 1e-9;

/// The metal density of a vessel, kg/m³: `metal_density` when given; otherwise
/// stainless steel for a stainless material specification (one naming SA-240,
/// SA-312, 304, 316, 321, 347 or "stainless"), carbon steel for any other or none.
pub fn metal_density(conditions: &DesignConditions) -> f64 {
    if let Some(d) = conditions.metal_density {
        return d;
    }
    let stainless = conditions.material.as_deref().is_some_and(|m| {
        let m = m.to_ascii_lowercase();
        ["240", "312", "304", "316", "321", "347", "stainless"]
            .iter()
            .any(|k| m.contains(k))
    });
    if stainless {
        STAINLESS_DENSITY
    } else {
        CARBON_STEEL_DENSITY
    }
}

/// Operating figures of one vessel (kept on its entity as
/// `components::OperatingFigures`).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct OperatingFigures {
    /// Height of the interior (lowest to highest inside point), mm.
    pub interior_height: f64,
    /// Volume of the interior, m³.
    pub interior_volume: f64,
    /// Liquid level above the lowest inside point, mm.
    pub liquid_level: f64,
    /// Liquid volume at that level, m³.
    pub liquid_volume: f64,
    /// Liquid mass, kg.
    pub liquid_mass: f64,
    /// Mass of the pressure envelope's walls (courses, reducers, heads), kg.
    pub metal_mass: f64,
    /// Metal + liquid, kg.
    pub operating_mass: f64,
    /// Centre of gravity of metal + liquid, plant frame, mm.
    pub centre_of_gravity: DVec3,
}

/// The wall thickness a part design gives, if any.
pub fn thickness(part: &PartDesign) -> Option<f64> {
    match part {
        PartDesign::Shell(s) => s.thickness,
        PartDesign::Head(h) => h.thickness,
        PartDesign::Reducer(r) => r.thickness,
        _ => None,
    }
}

/// Liquid volume, operating mass and centre of gravity of a vessel of `kind`
/// placed by `frame`, with stack `stack`, metal of `metal_density` kg/m³, and
/// liquid as `operating` says (none: empty).
///
/// # Errors
///
/// [`OperatingError`] for a wall too thick for its part, an eccentric reducer in
/// a horizontal vessel, a level outside the interior, or a density out of range.
pub fn operating_state(
    kind: VesselKind,
    frame: DAffine3,
    stack: &[StackPart],
    metal_density: f64,
    operating: Option<OperatingDesign>,
) -> Result<OperatingFigures, OperatingError> {
    check_density("metal_density", metal_density)?;
    let horizontal = kind == VesselKind::Horizontal;
    let inside = stack_profile(stack, Surface::Inside, horizontal)?;
    let middle = stack_profile(stack, Surface::Middle, horizontal)?;
    let (z_min, z_max) = inside.axial_extent();
    let r_max = inside.max_radius();
    let height = if horizontal {
        2.0 * r_max
    } else {
        z_max - z_min
    };
    let below = |level: f64| -> Moments {
        if horizontal {
            liquid::horizontal(&inside, level - r_max)
        } else {
            liquid::vertical(&inside, z_min + level)
        }
    };
    let full = below(height);
    let (level, density) = match operating {
        Some(o) => {
            let density = o.liquid_density.unwrap_or(WATER_DENSITY);
            check_density("liquid_density", density)?;
            (o.liquid_level, density)
        }
        None => (0.0, WATER_DENSITY),
    };
    if !(level.is_finite() && (0.0..=height * (1.0 + 1e-12)).contains(&level)) {
        return Err(OperatingError::Level { level, height });
    }
    let liquid = if level >= height { full } else { below(level) };
    let metal = walls(&middle);
    let liquid_mass = liquid.volume * MM3_TO_M3 * density;
    let metal_mass = metal.volume * MM3_TO_M3 * metal_density;
    let total = liquid_mass + metal_mass;
    let centroid = |m: &Moments| {
        if m.volume > 0.0 {
            DVec3::new(
                m.lateral.x / m.volume,
                (m.vertical + m.lateral.y) / m.volume,
                m.axial / m.volume,
            )
        } else {
            DVec3::ZERO
        }
    };
    let local = if total > 0.0 {
        (centroid(&liquid) * liquid_mass + centroid(&metal) * metal_mass) / total
    } else {
        DVec3::new(0.0, 0.0, 0.5 * (z_min + z_max))
    };
    Ok(OperatingFigures {
        interior_height: height,
        interior_volume: full.volume * MM3_TO_M3,
        liquid_level: level,
        liquid_volume: liquid.volume * MM3_TO_M3,
        liquid_mass,
        metal_mass,
        operating_mass: total,
        centre_of_gravity: frame.transform_point3(local),
    })
}

/// A density must be finite, > 0 and at most [`MAX_DENSITY`].
fn check_density(what: &'static str, value: f64) -> Result<(), OperatingError> {
    if value.is_finite() && value > 0.0 && value <= MAX_DENSITY {
        Ok(())
    } else {
        Err(OperatingError::Density {
            what,
            value,
            max: MAX_DENSITY,
        })
    }
}
