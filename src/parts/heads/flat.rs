//! Flat head: a plain flat plate at the tangent line, or (flanged flat) a quarter
//! torus knuckle turning the flange into the plate.

use std::f64::consts::FRAC_PI_2;

use glam::DVec3;

use super::profile::{Segment, arc_xz, knuckle_torus, xz};
use crate::nurbs::builders::line;
use crate::parts::check::{less_than, non_negative};
use crate::parts::{Analytic, PartError};

/// Profile from the tangent line at `z0`: optional knuckle, then the plate.
pub(super) fn profile(
    part: &'static str,
    r: f64,
    z0: f64,
    knuckle: f64,
) -> Result<Vec<Segment>, PartError> {
    let knuckle = non_negative(part, "knuckle_radius", knuckle)?;
    less_than(part, "knuckle_radius", knuckle, r, "the outside radius D/2")?;
    let plate_z = z0 + knuckle;
    let plate = Analytic::Plane {
        point: DVec3::new(0.0, 0.0, plate_z),
        normal: DVec3::Z,
    };
    let mut out = Vec::new();
    if knuckle > 0.0 {
        let major = r - knuckle;
        out.push(Segment {
            name: "knuckle",
            curve: arc_xz(major, z0, knuckle, 0.0, FRAC_PI_2)?,
            analytic: knuckle_torus(major, knuckle, z0),
        });
    }
    out.push(Segment {
        name: "plate",
        curve: line(xz(r - knuckle, plate_z), xz(0.0, plate_z))?,
        analytic: plate,
    });
    Ok(out)
}
