//! Exact constructions: lines, circular and elliptical arcs, and the surfaces the
//! vessel parts are made of (revolutions, ruled surfaces, extrusions, planar disks,
//! annuli and quads).
//!
//! Every arc is a rational quadratic whose segments sweep at most 90° and whose first
//! control point lies ON the circle (the thesis's shell polygons start at a square
//! corner and are not circles; see `shared/spec/000` §11). Angles are radians here;
//! the part builders convert from degrees.

mod arc;
mod line;
mod planar;
mod revolve;
mod ruled;

pub use arc::{circle, circular_arc, elliptical_arc};
pub use line::line;
pub use planar::{annulus, disk, planar_quad};
pub use revolve::{FULL_TURN_KNOTS, revolve};
pub use ruled::{extrude, ruled};

use super::NurbsError;
use glam::DVec3;

/// Checks that a length is finite and > 0.
pub(crate) fn positive(what: &'static str, value: f64) -> Result<f64, NurbsError> {
    if value.is_finite() && value > 0.0 {
        Ok(value)
    } else {
        Err(NurbsError::InvalidGeometry {
            what,
            value,
            rule: "must be finite and > 0",
        })
    }
}

/// Checks that a point or vector has finite coordinates.
pub(crate) fn finite_vec(what: &'static str, v: DVec3) -> Result<DVec3, NurbsError> {
    if v.is_finite() {
        Ok(v)
    } else {
        let bad = [v.x, v.y, v.z]
            .into_iter()
            .find(|c| !c.is_finite())
            .unwrap_or(f64::NAN);
        Err(NurbsError::InvalidGeometry {
            what,
            value: bad,
            rule: "coordinates must be finite",
        })
    }
}

/// Checks that a direction is finite and not zero, and returns it normalized.
pub(crate) fn direction(what: &'static str, v: DVec3) -> Result<DVec3, NurbsError> {
    let v = finite_vec(what, v)?;
    let len = v.length();
    if len > 0.0 && len.is_finite() {
        Ok(v / len)
    } else {
        Err(NurbsError::InvalidGeometry {
            what,
            value: len,
            rule: "direction must have non-zero length",
        })
    }
}
