//! Vessel reports: the figures `vesselcad info` prints — parts, nozzles, lengths,
//! largest OD, enclosed volume and outside surface area of each vessel, its
//! weights (the one weight model of `weights`, which the sheet and
//! the calculation report print too) and its code calculation's summary —
//! computed from the resolved design and the exact NURBS.

use serde::Serialize;

use crate::calc::{MaterialTable, VesselCalc, calculate};
use crate::constraints::{PartGeometry, ResolvedVessel};
use crate::design::{Design, DesignError, resolve};
use crate::parts::{PartError, enclosed_volume, surface_area};
use crate::weights::metal::MetalItem;
use crate::weights::weights;

/// One part in a report.
#[derive(Clone, Debug, Serialize, PartialEq)]
pub struct PartReport {
    /// Part id.
    pub id: String,
    /// Kind (`shell`, `head`, …).
    pub kind: &'static str,
    /// Axial extent in the vessel frame, mm.
    pub span: [f64; 2],
}

/// The figures of one vessel.
#[derive(Clone, Debug, Serialize, PartialEq)]
pub struct VesselReport {
    /// Tag.
    pub tag: String,
    /// Kind (`horizontal`, `vertical`, `tank`).
    pub kind: String,
    /// Parts in design order.
    pub parts: Vec<PartReport>,
    /// Nozzle marks in design order.
    pub nozzles: Vec<String>,
    /// Tangent-to-tangent length, mm.
    pub tangent_length: f64,
    /// Overall length along the axis incl. heads and supports, mm.
    pub overall_length: f64,
    /// Largest course outside diameter, mm.
    pub outside_diameter: f64,
    /// Volume enclosed by the outside surface of the heads and courses, m³.
    pub volume: f64,
    /// Outside surface area of the heads and courses, m².
    pub surface_area: f64,
    /// Operating figures (see [`crate::operating`]); `None` with the reason in
    /// `operating_problem` when they cannot be computed.
    pub operating: Option<OperatingReport>,
    /// Why there are no operating figures.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub operating_problem: Option<String>,
    /// The code calculation's vessel figures (pressures in MPa): MAWP,
    /// hydrotest, deficiencies, and what could not be calculated.
    pub calculation: VesselCalc,
}

/// The weights and operating figures of a vessel in a report (see
/// [`crate::weights::Weights`]).
#[derive(Clone, Debug, Serialize, PartialEq)]
pub struct OperatingReport {
    /// Capacity: the inside volume, m³.
    pub interior_volume: f64,
    /// Liquid level above the lowest inside point, mm.
    pub liquid_level: f64,
    /// Liquid volume, m³.
    pub liquid_volume: f64,
    /// Walls of the pressure envelope (courses, reducers, heads), kg.
    pub walls_mass: f64,
    /// Every metal item beyond the walls: supports, boot, nozzles with their
    /// flanges, pads, kg each.
    pub metal_items: Vec<MetalItem>,
    /// Empty weight: all metal (walls and items), kg.
    pub metal_mass: f64,
    /// Operating weight: metal + liquid at its level, kg.
    pub operating_mass: f64,
    /// Test weight: metal + water filling the interior, kg.
    pub test_mass: f64,
    /// Centre of gravity empty, plant frame, mm.
    pub centre_of_gravity_empty: [f64; 3],
    /// Centre of gravity operating, plant frame, mm.
    pub centre_of_gravity: [f64; 3],
    /// Centre of gravity full of water, plant frame, mm.
    pub centre_of_gravity_test: [f64; 3],
}

/// Volume (mm³) and area (mm²) of the pressure envelope of a resolved vessel.
fn envelope(vessel: &ResolvedVessel) -> Result<(f64, f64), PartError> {
    let mut volume = 0.0;
    let mut area = 0.0;
    for part in &vessel.parts {
        match &part.geometry {
            PartGeometry::Shell(s) => {
                let r = s.outside_diameter / 2.0;
                volume += std::f64::consts::PI * r * r * s.length;
                area += surface_area(&s.patches()?);
            }
            PartGeometry::Reducer(r) => {
                // Frustum volume; by Cavalieri the same for the eccentric reducer.
                let (a, b) = (r.large_diameter / 2.0, r.small_diameter / 2.0);
                volume += std::f64::consts::PI * r.length / 3.0 * (a * a + a * b + b * b);
                area += surface_area(&r.patches()?);
            }
            PartGeometry::Head(h) => {
                let patches = h.patches()?;
                volume += enclosed_volume(&patches);
                area += surface_area(&patches);
            }
            _ => {}
        }
    }
    Ok((volume, area))
}

/// Reports every vessel of a design.
pub fn report(design: &Design) -> Result<Vec<VesselReport>, DesignError> {
    let resolved = resolve(design)?;
    let table = &MaterialTable::builtin();
    let mut out = Vec::with_capacity(resolved.len());
    for (d, v) in design.vessels.iter().zip(&resolved) {
        let (volume, area) = envelope(v).map_err(|e| {
            DesignError::Invalid(vec![crate::design::RuleViolation {
                path: String::new(),
                entity: v.tag.clone(),
                field: String::new(),
                value: String::new(),
                rule: e.to_string(),
            }])
        })?;
        let (operating, operating_problem) = match weights(d, v) {
            Ok(w) => (
                Some(OperatingReport {
                    interior_volume: w.capacity,
                    liquid_level: d.operating.map_or(0.0, |o| o.liquid_level),
                    liquid_volume: w.liquid
                        / d.operating
                            .and_then(|o| o.liquid_density)
                            .unwrap_or(crate::design::WATER_DENSITY),
                    walls_mass: w.walls,
                    metal_items: w.items,
                    metal_mass: w.empty,
                    operating_mass: w.operating,
                    test_mass: w.test,
                    centre_of_gravity_empty: w.cog_empty,
                    centre_of_gravity: w.cog_operating,
                    centre_of_gravity_test: w.cog_test,
                }),
                None,
            ),
            Err(e) => (None, Some(e.to_string())),
        };
        let calculation = calculate(d, v, table).vessel;
        out.push(VesselReport {
            tag: v.tag.clone(),
            kind: format!("{:?}", v.kind).to_lowercase(),
            parts: v
                .parts
                .iter()
                .map(|p| PartReport {
                    id: p.id.clone(),
                    kind: p.geometry.kind(),
                    span: [p.span.0, p.span.1],
                })
                .collect(),
            nozzles: d.nozzles.iter().map(|n| n.mark.clone()).collect(),
            tangent_length: v.tangent_length,
            overall_length: v.extent.1 - v.extent.0,
            outside_diameter: v.max_diameter,
            volume: volume * 1e-9,
            surface_area: area * 1e-6,
            operating,
            operating_problem,
            calculation,
        });
    }
    Ok(out)
}
