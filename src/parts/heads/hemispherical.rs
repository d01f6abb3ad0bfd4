//! Hemispherical head: a quarter circle of the outside radius, revolved.

use std::f64::consts::FRAC_PI_2;

use glam::DVec3;

use super::profile::{Segment, arc_xz};
use crate::parts::{Analytic, PartError};

/// Profile from the tangent line at height `z0` to the pole at `z0 + r`.
pub(super) fn profile(r: f64, z0: f64) -> Result<Vec<Segment>, PartError> {
    Ok(vec![Segment {
        name: "crown",
        curve: arc_xz(0.0, z0, r, 0.0, FRAC_PI_2)?,
        analytic: Analytic::Sphere {
            center: DVec3::new(0.0, 0.0, z0),
            radius: r,
        },
    }])
}
