//! Length-unit conversion of a design on load.
//!
//! A file may declare `"units": "in"`; every length in it is then multiplied by 25.4
//! once, right after parsing, and the design is held (and saved) in mm from then on.
//! Nominal pipe sizes (NPS) stay in inches, as they are names rather than lengths;
//! angles, pressures and temperatures are not lengths and are never scaled.

use super::schema::{Design, PartDesign, Units};

/// Millimetres per inch.
pub const MM_PER_INCH: f64 = 25.4;

/// Converts a design to mm in place (a no-op for mm files) and marks it as mm.
pub fn to_millimetres(design: &mut Design) {
    if design.units == Units::Mm {
        return;
    }
    for_each_length(design, |v| *v *= MM_PER_INCH);
    design.units = Units::Mm;
}

/// Converts a design in mm to inches in place and marks it as inches: the form
/// an inch file is saved in. Each length is written with the fewest decimals
/// (up to 12) that read back to the same mm, so a value the file gave as `48`
/// is saved as `48`, not `48.00000000000001`; a value set in mm that no short
/// decimal reaches keeps 6 decimals (a millionth of an inch).
pub fn to_inches(design: &mut Design) {
    if design.units == Units::In {
        return;
    }
    for_each_length(design, |v| *v = shortest_inches(*v));
    design.units = Units::In;
}

/// The inch value of `mm` with the fewest decimals that converts back to `mm`
/// exactly; 6 decimals if none up to 12 does.
fn shortest_inches(mm: f64) -> f64 {
    let inches = mm / MM_PER_INCH;
    if !inches.is_finite() {
        return inches;
    }
    let round = |decimals: i32| {
        let k = 10f64.powi(decimals);
        (inches * k).round() / k
    };
    (0..=12)
        .map(round)
        .find(|&x| x * MM_PER_INCH == mm)
        .unwrap_or_else(|| round(6))
}

/// Calls `f` on every length of a design (not nominal sizes, angles, pressures
/// or temperatures).
fn for_each_length(design: &mut Design, mut f: impl FnMut(&mut f64)) {
    let mut scale = |v: &mut f64| f(v);
    for vessel in &mut design.vessels {
        vessel.placement.position.iter_mut().for_each(&mut scale);
        scale_opt(&mut vessel.design.corrosion_allowance, &mut scale);
        if let Some(w) = &mut vessel.design.wind {
            scale_opt(&mut w.base_elevation, &mut scale);
        }
        if let Some(op) = &mut vessel.operating {
            scale(&mut op.liquid_level);
        }
        for part in &mut vessel.parts {
            match part {
                PartDesign::Shell(p) => {
                    scale(&mut p.od);
                    scale(&mut p.length);
                    scale_opt(&mut p.thickness, &mut scale);
                }
                PartDesign::Head(p) => {
                    scale_opt(&mut p.crown_radius, &mut scale);
                    scale_opt(&mut p.knuckle_radius, &mut scale);
                    scale_opt(&mut p.small_od, &mut scale);
                    scale(&mut p.straight_flange);
                    scale_opt(&mut p.thickness, &mut scale);
                }
                PartDesign::Reducer(p) => {
                    scale(&mut p.length);
                    scale_opt(&mut p.thickness, &mut scale);
                }
                PartDesign::Skirt(p) => {
                    scale(&mut p.height);
                    scale(&mut p.base_ring_width);
                    scale_opt(&mut p.base_ring_thickness, &mut scale);
                    scale_opt(&mut p.thickness, &mut scale);
                }
                PartDesign::Saddle(p) => {
                    scale_opt(&mut p.position, &mut scale);
                    scale(&mut p.width);
                    scale(&mut p.height);
                    scale_opt(&mut p.web_thickness, &mut scale);
                    scale_opt(&mut p.wear_plate, &mut scale);
                }
                PartDesign::Legs(p) => scale(&mut p.length),
                PartDesign::Lugs(p) => {
                    scale(&mut p.elevation);
                    scale(&mut p.height);
                    scale(&mut p.projection);
                    scale(&mut p.width);
                }
                PartDesign::Boot(p) => {
                    scale(&mut p.position);
                    scale(&mut p.od);
                    scale(&mut p.length);
                }
            }
        }
        for n in &mut vessel.nozzles {
            scale_opt(&mut n.elevation, &mut scale);
            scale_opt(&mut n.offset, &mut scale);
            scale(&mut n.projection);
            if let Some(pad) = &mut n.pad {
                scale(&mut pad.od);
                scale(&mut pad.thickness);
            }
        }
        for note in &mut vessel.notes {
            note.offset.iter_mut().for_each(&mut scale);
        }
    }
}

/// Calls `scale` on a length that may be absent.
fn scale_opt(value: &mut Option<f64>, scale: &mut dyn FnMut(&mut f64)) {
    if let Some(x) = value {
        scale(x);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn inches_come_back_as_written() {
        for written in [48.0, 0.375, 120.125, 7.2, 1e-3, 33.333] {
            assert_eq!(shortest_inches(written * MM_PER_INCH), written);
        }
        // A value set in mm that no short decimal reaches: a millionth of an inch.
        assert_eq!(shortest_inches(1000.0 / 3.0), 13.123360);
    }
}
