//! Torispherical (flanged and dished) head: toroidal knuckle of radius r about a
//! centre at radius R − r on the tangent line, then a spherical crown of radius L
//! centred on the axis at z0 − √((L − r)² − (R − r)²). Knuckle and crown meet where
//! the line through both centres crosses them, at β = asin((R − r)/(L − r)) from the
//! axis, so the joint is tangent-continuous.

use std::f64::consts::FRAC_PI_2;

use glam::DVec3;

use super::profile::{Segment, arc_xz, knuckle_torus};
use crate::parts::check::{invalid, less_than, positive};
use crate::parts::{Analytic, PartError};

/// Profile from the tangent line at `z0`: knuckle, then crown up to the pole.
pub(super) fn profile(
    part: &'static str,
    r: f64,
    z0: f64,
    crown: f64,
    knuckle: f64,
) -> Result<Vec<Segment>, PartError> {
    let crown = positive(part, "crown_radius", crown)?;
    let knuckle = positive(part, "knuckle_radius", knuckle)?;
    less_than(part, "knuckle_radius", knuckle, crown, "the crown radius")?;
    less_than(part, "knuckle_radius", knuckle, r, "the outside radius D/2")?;
    if crown <= r {
        return Err(invalid(
            part,
            "crown_radius",
            crown,
            format!("must exceed the outside radius D/2 ({r})"),
        ));
    }
    let major = r - knuckle;
    let offset = ((crown - knuckle).powi(2) - major.powi(2)).sqrt();
    let crown_z = z0 - offset;
    let beta = (major / (crown - knuckle)).asin();
    let joint = FRAC_PI_2 - beta;
    Ok(vec![
        Segment {
            name: "knuckle",
            curve: arc_xz(major, z0, knuckle, 0.0, joint)?,
            analytic: knuckle_torus(major, knuckle, z0),
        },
        Segment {
            name: "crown",
            curve: arc_xz(0.0, crown_z, crown, joint, FRAC_PI_2)?,
            analytic: Analytic::Sphere {
                center: DVec3::new(0.0, 0.0, crown_z),
                radius: crown,
            },
        },
    ])
}
