//! Rules on a vessel's operating data: the liquid level lies within the interior,
//! densities are physical, and the walls leave an inside to fill.
//!
//! Part of the constraint resolution (so an edit that breaks them is refused with
//! its JSON path); the figures themselves come from [`crate::operating`]. Checked
//! only for vessels that carry operating data or a metal density, so designs
//! written before these fields existed are judged exactly as before.

use glam::DAffine3;

use super::{KnownOperating, Report, ResolvedPart, ResolvedVessel};
use crate::format::VesselDesign;
use crate::operating::{
    OperatingError, OperatingFigures, metal_density, operating_state, profile::StackPart, thickness,
};

/// Checks the operating data of `vessel` against its resolved stack; returns
/// the operating figures worked out on the way (none when it has no operating
/// data, breaks a rule or broke one before).
pub(crate) fn check(
    vessel: &VesselDesign,
    frame: DAffine3,
    parts: &[Option<ResolvedPart>],
    report: &mut Report,
) -> Option<KnownOperating> {
    if vessel.operating.is_none() && vessel.design.metal_density.is_none() {
        return None;
    }
    if !report.violations.is_empty() || parts.iter().any(Option::is_none) {
        return None;
    }
    let stack: Vec<StackPart> = parts
        .iter()
        .flatten()
        .map(|p| StackPart {
            id: &p.id,
            geometry: &p.geometry,
            frame: p.frame,
            thickness: vessel
                .parts
                .iter()
                .find(|d| d.id() == p.id)
                .and_then(thickness)
                .unwrap_or(0.0),
        })
        .collect();
    let error = match operating_state(
        vessel.kind,
        frame,
        &stack,
        metal_density(&vessel.design),
        vessel.operating,
    ) {
        Ok(state) => {
            return Some(KnownOperating {
                data: vessel.operating,
                metal_density: metal_density(&vessel.design),
                state,
            });
        }
        Err(error) => error,
    };
    let part_path = |id: &str| {
        let i = vessel.parts.iter().position(|p| p.id() == id).unwrap_or(0);
        format!("parts[{i}].{}", vessel.parts[i].kind())
    };
    match &error {
        OperatingError::Level { level, .. } => report.push(
            "operating.liquid_level",
            None,
            "liquid_level",
            *level,
            error.to_string(),
        ),
        OperatingError::Density { what, value, .. } => {
            let path = if *what == "metal_density" {
                "design.metal_density"
            } else {
                "operating.liquid_density"
            };
            report.push(path, None, what, *value, error.to_string());
        }
        OperatingError::ThickWall {
            part, thickness, ..
        } => report.push(
            format!("{}.thickness", part_path(part)),
            Some(part),
            "thickness",
            *thickness,
            error.to_string(),
        ),
        OperatingError::Eccentric { part } => report.push(
            format!("{}.eccentric", part_path(part)),
            Some(part),
            "eccentric",
            "set",
            error.to_string(),
        ),
    }
    None
}

/// The stack parts of a resolved vessel with their wall thicknesses (0 where the
/// design gives none).
pub fn stack_of<'a>(design: &'a VesselDesign, resolved: &'a ResolvedVessel) -> Vec<StackPart<'a>> {
    resolved
        .parts
        .iter()
        .map(|p| StackPart {
            id: &p.id,
            geometry: &p.geometry,
            frame: p.frame,
            thickness: design
                .parts
                .iter()
                .find(|d| d.id() == p.id)
                .and_then(thickness)
                .unwrap_or(0.0),
        })
        .collect()
}

/// [`operating_state`] of a design and its resolution.
///
/// # Errors
///
/// As [`operating_state`].
pub fn state_of_design(
    design: &VesselDesign,
    resolved: &ResolvedVessel,
) -> Result<OperatingFigures, OperatingError> {
    operating_state(
        design.kind,
        resolved.frame,
        &stack_of(design, resolved),
        metal_density(&design.design),
        design.operating,
    )
}
