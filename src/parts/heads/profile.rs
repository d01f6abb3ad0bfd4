//! A piece of a head's meridian profile: the curve in the XZ half-plane, its patch
//! name and the analytic surface its revolution lies on.

use glam::DVec3;

use crate::nurbs::NurbsCurve;
use crate::nurbs::builders::circular_arc;
use crate::parts::check::in_range;
use crate::parts::{Analytic, PartError};

/// One smooth piece of a meridian, running away from the open end.
pub(super) struct Segment {
    pub name: &'static str,
    pub curve: NurbsCurve,
    pub analytic: Analytic,
}

/// A point of the XZ half-plane at radius `x` and height `z`.
pub(super) fn xz(x: f64, z: f64) -> DVec3 {
    DVec3::new(x, 0.0, z)
}

/// The arc of `radius` about (`cx`, `cz`) in the XZ plane from angle `from` to `to`
/// (radians, measured from +X towards +Z).
pub(super) fn arc_xz(
    cx: f64,
    cz: f64,
    radius: f64,
    from: f64,
    to: f64,
) -> Result<NurbsCurve, PartError> {
    Ok(circular_arc(
        xz(cx, cz),
        DVec3::X,
        DVec3::Z,
        radius,
        from,
        to,
    )?)
}

/// The torus swept by a knuckle of `minor` radius whose centre is at radius `major`
/// and height `z`.
pub(super) fn knuckle_torus(major: f64, minor: f64, z: f64) -> Analytic {
    Analytic::Torus {
        center: DVec3::new(0.0, 0.0, z),
        axis: DVec3::Z,
        major,
        minor,
    }
}

/// Smallest cone half-angle a head accepts, degrees.
pub(super) const MIN_HALF_ANGLE: f64 = 1.0;
/// Largest cone half-angle a head accepts, degrees (beyond it, design a flat head).
pub(super) const MAX_HALF_ANGLE: f64 = 89.0;

/// A cone head's `half_angle` (degrees) checked to lie within
/// [`MIN_HALF_ANGLE`], [`MAX_HALF_ANGLE`]; in radians.
pub(super) fn half_angle(part: &'static str, degrees: f64) -> Result<f64, PartError> {
    Ok(in_range(
        part,
        "half_angle",
        degrees,
        MIN_HALF_ANGLE,
        MAX_HALF_ANGLE,
        false,
    )?
    .to_radians())
}
