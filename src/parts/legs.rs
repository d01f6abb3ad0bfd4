//! Pipe legs of a vertical vessel: `count` vertical pipes equally spaced around the
//! shell, each standing on a square base plate.
//!
//! Local frame: the vessel axis is +Z and the origin is on it at floor level; every
//! leg runs from z = 0 up to z = `length`. Leg k (1-based) has its axis at plan angle
//! `first_angle + (k − 1) · 360° / count`, counter-clockwise from +X about +Z, at the
//! distance `shell_diameter / 2 + pipe_diameter / 2` from the vessel axis, so each
//! pipe touches the shell's outside circle along one line.
//!
//! The pipe surface is the pipe's outside; the base plate is a sheet in the floor
//! plane (thickness is not modelled). Patches are named `"leg"` and
//! `"leg base plate"` with [`Patch::index`] = the leg's number k.

use std::f64::consts::TAU;

use glam::{DVec2, DVec3};

use super::check::{in_range, invalid, positive};
use super::{Analytic, PartError, Patch};
use crate::nurbs::builders::{line, planar_quad, revolve};

/// Most legs a vessel may have (bounds the work and the patch count).
pub const MAX_LEGS: u32 = 32;

/// Parameters of a set of pipe legs (mm, degrees).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Legs {
    /// Number of legs, 3 to [`MAX_LEGS`].
    pub count: u32,
    /// Outside diameter of the leg pipe, mm.
    pub pipe_diameter: f64,
    /// Length of each leg from the floor (z = 0) up, mm.
    pub length: f64,
    /// Outside diameter of the shell the legs touch, mm.
    pub shell_diameter: f64,
    /// Plan angle of leg 1, degrees counter-clockwise from +X, −360 to 360.
    pub first_angle: f64,
}

const PART: &str = "legs";

impl Legs {
    /// Checks the parameters: positive dimensions, 3 ≤ count ≤ [`MAX_LEGS`], the
    /// first angle within ±360°, and neighbouring base plates apart (they are squares
    /// of side 2 × `pipe_diameter`; too many or too thick legs make them overlap).
    pub fn validate(&self) -> Result<(), PartError> {
        in_range(
            PART,
            "count",
            self.count.into(),
            3.0,
            MAX_LEGS.into(),
            false,
        )?;
        positive(PART, "pipe_diameter", self.pipe_diameter)?;
        positive(PART, "length", self.length)?;
        positive(PART, "shell_diameter", self.shell_diameter)?;
        in_range(PART, "first_angle", self.first_angle, -360.0, 360.0, false)?;
        let spacing = TAU / f64::from(self.count);
        let center = DVec2::new(self.axis_radius(), 0.0);
        let half = self.pipe_diameter;
        if squares_overlap(
            center,
            0.0,
            DVec2::from_angle(spacing).rotate(center),
            spacing,
            half,
        ) {
            return Err(invalid(
                PART,
                "count",
                self.count.into(),
                format!(
                    "neighbouring base plates ({} mm squares) would overlap: use fewer or \
                     thinner legs",
                    2.0 * half
                ),
            ));
        }
        Ok(())
    }

    /// Distance from the vessel axis to each leg's axis: shell radius + pipe radius, mm.
    pub fn axis_radius(&self) -> f64 {
        (self.shell_diameter + self.pipe_diameter) / 2.0
    }

    /// Plan angle of leg `k` (1-based), radians counter-clockwise from +X.
    fn angle(&self, k: u32) -> f64 {
        self.first_angle.to_radians() + TAU * f64::from(k - 1) / f64::from(self.count)
    }

    /// The points where the leg axes meet the floor (z = 0), leg 1 first; the
    /// parameters are validated first.
    pub fn axis_points(&self) -> Result<Vec<DVec3>, PartError> {
        self.validate()?;
        Ok((1..=self.count)
            .map(|k| {
                let (s, c) = self.angle(k).sin_cos();
                DVec3::new(c, s, 0.0) * self.axis_radius()
            })
            .collect())
    }

    /// The exact patches, two per leg in leg order: `"leg"`, the pipe cylinder (u
    /// around the pipe axis counter-clockwise, starting on the line where it touches
    /// the shell; v up; normal outward from the pipe axis), and `"leg base plate"`, a
    /// square of side 2 × `pipe_diameter` centred on the pipe axis at z = 0 with edges
    /// along the radial and tangential directions (normal −Z, facing the floor).
    pub fn patches(&self) -> Result<Vec<Patch>, PartError> {
        self.validate()?;
        let r = self.pipe_diameter / 2.0;
        let d = self.pipe_diameter;
        let mut out = Vec::with_capacity(2 * self.count as usize);
        for k in 1..=self.count {
            let (s, c) = self.angle(k).sin_cos();
            let radial = DVec3::new(c, s, 0.0);
            let tangential = DVec3::new(-s, c, 0.0);
            let axis = radial * self.axis_radius();
            let contact = axis - radial * r;
            let profile = line(contact, contact + DVec3::Z * self.length)?;
            out.push(
                Patch::new(
                    "leg",
                    revolve(&profile, axis, DVec3::Z, TAU)?,
                    Analytic::Cylinder {
                        point: axis,
                        axis: DVec3::Z,
                        radius: r,
                    },
                )
                .with_index(k),
            );
            // u along the tangent, v along the radius: t × r = −Z.
            let corner = axis - (radial + tangential) * d;
            let plate = planar_quad(
                corner,
                corner + tangential * (2.0 * d),
                corner + radial * (2.0 * d),
                corner + (radial + tangential) * (2.0 * d),
            )?;
            out.push(
                Patch::new(
                    "leg base plate",
                    plate,
                    Analytic::Plane {
                        point: axis,
                        normal: -DVec3::Z,
                    },
                )
                .with_index(k),
            );
        }
        Ok(out)
    }
}

/// Whether two squares of half-side `half`, centred at `a` and `b` and turned by
/// `turn_a` and `turn_b` radians, overlap or touch (separating-axis test).
fn squares_overlap(a: DVec2, turn_a: f64, b: DVec2, turn_b: f64, half: f64) -> bool {
    let axes_a = [DVec2::from_angle(turn_a), DVec2::from_angle(turn_a).perp()];
    let axes_b = [DVec2::from_angle(turn_b), DVec2::from_angle(turn_b).perp()];
    let reach = |axes: &[DVec2; 2], n: DVec2| half * (axes[0].dot(n).abs() + axes[1].dot(n).abs());
    !axes_a
        .iter()
        .chain(&axes_b)
        .any(|&n| (b - a).dot(n).abs() > reach(&axes_a, n) + reach(&axes_b, n))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn square_overlap_separating_axes() {
        let a = DVec2::ZERO;
        assert!(squares_overlap(a, 0.0, DVec2::new(1.9, 0.0), 0.0, 1.0));
        assert!(!squares_overlap(a, 0.0, DVec2::new(2.1, 0.0), 0.0, 1.0));
        // A diamond's corner reaches √2 from its centre.
        let turn = std::f64::consts::FRAC_PI_4;
        assert!(squares_overlap(a, 0.0, DVec2::new(2.3, 0.0), turn, 1.0));
        assert!(!squares_overlap(a, 0.0, DVec2::new(2.5, 0.0), turn, 1.0));
    }
}
