//! Ellipsoidal head: a quarter ellipse with semi-axes D/2 (across) and D/(2·ratio)
//! (along the axis), revolved. The 2:1 head has depth D/4.

use std::f64::consts::FRAC_PI_2;

use glam::DVec3;

use super::profile::{Segment, xz};
use crate::nurbs::builders::elliptical_arc;
use crate::parts::check::{in_range, positive};
use crate::parts::{Analytic, PartError};

/// Profile from the tangent line at `z0` to the pole at `z0 + r / ratio`.
pub(super) fn profile(
    part: &'static str,
    r: f64,
    z0: f64,
    ratio: f64,
) -> Result<Vec<Segment>, PartError> {
    let ratio = in_range(part, "ratio", ratio, 0.1, 100.0, false)?;
    let depth = r / ratio;
    positive(part, "depth", depth)?;
    Ok(vec![Segment {
        name: "crown",
        curve: elliptical_arc(xz(0.0, z0), DVec3::X, DVec3::Z, r, depth, 0.0, FRAC_PI_2)?,
        analytic: Analytic::Spheroid {
            center: DVec3::new(0.0, 0.0, z0),
            axis: DVec3::Z,
            equatorial: r,
            polar: depth,
        },
    }])
}
