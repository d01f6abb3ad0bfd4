//! Data a vessel carries for drawings, weights and analysis rather than for its
//! shape: design conditions and wall thicknesses.
//!
//! No part builder reads these numbers, so nothing downstream of the shape would
//! notice a negative wall or a pressure below full vacuum; they are checked here so
//! that everything a design file is allowed to say makes physical sense:
//!
//! - design pressure (kPa gauge) is finite, at least full vacuum (−101.325 kPa)
//!   and at most [`MAX_PRESSURE`];
//! - design temperature (°C) is finite, above absolute zero and at most
//!   [`MAX_TEMPERATURE`];
//! - a wall thickness given for a shell course, head or reducer lies between
//!   [`MIN_DIMENSION`] and the smallest outside radius of that part;
//! - the corrosion allowance is finite, ≥ 0 and thinner than every wall thickness
//!   the design gives.

use super::geometry::PartGeometry;
use super::{Report, ResolvedPart};
use crate::design::{PartDesign, VesselDesign};
use crate::parts::MIN_DIMENSION;

/// Full vacuum as a gauge pressure, kPa.
pub const FULL_VACUUM: f64 = -101.325;
/// Largest design pressure accepted, kPa gauge (1 GPa).
pub const MAX_PRESSURE: f64 = 1e6;
/// Absolute zero, °C.
pub const ABSOLUTE_ZERO: f64 = -273.15;
/// Largest design temperature accepted, °C.
pub const MAX_TEMPERATURE: f64 = 1e4;

/// Checks the design conditions and the wall thicknesses of the resolved stack
/// parts (parts that failed to resolve were reported already).
pub(crate) fn check(vessel: &VesselDesign, parts: &[Option<ResolvedPart>], report: &mut Report) {
    let c = &vessel.design;
    if let Some(p) = c.pressure
        && !(p.is_finite() && (FULL_VACUUM..=MAX_PRESSURE).contains(&p))
    {
        report.push(
            "design.pressure",
            None,
            "pressure",
            p,
            format!(
                "must be a gauge pressure between full vacuum ({FULL_VACUUM} kPa) and \
                 {MAX_PRESSURE} kPa"
            ),
        );
    }
    if let Some(t) = c.temperature
        && !(t.is_finite() && t > ABSOLUTE_ZERO && t <= MAX_TEMPERATURE)
    {
        report.push(
            "design.temperature",
            None,
            "temperature",
            t,
            format!(
                "must lie above absolute zero ({ABSOLUTE_ZERO} °C) and at most {MAX_TEMPERATURE} °C"
            ),
        );
    }
    if c.material.as_deref().is_some_and(|m| m.trim().is_empty()) {
        report.push(
            "design.material",
            None,
            "material",
            "\"\"",
            "must not be empty when given (leave it out instead)",
        );
    }
    // Wall thicknesses, and the thinnest of them for the corrosion allowance.
    let mut thinnest: Option<(f64, &str)> = None;
    for (i, (design, resolved)) in vessel.parts.iter().zip(parts).enumerate() {
        let Some(resolved) = resolved else { continue };
        let (thickness, radius) = match (design, &resolved.geometry) {
            (PartDesign::Shell(s), PartGeometry::Shell(g)) => {
                (s.thickness, g.outside_diameter / 2.0)
            }
            (PartDesign::Head(h), PartGeometry::Head(g)) => (h.thickness, g.outside_diameter / 2.0),
            (PartDesign::Reducer(r), PartGeometry::Reducer(g)) => {
                (r.thickness, g.small_diameter / 2.0)
            }
            _ => continue,
        };
        let Some(t) = thickness else { continue };
        if !(t.is_finite() && t >= MIN_DIMENSION && t < radius) {
            report.push(
                format!("parts[{i}].{}.thickness", design.kind()),
                Some(design.id()),
                "thickness",
                t,
                format!(
                    "must lie between {MIN_DIMENSION} mm and the part's smallest outside \
                     radius ({radius} mm)"
                ),
            );
            continue;
        }
        if thinnest.is_none_or(|(least, _)| t < least) {
            thinnest = Some((t, design.id()));
        }
    }
    if let Some(ca) = c.corrosion_allowance {
        if !(ca.is_finite() && ca >= 0.0) {
            report.push(
                "design.corrosion_allowance",
                None,
                "corrosion_allowance",
                ca,
                "must be a finite number ≥ 0 mm",
            );
        } else if let Some((least, id)) = thinnest
            && ca >= least
        {
            report.push(
                "design.corrosion_allowance",
                None,
                "corrosion_allowance",
                ca,
                format!("must be thinner than every wall: {id} is {least} mm thick"),
            );
        }
    }
}
