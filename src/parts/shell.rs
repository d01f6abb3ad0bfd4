//! Cylindrical shell course: one exact cylinder patch.
//!
//! Local frame: the axis is +Z, the origin is on the axis at the bottom (or left)
//! end of the course; the course runs from z = 0 to z = `length`.

use std::f64::consts::TAU;

use glam::DVec3;

use super::check::positive;
use super::{Analytic, PartError, Patch};
use crate::nurbs::builders::{line, revolve};

/// Parameters of a cylindrical shell course.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Shell {
    /// Outside diameter, mm.
    pub outside_diameter: f64,
    /// Length along the axis, mm.
    pub length: f64,
}

const PART: &str = "shell";

impl Shell {
    /// Checks the parameters: both finite and > 0.
    pub fn validate(&self) -> Result<(), PartError> {
        positive(PART, "outside_diameter", self.outside_diameter)?;
        positive(PART, "length", self.length)?;
        Ok(())
    }

    /// The exact cylinder: u around the axis (counter-clockwise from +X), v along +Z;
    /// normals point outward.
    pub fn patches(&self) -> Result<Vec<Patch>, PartError> {
        self.validate()?;
        let r = self.outside_diameter / 2.0;
        let profile = line(DVec3::new(r, 0.0, 0.0), DVec3::new(r, 0.0, self.length))?;
        let surface = revolve(&profile, DVec3::ZERO, DVec3::Z, TAU)?;
        Ok(vec![Patch::new(
            "shell",
            surface,
            Analytic::Cylinder {
                point: DVec3::ZERO,
                axis: DVec3::Z,
                radius: r,
            },
        )])
    }
}
