//! Conical head without knuckle: a cone of half-angle α from the flange to an apex,
//! or truncated at a small diameter and closed there by a flat plate.

use glam::DVec3;

use super::profile::{Segment, half_angle, xz};
use crate::nurbs::builders::line;
use crate::parts::check::{less_than, non_negative};
use crate::parts::{Analytic, PartError};

/// Profile from the tangent line at `z0`: cone, then (truncated) the small-end plate.
pub(super) fn profile(
    part: &'static str,
    r: f64,
    z0: f64,
    half_angle_deg: f64,
    small_diameter: f64,
) -> Result<Vec<Segment>, PartError> {
    let alpha = half_angle(part, half_angle_deg)?;
    let small = non_negative(part, "small_diameter", small_diameter)?;
    less_than(
        part,
        "small_diameter",
        small,
        2.0 * r,
        "the outside diameter",
    )?;
    let apex = xz(0.0, z0 + r / alpha.tan());
    let cone = Analytic::Cone {
        apex,
        axis: -DVec3::Z,
        half_angle: alpha,
    };
    if small == 0.0 {
        return Ok(vec![Segment {
            name: "cone",
            curve: line(xz(r, z0), apex)?,
            analytic: cone,
        }]);
    }
    let rs = small / 2.0;
    let top = z0 + (r - rs) / alpha.tan();
    Ok(vec![
        Segment {
            name: "cone",
            curve: line(xz(r, z0), xz(rs, top))?,
            analytic: cone,
        },
        Segment {
            name: "small end plate",
            curve: line(xz(rs, top), xz(0.0, top))?,
            analytic: Analytic::Plane {
                point: DVec3::new(0.0, 0.0, top),
                normal: DVec3::Z,
            },
        },
    ])
}
