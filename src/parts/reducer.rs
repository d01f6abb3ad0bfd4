//! Conical reducer joining two shell courses of different diameters, concentric or
//! eccentric.
//!
//! Local frame: the axis of the large end is +Z, the origin is on it at the large
//! end, and the small end lies at z = `length`. A concentric reducer is a revolved
//! frustum. An eccentric reducer keeps one side straight: its small end is offset by
//! (D − d)/2 towards the flat side, and its surface is the ruled surface between the
//! two end circles — an exact oblique circular cone.

use std::f64::consts::TAU;

use glam::DVec3;

use super::check::{in_range, less_than, positive};
use super::{Analytic, PartError, Patch};
use crate::nurbs::builders::{circular_arc, line, revolve, ruled};

/// How the small end sits relative to the large end.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum ReducerAlignment {
    /// Both ends on one axis.
    Concentric,
    /// One generatrix parallel to the axis, on the side at `flat_side` degrees from +X
    /// (counter-clockwise about +Z).
    Eccentric {
        /// Plan angle of the flat side, degrees.
        flat_side: f64,
    },
}

/// Parameters of a conical reducer.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Reducer {
    /// Outside diameter at the large end (z = 0), mm.
    pub large_diameter: f64,
    /// Outside diameter at the small end (z = length), mm.
    pub small_diameter: f64,
    /// Axial length, mm.
    pub length: f64,
    /// Concentric or eccentric.
    pub alignment: ReducerAlignment,
}

const PART: &str = "conical reducer";

impl Reducer {
    /// Checks the parameters: positive dimensions, small end smaller than large end.
    pub fn validate(&self) -> Result<(), PartError> {
        let large = positive(PART, "large_diameter", self.large_diameter)?;
        let small = positive(PART, "small_diameter", self.small_diameter)?;
        less_than(PART, "small_diameter", small, large, "the large diameter")?;
        positive(PART, "length", self.length)?;
        if let ReducerAlignment::Eccentric { flat_side } = self.alignment {
            in_range(PART, "flat_side", flat_side, -360.0, 360.0, false)?;
        }
        Ok(())
    }

    /// Centre of the small end in the local frame.
    pub fn small_end_center(&self) -> DVec3 {
        let offset = match self.alignment {
            ReducerAlignment::Concentric => 0.0,
            ReducerAlignment::Eccentric { .. } => (self.large_diameter - self.small_diameter) / 2.0,
        };
        let angle = match self.alignment {
            ReducerAlignment::Concentric => 0.0,
            ReducerAlignment::Eccentric { flat_side } => flat_side.to_radians(),
        };
        DVec3::new(offset * angle.cos(), offset * angle.sin(), self.length)
    }

    /// Half-angle of the cone (between its axis and a generatrix for the concentric
    /// reducer; between the axis and the steepest generatrix for the eccentric one),
    /// degrees.
    pub fn half_angle(&self) -> f64 {
        let drop = self.large_diameter - self.small_diameter;
        let run = match self.alignment {
            ReducerAlignment::Concentric => drop / 2.0,
            ReducerAlignment::Eccentric { .. } => drop,
        };
        run.atan2(self.length).to_degrees()
    }

    /// The exact conical patch, u around the axis, v from the large to the small end;
    /// normals point outward.
    pub fn patches(&self) -> Result<Vec<Patch>, PartError> {
        self.validate()?;
        let r1 = self.large_diameter / 2.0;
        let r2 = self.small_diameter / 2.0;
        let l = self.length;
        let apex_fraction = r1 / (r1 - r2);
        let top = self.small_end_center();
        let apex = top * apex_fraction;
        let (surface, analytic) = match self.alignment {
            ReducerAlignment::Concentric => (
                revolve(
                    &line(DVec3::new(r1, 0.0, 0.0), DVec3::new(r2, 0.0, l))?,
                    DVec3::ZERO,
                    DVec3::Z,
                    TAU,
                )?,
                Analytic::Cone {
                    apex,
                    axis: -DVec3::Z,
                    half_angle: (r1 - r2).atan2(l),
                },
            ),
            ReducerAlignment::Eccentric { .. } => {
                // Both end circles start on +X, as a course's do, so that the
                // reducer's end edges are the very curves of the courses it
                // joins (sampled alike: the vessel stays closed whichever way
                // the flat side faces). Points of equal angle on the two
                // circles lie on one generatrix through the apex.
                let large = circular_arc(DVec3::ZERO, DVec3::X, DVec3::Y, r1, 0.0, TAU)?;
                let small = circular_arc(top, DVec3::X, DVec3::Y, r2, 0.0, TAU)?;
                (
                    ruled(&large, &small)?,
                    Analytic::ObliqueCone {
                        apex,
                        base_center: DVec3::ZERO,
                        base_normal: DVec3::Z,
                        radius: r1,
                    },
                )
            }
        };
        Ok(vec![Patch::new("cone", surface, analytic)])
    }
}
