//! Clearances between nozzles and supports: an opening (the neck's or pad's
//! footprint on its host) or a nozzle body (neck, flange) may not reach into a
//! support — a saddle's wear plate (its horns, the plate's ends at the contact
//! angle, included), web or base plate, a skirt's attachment line or plate, a
//! leg, a lug. `footprints` and `clearances` see openings and nozzles only.
//!
//! Each support is taken as the solids it is made of, in the vessel frame:
//!
//! - a **saddle**'s wear plate is the strip of the shell's outside cylinder it
//!   covers (the contact arc about −Y, its width along the axis); an opening's
//!   footprint ball overlaps it when the ball's centre is nearer the strip than
//!   its radius (the strip point nearest a point is the clamp of its angle and
//!   its axial position, exact). Its web (its plane, as thick as the web, from
//!   the horns' height down) and base plate are boxes;
//! - a **skirt** is welded to the bottom course along its top circle: a
//!   footprint reaching that circle overlaps the weld. A body parallel to the
//!   axis (a bottom-head nozzle) meets the skirt plate when, at the top of their
//!   common height, it reaches past the plate's inside (exact for a cylinder
//!   parallel to the axis: its distances from the axis are the same interval at
//!   every height). The design format has no skirt access openings yet;
//! - a **leg** is its pipe, a solid cylinder; a **lug** the box holding its
//!   gussets and bearing plate, from where its gussets meet the shell out to its
//!   projection.
//!
//! Boxes, cylinders and balls meet by `clearances::meet` (alternating
//! projections, exact for convex solids). Touching is allowed.

use std::f64::consts::{FRAC_PI_2, TAU};

use glam::{DAffine3, DVec3};

use super::ResolvedPart;
use super::clearances::{Ball, Block, Body, Convex, meet};
use super::footprints::Footprint;
use crate::format::VesselDesign;
use crate::parts::PartGeometry;

/// A piece of a support as a convex solid.
#[derive(Clone, Copy, Debug)]
enum Solid {
    Cylinder(Body),
    Box(Block),
}

impl Solid {
    fn convex(&self) -> &dyn Convex {
        match self {
            Solid::Cylinder(b) => b,
            Solid::Box(b) => b,
        }
    }
}

/// A saddle's wear plate: the strip of the cylinder of `radius` about the
/// saddle frame's Z within `half_angle` of −Y and `half_width` of z = 0.
#[derive(Clone, Copy, Debug)]
struct WearPlate {
    to_local: DAffine3,
    radius: f64,
    half_angle: f64,
    half_width: f64,
}

impl WearPlate {
    /// Distance from `p` (vessel frame) to the strip.
    fn distance(&self, p: DVec3) -> f64 {
        let q = self.to_local.transform_point3(p);
        let rho = q.x.hypot(q.y);
        // Angle from −Y, in (−π, π].
        let from_down = (q.y.atan2(q.x) + FRAC_PI_2 + TAU).rem_euclid(TAU);
        let from_down = if from_down > TAU / 2.0 {
            from_down - TAU
        } else {
            from_down
        };
        let off = (from_down.abs() - self.half_angle).max(0.0);
        let dz = (q.z.abs() - self.half_width).max(0.0);
        let across =
            (rho * rho + self.radius * self.radius - 2.0 * rho * self.radius * off.cos()).max(0.0);
        (across + dz * dz).sqrt()
    }
}

/// A skirt: its top circle (where it is welded to the vessel) and its plate.
#[derive(Clone, Copy, Debug)]
struct SkirtShell {
    to_local: DAffine3,
    axis: DVec3,
    /// Height of the top above the base, the top's outside radius, the plate's
    /// horizontal thickness and the flare's tangent.
    height: f64,
    top_radius: f64,
    thickness: f64,
    flare: f64,
}

impl SkirtShell {
    /// Distance from `p` (vessel frame) to the top circle.
    fn weld_distance(&self, p: DVec3) -> f64 {
        let q = self.to_local.transform_point3(p);
        (q.x.hypot(q.y) - self.top_radius).hypot(q.z - self.height)
    }

    /// Whether `body`, parallel to the skirt's axis, reaches into its plate.
    fn holds(&self, body: &Body) -> bool {
        if body.axis.cross(self.axis).length() > 1e-9 {
            return false;
        }
        let a = self
            .to_local
            .transform_point3(body.origin + body.axis * body.from);
        let b = self
            .to_local
            .transform_point3(body.origin + body.axis * body.to);
        let (lo, hi) = (a.z.min(b.z).max(0.0), a.z.max(b.z).min(self.height));
        if lo > hi {
            return false;
        }
        let d = a.x.hypot(a.y);
        // The plate widens downwards: its inside is nearest the axis at `hi`,
        // its outside farthest at `lo`.
        let outside = |z: f64| self.top_radius + (self.height - z) * self.flare;
        d + body.radius > outside(hi) - self.thickness && d - body.radius < outside(lo)
    }
}

/// What a nozzle must keep clear of one support.
#[derive(Clone, Debug)]
pub(crate) struct Support {
    /// Its JSON path in the vessel: `parts[3].saddle`.
    pub path: String,
    /// For messages: `saddle SD1`.
    pub name: String,
    solids: Vec<(String, Solid)>,
    wear_plate: Option<WearPlate>,
    skirt: Option<SkirtShell>,
}

impl Support {
    fn new(vessel: &VesselDesign, index: usize, part: &ResolvedPart) -> Self {
        let kind = vessel.parts[index].kind();
        Self {
            path: format!("parts[{index}].{kind}"),
            name: format!("{kind} {}", part.id),
            solids: Vec::new(),
            wear_plate: None,
            skirt: None,
        }
    }

    /// The piece of this support that a nozzle's opening `footprint` or one of
    /// its `bodies` reaches into, with what of the nozzle does: `("opening",
    /// "wear plate")`, `("flange", "leg 2")`; `None` when the nozzle clears it.
    pub fn clash(&self, footprint: &Footprint, bodies: &[Body]) -> Option<(&'static str, String)> {
        let ball = Ball {
            centre: footprint.centre,
            radius: footprint.radius,
        };
        if let Some(w) = &self.wear_plate
            && w.distance(ball.centre) < ball.radius
        {
            return Some((
                "opening",
                "wear plate (the strip it covers, horns included)".into(),
            ));
        }
        if let Some(s) = &self.skirt {
            if s.weld_distance(ball.centre) < ball.radius {
                return Some(("opening", "attachment line (its weld to the vessel)".into()));
            }
            if let Some(body) = bodies.iter().find(|b| s.holds(b)) {
                return Some((body.name, "plate".into()));
            }
        }
        for (piece, solid) in &self.solids {
            if meet(&ball, solid.convex()) {
                return Some(("opening", piece.clone()));
            }
            if let Some(body) = bodies.iter().find(|b| meet(*b, solid.convex())) {
                return Some((body.name, piece.clone()));
            }
        }
        None
    }
}

/// The supports of a vessel's resolved `parts` (saddles, skirt, legs, lugs).
pub(crate) fn supports(vessel: &VesselDesign, parts: &[Option<ResolvedPart>]) -> Vec<Support> {
    let mut out = Vec::new();
    for (index, part) in parts.iter().enumerate() {
        let Some(part) = part else { continue };
        let frame = part.frame;
        let mut support = Support::new(vessel, index, part);
        match &part.geometry {
            PartGeometry::Saddle(s) => {
                let radius = s.shell_diameter / 2.0;
                let half_angle = (s.contact_angle.to_radians() / 2.0).min(FRAC_PI_2);
                let horn = -radius * half_angle.cos();
                support.wear_plate = Some(WearPlate {
                    to_local: frame.inverse(),
                    radius,
                    half_angle,
                    half_width: s.width / 2.0,
                });
                let axes = [DVec3::X, DVec3::Y, DVec3::Z].map(|a| frame.matrix3 * a);
                let block = |y0: f64, y1: f64, half_z: f64| {
                    Solid::Box(Block {
                        centre: frame.transform_point3(DVec3::new(0.0, 0.5 * (y0 + y1), 0.0)),
                        axes,
                        half: [s.base_length / 2.0, 0.5 * (y1 - y0), half_z],
                    })
                };
                support
                    .solids
                    .push(("web".into(), block(-s.height, horn, s.web_thickness / 2.0)));
                support.solids.push((
                    "base plate".into(),
                    block(-s.height, -s.height + s.base_thickness, s.base_width / 2.0),
                ));
            }
            PartGeometry::Skirt(s) => {
                let flare = s.flare_angle.to_radians();
                support.skirt = Some(SkirtShell {
                    to_local: frame.inverse(),
                    axis: frame.matrix3 * DVec3::Z,
                    height: s.height,
                    top_radius: s.top_diameter / 2.0,
                    thickness: s.thickness / flare.cos(),
                    flare: flare.tan(),
                });
            }
            PartGeometry::Legs(l) => {
                let at = l.shell_diameter / 2.0 + l.pipe_diameter / 2.0;
                for k in 0..l.count {
                    let a =
                        (l.first_angle + f64::from(k) * 360.0 / f64::from(l.count)).to_radians();
                    support.solids.push((
                        format!("leg {}", k + 1),
                        Solid::Cylinder(Body {
                            name: "leg",
                            origin: frame.transform_point3(DVec3::new(
                                at * a.cos(),
                                at * a.sin(),
                                0.0,
                            )),
                            axis: frame.matrix3 * DVec3::Z,
                            from: 0.0,
                            to: l.length,
                            radius: l.pipe_diameter / 2.0,
                        }),
                    ));
                }
            }
            PartGeometry::Lugs(l) => {
                let radius = l.shell_diameter / 2.0;
                let half_t = l.width / 2.0;
                let inner = (radius * radius - half_t * half_t).max(0.0).sqrt();
                let outer = radius + l.projection;
                for k in 0..l.count {
                    let a =
                        (l.first_angle + f64::from(k) * 360.0 / f64::from(l.count)).to_radians();
                    let (r, t) = (
                        DVec3::new(a.cos(), a.sin(), 0.0),
                        DVec3::new(-a.sin(), a.cos(), 0.0),
                    );
                    let centre = r * (0.5 * (inner + outer)) + DVec3::Z * (0.5 * l.height);
                    support.solids.push((
                        format!("lug {}", k + 1),
                        Solid::Box(Block {
                            centre: frame.transform_point3(centre),
                            axes: [r, t, DVec3::Z].map(|v| frame.matrix3 * v),
                            half: [0.5 * (outer - inner), half_t, 0.5 * l.height],
                        }),
                    ));
                }
            }
            _ => continue,
        }
        out.push(support);
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_wear_plate_distance_is_exact_on_its_cylinder() {
        let w = WearPlate {
            to_local: DAffine3::IDENTITY,
            radius: 1000.0,
            half_angle: 60f64.to_radians(),
            half_width: 150.0,
        };
        // On the plate: at the bottom, and at a horn.
        assert!(w.distance(DVec3::new(0.0, -1000.0, 0.0)) < 1e-9);
        let horn = DVec3::new(1000.0 * 60f64.to_radians().sin(), -500.0, 150.0);
        assert!(w.distance(horn) < 1e-9);
        // Beside it along the axis, and round the shell past a horn.
        assert!((w.distance(DVec3::new(0.0, -1000.0, 250.0)) - 100.0).abs() < 1e-9);
        let past = 70f64.to_radians();
        let p = DVec3::new(1000.0 * past.sin(), -1000.0 * past.cos(), 0.0);
        let chord = 2.0 * 1000.0 * (10f64.to_radians() / 2.0).sin();
        assert!((w.distance(p) - chord).abs() < 1e-9);
        // On top of the shell: 120° past either horn.
        let top = 2.0 * 1000.0 * 60f64.to_radians().sin();
        assert!((w.distance(DVec3::new(0.0, 1000.0, 0.0)) - top).abs() < 1e-9);
    }

    #[test]
    fn a_skirt_holds_axial_bodies_reaching_its_plate() {
        let skirt = SkirtShell {
            to_local: DAffine3::from_translation(DVec3::new(0.0, 0.0, 2000.0)),
            axis: DVec3::Z,
            height: 2000.0,
            top_radius: 1000.0,
            thickness: 12.0,
            flare: 0.0,
        };
        let drain = |offset: f64, radius: f64| Body {
            name: "flange",
            origin: DVec3::new(offset, 0.0, -300.0),
            axis: -DVec3::Z,
            from: 0.0,
            to: 200.0,
            radius,
        };
        assert!(!skirt.holds(&drain(900.0, 80.0)));
        assert!(skirt.holds(&drain(900.0, 95.0)));
        // Below the base: clear.
        let deep = Body {
            from: 1800.0,
            to: 1900.0,
            ..drain(900.0, 95.0)
        };
        assert!(!skirt.holds(&deep));
        assert!(skirt.weld_distance(DVec3::new(1000.0, 0.0, 30.0)) - 30.0 < 1e-9);
    }
}
