//! Saddle support of a horizontal vessel: a wear plate on the shell, a vertical web
//! and a base plate on the foundation.
//!
//! Local frame: the vessel's frame — the vessel axis is +Z, the origin is on it in
//! the saddle's mid-plane (the plane of the web, z = 0), and local −Y is down. The
//! base plate's underside, the bearing plane on the foundation, is the plane
//! y = −`height`; across the vessel is ±X.
//!
//! Plates are modelled as sheets and their thicknesses are carried as parameters
//! for later use (weights, drawings, FEM): the wear plate is the strip of the shell's
//! outside cylinder it covers, the web is its mid-plane z = 0, and the base plate is
//! the bearing plane. The web sheet meets the wear plate along the contact arc (the
//! middle line of the wear strip) and the base plate along the middle line of the
//! base rectangle.

use std::f64::consts::FRAC_PI_2;

use glam::DVec3;

use super::check::{in_range, invalid, less_than, positive};
use super::{Analytic, PartError, Patch};
use crate::nurbs::builders::{circular_arc, extrude, line, planar_quad, ruled};

/// Parameters of a saddle (mm, degrees).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Saddle {
    /// Outside diameter of the shell the saddle carries, mm.
    pub shell_diameter: f64,
    /// Angle of shell the saddle wraps, symmetric about −Y, degrees, 120 to 150
    /// (the range used in practice; the thesis's unused `si_an` rule, 2–120°, is
    /// not followed).
    pub contact_angle: f64,
    /// Width of the wear plate along the vessel axis, mm.
    pub width: f64,
    /// Distance from the vessel axis down to the bearing plane, mm; more than the
    /// shell radius.
    pub height: f64,
    /// Web thickness, mm; smaller than `width` and `base_width`. Not used by the
    /// surfaces.
    pub web_thickness: f64,
    /// Length of the base plate across the vessel (along X), mm; at least the chord
    /// of the contact arc, so the web's sides are vertical or splay outwards.
    pub base_length: f64,
    /// Width of the base plate along the vessel axis, mm.
    pub base_width: f64,
    /// Base plate thickness, mm; smaller than the clearance `height − shell radius`.
    /// Not used by the surfaces.
    pub base_thickness: f64,
}

const PART: &str = "saddle";

impl Saddle {
    /// Checks the parameters: positive dimensions, contact angle in [120°, 150°],
    /// height above the shell radius, base at least as long as the contact chord,
    /// the web thinner than both plates it joins, the base plate thinner than the
    /// clearance below the shell.
    pub fn validate(&self) -> Result<(), PartError> {
        let d = positive(PART, "shell_diameter", self.shell_diameter)?;
        in_range(
            PART,
            "contact_angle",
            self.contact_angle,
            120.0,
            150.0,
            false,
        )?;
        let width = positive(PART, "width", self.width)?;
        let height = positive(PART, "height", self.height)?;
        if height <= d / 2.0 {
            return Err(invalid(
                PART,
                "height",
                height,
                format!("must exceed the shell radius ({})", d / 2.0),
            ));
        }
        let web = positive(PART, "web_thickness", self.web_thickness)?;
        let base_length = positive(PART, "base_length", self.base_length)?;
        let base_width = positive(PART, "base_width", self.base_width)?;
        let base_thickness = positive(PART, "base_thickness", self.base_thickness)?;
        let chord = self.chord();
        if base_length < chord {
            return Err(invalid(
                PART,
                "base_length",
                base_length,
                format!("must be at least the chord of the contact arc ({chord})"),
            ));
        }
        less_than(PART, "web_thickness", web, width, "the width")?;
        less_than(PART, "web_thickness", web, base_width, "the base width")?;
        less_than(
            PART,
            "base_thickness",
            base_thickness,
            height - d / 2.0,
            "the clearance height − shell radius",
        )?;
        Ok(())
    }

    /// Chord of the contact arc, mm: `shell_diameter · sin(contact_angle / 2)`.
    pub fn chord(&self) -> f64 {
        self.shell_diameter * (self.contact_angle.to_radians() / 2.0).sin()
    }

    /// The exact patches:
    /// - `"wear plate"`: the strip of the shell cylinder over the contact angle, from
    ///   z = −width/2 to width/2; u along the arc counter-clockwise about +Z (towards
    ///   +X at the bottom), v along +Z; normal outward, away from the vessel axis.
    /// - `"web"`: the planar sheet in z = 0 between the straight base edge (v = 0, at
    ///   y = −height, from x = −base_length/2 to base_length/2) and the contact arc
    ///   (v = 1); its sides are the straight lines joining their ends; normal +Z.
    /// - `"base plate"`: the rectangle base_length × base_width in y = −height,
    ///   centred under the axis; normal −Y, facing the foundation.
    pub fn patches(&self) -> Result<Vec<Patch>, PartError> {
        self.validate()?;
        let r = self.shell_diameter / 2.0;
        let half_sweep = self.contact_angle.to_radians() / 2.0;
        let (h, l, w, bw) = (self.height, self.base_length, self.width, self.base_width);
        let contact = |z: f64| {
            circular_arc(
                DVec3::new(0.0, 0.0, z),
                DVec3::X,
                DVec3::Y,
                r,
                -FRAC_PI_2 - half_sweep,
                -FRAC_PI_2 + half_sweep,
            )
        };
        let wear = extrude(&contact(-w / 2.0)?, DVec3::new(0.0, 0.0, w))?;
        let arc = contact(0.0)?;
        let base_edge = line(DVec3::new(-l / 2.0, -h, 0.0), DVec3::new(l / 2.0, -h, 0.0))?;
        let web = ruled(&base_edge, &arc)?;
        let corner = DVec3::new(-l / 2.0, -h, -bw / 2.0);
        let base = planar_quad(
            corner,
            corner + DVec3::X * l,
            corner + DVec3::Z * bw,
            corner + DVec3::new(l, 0.0, bw),
        )?;
        Ok(vec![
            Patch::new(
                "wear plate",
                wear,
                Analytic::Cylinder {
                    point: DVec3::ZERO,
                    axis: DVec3::Z,
                    radius: r,
                },
            ),
            Patch::new(
                "web",
                web,
                Analytic::Plane {
                    point: DVec3::ZERO,
                    normal: DVec3::Z,
                },
            ),
            Patch::new(
                "base plate",
                base,
                Analytic::Plane {
                    point: DVec3::new(0.0, -h, 0.0),
                    normal: -DVec3::Y,
                },
            ),
        ])
    }
}
