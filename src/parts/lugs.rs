//! Support lugs of a vertical vessel: `count` brackets equally spaced around the
//! shell, each a horizontal bearing plate between two vertical gussets.
//!
//! Local frame: the vessel axis is +Z and the origin is on it in the bearing plane
//! (the underside of the bearing plates, which rests on the supporting steel),
//! z = 0. Lug k (1-based) is centred at plan angle `first_angle + (k − 1) · 360° /
//! count`, counter-clockwise from +X about +Z. In the lug's own plan directions —
//! radial r and tangential t (r turned 90° counter-clockwise) — its gussets lie in
//! the planes t = ±`width`/2, parallel to r, from the shell outwards to
//! r = shell radius + `projection`, and from z = 0 up to z = `height`. The bearing
//! plate fills the space between them at z = 0: its inner edge is the arc of the
//! shell circle between the gussets, its outer edge the straight line at
//! r = shell radius + `projection`.
//!
//! Plates are modelled as sheets (mid-planes of the gussets, underside of the
//! bearing plate); thicknesses are not modelled here. Patches are named
//! `"lug bearing plate"`, `"lug gusset cw"` and `"lug gusset ccw"` with
//! [`Patch::index`] = the lug's number k.

use std::f64::consts::PI;

use glam::DVec3;

use super::check::{in_range, less_than, positive};
use super::{Analytic, PartError, Patch};
use crate::nurbs::builders::{circular_arc, line, planar_quad, ruled};

/// Most lugs a vessel may have (bounds the work and the patch count).
pub const MAX_LUGS: u32 = 32;

/// Parameters of a set of support lugs (mm, degrees).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Lugs {
    /// Number of lugs, 2 to [`MAX_LUGS`].
    pub count: u32,
    /// Outside diameter of the shell the lugs are welded to, mm.
    pub shell_diameter: f64,
    /// Height of the gussets above the bearing plane, mm.
    pub height: f64,
    /// Radial projection of the lug beyond the shell's outside radius, mm.
    pub projection: f64,
    /// Tangential gap between the two gussets, mm; less than
    /// `shell_diameter · sin(180° / count)` so neighbouring lugs stay apart.
    pub width: f64,
    /// Plan angle of lug 1, degrees counter-clockwise from +X, −360 to 360.
    pub first_angle: f64,
}

const PART: &str = "lugs";

impl Lugs {
    /// Checks the parameters: positive dimensions, 2 ≤ count ≤ [`MAX_LUGS`], the
    /// first angle within ±360°, and `width < shell_diameter · sin(180° / count)`
    /// (the gussets meet the shell, and neighbouring lugs do not touch).
    pub fn validate(&self) -> Result<(), PartError> {
        in_range(
            PART,
            "count",
            self.count.into(),
            2.0,
            MAX_LUGS.into(),
            false,
        )?;
        let d = positive(PART, "shell_diameter", self.shell_diameter)?;
        positive(PART, "height", self.height)?;
        positive(PART, "projection", self.projection)?;
        let w = positive(PART, "width", self.width)?;
        in_range(PART, "first_angle", self.first_angle, -360.0, 360.0, false)?;
        let limit = d * (PI / f64::from(self.count)).sin();
        less_than(
            PART,
            "width",
            w,
            limit,
            "shell_diameter · sin(180° / count), where neighbouring lugs touch",
        )?;
        Ok(())
    }

    /// Plan angle of lug `k` (1-based), radians counter-clockwise from +X.
    fn angle(&self, k: u32) -> f64 {
        self.first_angle.to_radians() + 2.0 * PI * f64::from(k - 1) / f64::from(self.count)
    }

    /// The exact patches, three per lug in lug order:
    /// - `"lug bearing plate"`: u along the shell arc counter-clockwise, v from the
    ///   shell out to the outer edge; normal −Z (the load-bearing underside).
    /// - `"lug gusset cw"` (at t = −width/2): u radially outwards, v up; normal −t.
    /// - `"lug gusset ccw"` (at t = +width/2): u radially inwards, v up; normal +t.
    ///
    /// So every gusset's normal faces away from the gap between the gussets, and the
    /// bearing plate's side edges are the gussets' bottom edges.
    pub fn patches(&self) -> Result<Vec<Patch>, PartError> {
        self.validate()?;
        let r = self.shell_diameter / 2.0;
        let half = self.width / 2.0;
        let outer = r + self.projection;
        let inner = (r * r - half * half).sqrt();
        let up = DVec3::Z * self.height;
        let reach = (half / r).asin();
        let mut out = Vec::with_capacity(3 * self.count as usize);
        for k in 1..=self.count {
            let (s, c) = self.angle(k).sin_cos();
            let radial = DVec3::new(c, s, 0.0);
            let tangential = DVec3::new(-s, c, 0.0);
            let arc = circular_arc(DVec3::ZERO, radial, tangential, r, -reach, reach)?;
            let edge = line(
                radial * outer - tangential * half,
                radial * outer + tangential * half,
            )?;
            out.push(
                Patch::new(
                    "lug bearing plate",
                    ruled(&arc, &edge)?,
                    Analytic::Plane {
                        point: DVec3::ZERO,
                        normal: -DVec3::Z,
                    },
                )
                .with_index(k),
            );
            for (name, side) in [("lug gusset cw", -1.0), ("lug gusset ccw", 1.0)] {
                let a = radial * inner + tangential * (side * half);
                let b = radial * outer + tangential * (side * half);
                // (b − a) × Z = −t: run outwards on the cw side, inwards on the ccw.
                let (start, end) = if side < 0.0 { (a, b) } else { (b, a) };
                let sheet = planar_quad(start, end, start + up, end + up)?;
                out.push(
                    Patch::new(
                        name,
                        sheet,
                        Analytic::Plane {
                            point: a,
                            normal: tangential * side,
                        },
                    )
                    .with_index(k),
                );
            }
        }
        Ok(out)
    }
}
