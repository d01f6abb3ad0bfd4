//! Boot: a small vertical drum under a horizontal vessel, where water or heavy
//! liquid collects, closed at its far end by a head.
//!
//! Local frame: the boot axis is +Z pointing away from the host vessel (the
//! placement turns it downwards), and the origin is on the boot axis at the host's
//! axis. The boot cylinder runs from z = 0, inside the host, to its tangent line at
//! z = host radius + `length`; the part of it inside the host is trimmed off by the
//! host–boot intersection, cut exactly like a nozzle neck (`mesh::cut_opening`):
//! the host course gets the matching hole. Beyond the tangent line the head
//! (any [`HeadKind`], 2:1 ellipsoidal by default) closes the boot.
//!
//! The surfaces are the outsides of the boot and its head; plate thicknesses are
//! not modelled here.

use std::f64::consts::TAU;

use glam::{DAffine3, DVec3};

use super::check::{less_than, positive};
use super::heads::{Head, HeadKind};
use super::{Analytic, PartError, Patch};
use crate::nurbs::builders::{line, revolve};

/// Parameters of a boot (mm).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Boot {
    /// Outside diameter of the boot, mm; smaller than the host's.
    pub diameter: f64,
    /// Length of the boot cylinder outside the host, from the host's outside
    /// radius (measured along the boot axis) to the boot head's tangent line, mm.
    pub length: f64,
    /// Kind of the head closing the boot.
    pub head: HeadKind,
    /// Outside diameter of the host vessel's shell, mm.
    pub host_diameter: f64,
}

const PART: &str = "boot";

impl Boot {
    /// A boot closed by a 2:1 ellipsoidal head.
    pub fn new(diameter: f64, length: f64, host_diameter: f64) -> Self {
        Self {
            diameter,
            length,
            head: HeadKind::TWO_TO_ONE,
            host_diameter,
        }
    }

    /// The same boot closed by a head of `kind`.
    pub fn with_head(mut self, kind: HeadKind) -> Self {
        self.head = kind;
        self
    }

    /// Checks the parameters: positive dimensions, boot smaller than the host, and
    /// the head's own rules (its errors name the head, e.g. `"torispherical head"`).
    pub fn validate(&self) -> Result<(), PartError> {
        let d = positive(PART, "diameter", self.diameter)?;
        positive(PART, "length", self.length)?;
        let host = positive(PART, "host_diameter", self.host_diameter)?;
        less_than(PART, "diameter", d, host, "the host diameter")?;
        self.head_part().validate()
    }

    /// Height of the boot head's tangent line above the host axis: host radius +
    /// `length`, mm.
    pub fn tangent_line(&self) -> f64 {
        self.host_diameter / 2.0 + self.length
    }

    /// The head closing the boot, in its own frame (open end at its origin).
    pub fn head_part(&self) -> Head {
        Head::new(self.diameter, self.head)
    }

    /// The exact patches: `"boot shell"`, the cylinder from z = 0 to the tangent
    /// line (u counter-clockwise about +Z from +X, v along +Z, normal outward), then
    /// the head's patches (named as in [`Head::patches`]) moved up to the tangent
    /// line. All share the seam at +X and one u parametrization, so the boot shell's
    /// top edge is the first head patch's bottom edge.
    pub fn patches(&self) -> Result<Vec<Patch>, PartError> {
        self.validate()?;
        let r = self.diameter / 2.0;
        let top = self.tangent_line();
        let profile = line(DVec3::new(r, 0.0, 0.0), DVec3::new(r, 0.0, top))?;
        let mut out = vec![Patch::new(
            "boot shell",
            revolve(&profile, DVec3::ZERO, DVec3::Z, TAU)?,
            Analytic::Cylinder {
                point: DVec3::ZERO,
                axis: DVec3::Z,
                radius: r,
            },
        )];
        let offset = DVec3::Z * top;
        let lift = DAffine3::from_translation(offset);
        for patch in self.head_part().patches()? {
            out.push(Patch {
                surface: patch.surface.transformed(&lift)?,
                analytic: patch.analytic.transformed(&lift),
                ..patch
            });
        }
        Ok(out)
    }
}
