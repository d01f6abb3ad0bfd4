//! Toriconical head: a toroidal knuckle turning the flange through the half-angle α,
//! then a cone of half-angle α closing to an apex on the axis.

use glam::DVec3;

use super::profile::{Segment, arc_xz, half_angle, knuckle_torus, xz};
use crate::nurbs::builders::line;
use crate::parts::check::{less_than, positive};
use crate::parts::{Analytic, PartError};

/// Profile from the tangent line at `z0`: knuckle, then cone to the apex.
pub(super) fn profile(
    part: &'static str,
    r: f64,
    z0: f64,
    half_angle_deg: f64,
    knuckle: f64,
) -> Result<Vec<Segment>, PartError> {
    let alpha = half_angle(part, half_angle_deg)?;
    let knuckle = positive(part, "knuckle_radius", knuckle)?;
    less_than(part, "knuckle_radius", knuckle, r, "the outside radius D/2")?;
    let major = r - knuckle;
    let end = xz(major + knuckle * alpha.cos(), z0 + knuckle * alpha.sin());
    let apex = xz(0.0, end.z + end.x / alpha.tan());
    Ok(vec![
        Segment {
            name: "knuckle",
            curve: arc_xz(major, z0, knuckle, 0.0, alpha)?,
            analytic: knuckle_torus(major, knuckle, z0),
        },
        Segment {
            name: "cone",
            curve: line(end, apex)?,
            analytic: Analytic::Cone {
                apex,
                axis: -DVec3::Z,
                half_angle: alpha,
            },
        },
    ])
}
