//! Skirt support of a vertical vessel: a cylinder or a frustum flared outwards at
//! the bottom, with an optional base ring (the bearing plate on the foundation).
//!
//! Local frame: the axis is +Z and the origin is on the axis at the base, z = 0. The
//! skirt's top, where it meets the vessel, is at z = `height` with outside diameter
//! `top_diameter`; a flared skirt widens downwards, so its bottom radius is
//! `top_diameter / 2 + height · tan(flare_angle)`. The base ring lies in the plane
//! z = 0 from the bottom radius outwards by `base_ring_width`.
//!
//! The skirt surface is the outside of the skirt plate; the base ring is modelled as
//! a sheet in the bearing plane. Plate thickness is carried as a parameter for later
//! use (weights, drawings, FEM) and does not change the surfaces.

use std::f64::consts::TAU;

use glam::DVec3;

use super::check::{in_range, less_than, non_negative, positive};
use super::{Analytic, PartError, Patch};
use crate::nurbs::builders::{line, revolve};

/// Parameters of a skirt (mm, degrees).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Skirt {
    /// Outside diameter at the top, where the skirt meets the vessel, mm.
    pub top_diameter: f64,
    /// Height from the base (z = 0) to the top, mm.
    pub height: f64,
    /// Angle between the skirt and the axis, degrees, 0 (straight) to 45 inclusive;
    /// a flared skirt widens downwards.
    pub flare_angle: f64,
    /// Plate thickness, mm; smaller than the top radius. Not used by the surfaces.
    pub thickness: f64,
    /// Radial width of the base ring outside the skirt's bottom edge, mm; 0 for none.
    pub base_ring_width: f64,
}

const PART: &str = "skirt";

impl Skirt {
    /// Checks the parameters: positive dimensions, flare angle in [0°, 45°],
    /// thickness below the top radius, base ring width 0 or positive.
    pub fn validate(&self) -> Result<(), PartError> {
        let top = positive(PART, "top_diameter", self.top_diameter)?;
        positive(PART, "height", self.height)?;
        in_range(PART, "flare_angle", self.flare_angle, 0.0, 45.0, false)?;
        let t = positive(PART, "thickness", self.thickness)?;
        less_than(PART, "thickness", t, top / 2.0, "half the top diameter")?;
        non_negative(PART, "base_ring_width", self.base_ring_width)?;
        Ok(())
    }

    /// Outside diameter at the base, mm: `top_diameter + 2 · height · tan(flare_angle)`.
    pub fn bottom_diameter(&self) -> f64 {
        self.top_diameter + 2.0 * self.height * self.flare_angle.to_radians().tan()
    }

    /// The exact patches: `"skirt"` (u around the axis counter-clockwise from +X, v
    /// from the base up; normal outward, away from the axis) and, if the base ring
    /// width is > 0, `"base ring"` (u as the skirt, so the two share their seam and
    /// their common circle has one parametrization; v from the skirt outwards;
    /// normal −Z, facing the foundation).
    pub fn patches(&self) -> Result<Vec<Patch>, PartError> {
        self.validate()?;
        let top = self.top_diameter / 2.0;
        let bottom = self.bottom_diameter() / 2.0;
        let h = self.height;
        let profile = line(DVec3::new(bottom, 0.0, 0.0), DVec3::new(top, 0.0, h))?;
        let skirt = revolve(&profile, DVec3::ZERO, DVec3::Z, TAU)?;
        let flare = bottom - top;
        let analytic = if flare > 0.0 {
            // The cone closes upwards: its apex is above the top, where r = 0.
            Analytic::Cone {
                apex: DVec3::new(0.0, 0.0, h + top * h / flare),
                axis: -DVec3::Z,
                half_angle: flare.atan2(h),
            }
        } else {
            Analytic::Cylinder {
                point: DVec3::ZERO,
                axis: DVec3::Z,
                radius: top,
            }
        };
        let mut out = vec![Patch::new("skirt", skirt, analytic)];
        if self.base_ring_width > 0.0 {
            let outer = bottom + self.base_ring_width;
            let profile = line(DVec3::new(bottom, 0.0, 0.0), DVec3::new(outer, 0.0, 0.0))?;
            out.push(Patch::new(
                "base ring",
                revolve(&profile, DVec3::ZERO, DVec3::Z, TAU)?,
                Analytic::Plane {
                    point: DVec3::ZERO,
                    normal: -DVec3::Z,
                },
            ));
        }
        Ok(out)
    }
}
