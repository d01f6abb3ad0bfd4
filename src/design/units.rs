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
    let k = MM_PER_INCH;
    let scale = |v: &mut f64| *v *= k;
    let scale_opt = |v: &mut Option<f64>| {
        if let Some(x) = v {
            *x *= k;
        }
    };
    for vessel in &mut design.vessels {
        vessel.placement.position.iter_mut().for_each(scale);
        scale_opt(&mut vessel.design.corrosion_allowance);
        if let Some(op) = &mut vessel.operating {
            scale(&mut op.liquid_level);
        }
        for part in &mut vessel.parts {
            match part {
                PartDesign::Shell(p) => {
                    scale(&mut p.od);
                    scale(&mut p.length);
                    scale_opt(&mut p.thickness);
                }
                PartDesign::Head(p) => {
                    scale_opt(&mut p.crown_radius);
                    scale_opt(&mut p.knuckle_radius);
                    scale_opt(&mut p.small_od);
                    scale(&mut p.straight_flange);
                    scale_opt(&mut p.thickness);
                }
                PartDesign::Reducer(p) => {
                    scale(&mut p.length);
                    scale_opt(&mut p.thickness);
                }
                PartDesign::Skirt(p) => {
                    scale(&mut p.height);
                    scale(&mut p.base_ring_width);
                    scale_opt(&mut p.thickness);
                }
                PartDesign::Saddle(p) => {
                    scale_opt(&mut p.position);
                    scale(&mut p.width);
                    scale(&mut p.height);
                    scale_opt(&mut p.web_thickness);
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
            scale_opt(&mut n.elevation);
            scale_opt(&mut n.offset);
            scale(&mut n.projection);
            if let Some(pad) = &mut n.pad {
                scale(&mut pad.od);
                scale(&mut pad.thickness);
            }
        }
        for note in &mut vessel.notes {
            note.offset.iter_mut().for_each(scale);
        }
    }
    design.units = Units::Mm;
}
