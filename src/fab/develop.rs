//! Exact developments of a vessel's rolled parts and head blanks.
//!
//! Every rolled part — shell course, concentric reducer, skirt — is developed
//! on its **mid-surface** (half the thickness in from the outside, measured
//! normal to the wall): a cylinder of mid radius `r` unrolls to `u = r·θ`,
//! `v = z`; a cone frustum to an annular sector of radii `r/sin α` (α the
//! half-angle) and angle `2π·sin α`. Both are isometries, so a developed area
//! is the mid-surface area exactly. A part is described by a [`Rolled`]: its
//! mid radius at each end of its axial range in the part's local frame.
//!
//! Heads are formed, not rolled: their blank is a disc by the **area
//! equivalence of the mid-surface** ([`HeadBlank`]): the blank's area equals
//! the exact area of the head of the same kind built on the mid-surface
//! (diameter `D − t`, knuckle and crown radii less `t/2`, an ellipsoid's
//! depth less `t/2`), straight flange included. An eccentric reducer is an
//! oblique cone: a [`Rolled`] with a flat side, developed exactly by
//! [`super::oblique`].
//!
//! A boot is a cylinder ending on its host course in a saddle-shaped curve
//! ([`BootShell`]): developed like a course (`u = r·φ` at its mid radius, `v`
//! along its axis) by [`super::boot`] once its host end is cut
//! ([`super::openings::cut_boot`]); its head gets a blank like the others.

use glam::{DAffine3, DVec2, DVec3};

use crate::constraints::{ResolvedPart, ResolvedVessel};
use crate::format::{PartDesign, RuleViolation, VesselDesign};
use crate::operating::thickness as design_thickness;
use crate::parts::heads::{Head, HeadKind};
use crate::parts::surface_area;
use crate::parts::{PartGeometry, ReducerAlignment};

use super::oblique::{ObliqueCone, ObliquePlate};

/// What a rolled part is.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum RolledKind {
    /// A cylindrical shell course.
    Course,
    /// A conical reducer, concentric or (with a flat side) eccentric.
    Cone,
    /// A skirt (straight or flared).
    Skirt,
}

/// A rolled part's mid-surface: circles about the part's local +Z whose
/// radius is linear in `z` — a surface of revolution, or, with a
/// [`flat_side`](Self::flat_side), an oblique cone whose circles' centres
/// move towards the flat side as the radius shrinks.
#[derive(Clone, Debug, PartialEq)]
pub struct Rolled {
    /// Index of the part in the resolved vessel.
    pub part: usize,
    /// Part id.
    pub id: String,
    /// JSON path of the part, `vessels[0].parts[2]`.
    pub path: String,
    /// Kind.
    pub kind: RolledKind,
    /// Part local frame → vessel frame.
    pub frame: DAffine3,
    /// Axial range in the part's local frame, mm.
    pub z: (f64, f64),
    /// Mid-surface radius at `z.0` and at `z.1`, mm.
    pub radius: (f64, f64),
    /// Outside radius at `z.0` and at `z.1`, mm.
    pub outside: (f64, f64),
    /// Wall thickness, mm.
    pub thickness: f64,
    /// An eccentric reducer's flat side, part-local angle from +x, radians
    /// (`None` for a surface of revolution).
    pub flat_side: Option<f64>,
}

impl Rolled {
    /// The oblique cone of an eccentric reducer's mid-surface.
    pub fn oblique(&self) -> Option<ObliqueCone> {
        self.flat_side.map(|flat_side| ObliqueCone {
            large: self.radius_at(0.0),
            small: self.radius_at(self.z.1),
            length: self.z.1,
            flat_side,
        })
    }

    /// The centre of the mid-surface's circle at local height `z` (the axis,
    /// or for an eccentric reducer moved towards its flat side), part-local.
    pub fn centre_at(&self, z: f64) -> DVec2 {
        match self.flat_side {
            Some(f) => DVec2::from_angle(f) * (self.radius_at(0.0) - self.radius_at(z)),
            None => DVec2::ZERO,
        }
    }

    /// The part-local point at angle `theta` about the circle at height `z`,
    /// `radius` from its centre.
    pub fn point(&self, theta: f64, z: f64, radius: f64) -> DVec3 {
        let c = self.centre_at(z) + DVec2::from_angle(theta) * radius;
        DVec3::new(c.x, c.y, z)
    }

    /// Mid radius at local height `z`.
    pub fn radius_at(&self, z: f64) -> f64 {
        let t = (z - self.z.0) / (self.z.1 - self.z.0);
        self.radius.0 + (self.radius.1 - self.radius.0) * t
    }

    /// Outside radius at local height `z`.
    pub fn outside_at(&self, z: f64) -> f64 {
        let t = (z - self.z.0) / (self.z.1 - self.z.0);
        self.outside.0 + (self.outside.1 - self.outside.0) * t
    }

    /// Whether the mid-surface is a cylinder.
    pub fn is_cylinder(&self) -> bool {
        self.radius.0 == self.radius.1
    }

    /// dr/dz of the mid-surface.
    pub fn taper(&self) -> f64 {
        (self.radius.1 - self.radius.0) / (self.z.1 - self.z.0)
    }

    /// Slant length of the band `z0..z1` along the mid-surface (the longest
    /// generator of an eccentric reducer's), mm.
    pub fn slant(&self, z0: f64, z1: f64) -> f64 {
        let slope = match self.oblique() {
            Some(cone) => cone.slope(),
            None => self.taper().hypot(1.0),
        };
        (z1 - z0).abs() * slope
    }

    /// Length of the generator at angle `theta` of the band `z0..z1`, mm.
    pub fn generator(&self, theta: f64, z0: f64, z1: f64) -> f64 {
        match self.oblique() {
            Some(cone) => cone.generator(theta, z0, z1),
            None => self.slant(z0, z1),
        }
    }

    /// Exact mid-surface area of the band `z0..z1` over `angle` radians
    /// from angle `from`, mm² (Pappus for a surface of revolution: angle ×
    /// mean radius × slant length; an oblique cone's by [`ObliqueCone::band_area`]).
    pub fn area(&self, from: f64, angle: f64, z0: f64, z1: f64) -> f64 {
        match self.oblique() {
            Some(cone) => cone.band_area(from, from + angle, z0, z1),
            None => angle * 0.5 * (self.radius_at(z0) + self.radius_at(z1)) * self.slant(z0, z1),
        }
    }

    /// The developed outline of the band `z0..z1` over `angle` radians from
    /// angle `from`.
    pub fn outline(&self, from: f64, angle: f64, z0: f64, z1: f64) -> Outline {
        if let Some(cone) = self.oblique() {
            return Outline::Oblique(ObliquePlate {
                cone,
                from,
                angle,
                z: (z0, z1),
            });
        }
        if self.is_cylinder() {
            return Outline::Rectangle {
                width: self.radius.0 * angle,
                height: z1 - z0,
            };
        }
        // sin α = |dr/ds|: the sector radius of a circle of radius r is r / sin α.
        let sin = self.taper().abs() / self.taper().hypot(1.0);
        let (ra, rb) = (self.radius_at(z0) / sin, self.radius_at(z1) / sin);
        Outline::Sector {
            inner: ra.min(rb),
            outer: ra.max(rb),
            angle: angle * sin,
        }
    }
}

/// A developed outline of a plate without its openings.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Outline {
    /// A cylinder's plate: `width` around (u), `height` along the axis (v), mm.
    Rectangle {
        /// Developed arc length, mm.
        width: f64,
        /// Axial height, mm.
        height: f64,
    },
    /// A cone's plate: an annular sector, radii in mm, angle in radians.
    Sector {
        /// Inner radius (the small end), mm.
        inner: f64,
        /// Outer radius (the large end), mm.
        outer: f64,
        /// Sector angle, radians.
        angle: f64,
    },
    /// An eccentric reducer's plate, laid like a sector (apex at the
    /// origin, bisector along +y).
    Oblique(ObliquePlate),
}

impl Outline {
    /// Area, mm².
    pub fn area(&self) -> f64 {
        match *self {
            Outline::Rectangle { width, height } => width * height,
            Outline::Sector {
                inner,
                outer,
                angle,
            } => 0.5 * angle * (outer * outer - inner * inner),
            Outline::Oblique(plate) => plate.area(),
        }
    }

    /// The bounding box `(width, height)` of the outline laid with a sector's
    /// bisector along +y, mm.
    pub fn extent(&self) -> (f64, f64) {
        match *self {
            Outline::Rectangle { width, height } => (width, height),
            Outline::Sector {
                inner,
                outer,
                angle,
            } => {
                let half = 0.5 * angle;
                let width = if half >= std::f64::consts::FRAC_PI_2 {
                    2.0 * outer
                } else {
                    2.0 * outer * half.sin()
                };
                let low = if half >= std::f64::consts::PI {
                    -outer
                } else if half >= std::f64::consts::FRAC_PI_2 {
                    outer * half.cos()
                } else {
                    inner * half.cos()
                };
                (width, outer - low)
            }
            Outline::Oblique(plate) => {
                let (lo, hi) = plate.bounds();
                (hi.x - lo.x, hi.y - lo.y)
            }
        }
    }
}

/// A head's flat blank by the area equivalence of its mid-surface.
#[derive(Clone, Debug, PartialEq)]
pub struct HeadBlank {
    /// Index of the part in the resolved vessel.
    pub part: usize,
    /// Part id.
    pub id: String,
    /// JSON path of the part.
    pub path: String,
    /// Thickness, mm.
    pub thickness: f64,
    /// Exact area of the mid-surface head, mm².
    pub mid_area: f64,
    /// Blank diameter √(4·A/π), mm.
    pub diameter: f64,
}

/// A boot's cylinder and its head's blank. The design gives a boot no
/// thickness: it takes its host course's (as the weight model does).
#[derive(Clone, Debug, PartialEq)]
pub struct BootShell {
    /// Index of the part in the resolved vessel.
    pub part: usize,
    /// Part id.
    pub id: String,
    /// JSON path of the part.
    pub path: String,
    /// Index of its host course in the resolved vessel.
    pub host: usize,
    /// Boot local frame (origin on the host's axis, +Z along the boot away
    /// from the host) → vessel frame.
    pub frame: DAffine3,
    /// Mid-surface radius, mm.
    pub radius: f64,
    /// Outside radius, mm.
    pub outside: f64,
    /// Wall thickness (its host course's), mm.
    pub thickness: f64,
    /// Local height of the head's tangent line (the boot-to-head seam), mm.
    pub tangent: f64,
    /// The blank of its head (id `B1-HEAD`), `None` when the mid-surface
    /// head is not valid.
    pub head: Option<HeadBlank>,
}

impl BootShell {
    /// Plates round the boot: its mid circumference over the maximum plate
    /// length, rounded up.
    pub fn plate_count(&self, max_plate_length: f64) -> usize {
        let c = std::f64::consts::TAU * self.radius;
        ((c / max_plate_length).ceil() as usize).max(1)
    }
}

/// The id of a boot's head, as blanks, welds and operations name it.
pub fn boot_head_id(boot: &str) -> String {
    format!("{boot}-HEAD")
}

/// The forming rule the blanks follow, as reports print it.
pub const BLANK_RULE: &str = "blank area = exact mid-surface area of the head (D - t, radii - t/2, straight flange included)";

/// A part the development leaves out, and why.
#[derive(Clone, Debug, PartialEq)]
pub struct Skipped {
    /// Part id.
    pub id: String,
    /// Why.
    pub reason: String,
}

/// The developments of one vessel's parts.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Developments {
    /// Rolled parts in design order.
    pub rolled: Vec<Rolled>,
    /// Head blanks in design order.
    pub heads: Vec<HeadBlank>,
    /// Boots in design order.
    pub boots: Vec<BootShell>,
    /// Parts left out (supports other than skirts).
    pub skipped: Vec<Skipped>,
}

/// The thickness of part `index` of `vessel`, or a violation naming it.
fn thickness_of(
    vessel: &VesselDesign,
    vessel_index: usize,
    index: usize,
) -> Result<f64, RuleViolation> {
    let part = &vessel.parts[index];
    let t = match part {
        PartDesign::Skirt(s) => s.thickness,
        other => design_thickness(other),
    };
    let id = part.id();
    t.ok_or_else(|| RuleViolation {
        path: format!("vessels[{vessel_index}].parts[{index}].thickness"),
        entity: format!("{}/{id}", vessel.tag),
        field: "thickness".into(),
        value: "missing".into(),
        rule: "fabrication needs every rolled part's and head's thickness".into(),
    })
}

/// What the development of one part gives.
#[derive(Clone, Debug, PartialEq)]
pub enum PartDevelopment {
    /// A rolled part.
    Rolled(Rolled),
    /// A head's blank.
    Head(HeadBlank),
    /// A boot.
    Boot(BootShell),
    /// A part left out, and why.
    Skipped(Skipped),
}

impl Developments {
    /// Adds one part's development in its list.
    pub fn push(&mut self, d: PartDevelopment) {
        match d {
            PartDevelopment::Rolled(r) => self.rolled.push(r),
            PartDevelopment::Head(h) => self.heads.push(h),
            PartDevelopment::Boot(b) => self.boots.push(b),
            PartDevelopment::Skipped(s) => self.skipped.push(s),
        }
    }

    /// The development of part `index` of the resolved vessel (`id` its id),
    /// if it has one.
    pub fn of_part(&self, index: usize, id: &str) -> Option<PartDevelopment> {
        if let Some(r) = self.rolled.iter().find(|r| r.part == index) {
            return Some(PartDevelopment::Rolled(r.clone()));
        }
        if let Some(h) = self.heads.iter().find(|h| h.part == index) {
            return Some(PartDevelopment::Head(h.clone()));
        }
        if let Some(b) = self.boots.iter().find(|b| b.part == index) {
            return Some(PartDevelopment::Boot(b.clone()));
        }
        self.skipped
            .iter()
            .find(|s| s.id == id)
            .map(|s| PartDevelopment::Skipped(s.clone()))
    }
}

/// Develops part `index` of `resolved` (vessel `vessel_index` of its design,
/// `vessel`): `None` for parts that are neither rolled nor formed (saddles,
/// legs, lugs).
///
/// # Errors
///
/// A violation naming the part when it has no thickness.
pub fn develop_one(
    vessel: &VesselDesign,
    vessel_index: usize,
    resolved: &ResolvedVessel,
    index: usize,
) -> Result<Option<PartDevelopment>, RuleViolation> {
    let part = &resolved.parts[index];
    let Some(design_index) = vessel.parts.iter().position(|p| p.id() == part.id) else {
        return Ok(None);
    };
    let path = format!("vessels[{vessel_index}].parts[{design_index}]");
    let needs_thickness = matches!(
        part.geometry,
        PartGeometry::Shell(_)
            | PartGeometry::Reducer(_)
            | PartGeometry::Skirt(_)
            | PartGeometry::Head(_)
    );
    let thickness = if needs_thickness {
        thickness_of(vessel, vessel_index, design_index)?
    } else if let (PartGeometry::Boot(_), Some(host)) = (&part.geometry, part.host) {
        let host_id = &resolved.parts[host].id;
        match vessel.parts.iter().position(|p| p.id() == *host_id) {
            Some(k) => thickness_of(vessel, vessel_index, k)?,
            None => return Ok(None),
        }
    } else {
        0.0
    };
    Ok(develop_part(part, index, path, thickness))
}

/// Develops every rolled part and head of `resolved` (vessel `vessel_index`
/// of its design, `vessel`).
///
/// # Errors
///
/// A violation per part without a thickness.
pub fn develop(
    vessel: &VesselDesign,
    vessel_index: usize,
    resolved: &ResolvedVessel,
) -> Result<Developments, Vec<RuleViolation>> {
    let mut out = Developments::default();
    let mut errors = Vec::new();
    for index in 0..resolved.parts.len() {
        match develop_one(vessel, vessel_index, resolved, index) {
            Ok(Some(d)) => out.push(d),
            Ok(None) => {}
            Err(e) => errors.push(e),
        }
    }
    if errors.is_empty() {
        Ok(out)
    } else {
        Err(errors)
    }
}

fn develop_part(
    part: &ResolvedPart,
    index: usize,
    path: String,
    t: f64,
) -> Option<PartDevelopment> {
    let skipped = |reason: String| {
        PartDevelopment::Skipped(Skipped {
            id: part.id.clone(),
            reason,
        })
    };
    let rolled = |kind, z: (f64, f64), outside: (f64, f64)| {
        // The mid-surface lies t/2 in from the outside along the wall's
        // normal: t/(2 cos α) in radius.
        let taper = (outside.1 - outside.0) / (z.1 - z.0);
        let inset = 0.5 * t * taper.hypot(1.0);
        PartDevelopment::Rolled(Rolled {
            part: index,
            id: part.id.clone(),
            path: path.clone(),
            kind,
            frame: part.frame,
            z,
            radius: (outside.0 - inset, outside.1 - inset),
            outside,
            thickness: t,
            flat_side: None,
        })
    };
    Some(match &part.geometry {
        PartGeometry::Shell(s) => {
            let r = 0.5 * s.outside_diameter;
            rolled(RolledKind::Course, (0.0, s.length), (r, r))
        }
        PartGeometry::Reducer(r) => match r.alignment {
            ReducerAlignment::Concentric => rolled(
                RolledKind::Cone,
                (0.0, r.length),
                (0.5 * r.large_diameter, 0.5 * r.small_diameter),
            ),
            ReducerAlignment::Eccentric { flat_side } => {
                // The wall measured in the end planes (see `oblique`).
                let h = 0.5 * t;
                let (large, small) = (0.5 * r.large_diameter, 0.5 * r.small_diameter);
                PartDevelopment::Rolled(Rolled {
                    part: index,
                    id: part.id.clone(),
                    path: path.clone(),
                    kind: RolledKind::Cone,
                    frame: part.frame,
                    z: (0.0, r.length),
                    radius: (large - h, small - h),
                    outside: (large, small),
                    thickness: t,
                    flat_side: Some(flat_side.to_radians()),
                })
            }
        },
        PartGeometry::Skirt(s) => {
            let top = 0.5 * s.top_diameter;
            let base = top + s.height * s.flare_angle.to_radians().tan();
            rolled(RolledKind::Skirt, (0.0, s.height), (base, top))
        }
        PartGeometry::Head(h) => match head_blank(h, index, &part.id, path, t) {
            Some(blank) => PartDevelopment::Head(blank),
            None => skipped(format!(
                "head: its mid-surface (t = {t} mm) is not a valid head of its kind, no blank"
            )),
        },
        PartGeometry::Boot(b) => match part.host {
            Some(host) => PartDevelopment::Boot(BootShell {
                part: index,
                id: part.id.clone(),
                head: head_blank(
                    &b.head_part(),
                    index,
                    &boot_head_id(&part.id),
                    format!("{path}.head"),
                    t,
                ),
                path,
                host,
                frame: part.frame,
                radius: 0.5 * (b.diameter - t),
                outside: 0.5 * b.diameter,
                thickness: t,
                tangent: b.tangent_line(),
            }),
            None => skipped("boot: not cut into a host course, not developed".into()),
        },
        _ => return None,
    })
}

/// The head of the same kind on the mid-surface of `head`, `t` thick.
pub fn mid_head(head: &Head, t: f64) -> Head {
    let h = 0.5 * t;
    let kind = match head.kind {
        HeadKind::Hemispherical => HeadKind::Hemispherical,
        HeadKind::Ellipsoidal { ratio } => {
            let depth = head.outside_diameter / (2.0 * ratio) - h;
            HeadKind::Ellipsoidal {
                ratio: (head.outside_diameter - t) / (2.0 * depth),
            }
        }
        HeadKind::Torispherical {
            crown_radius,
            knuckle_radius,
        } => HeadKind::Torispherical {
            crown_radius: crown_radius - h,
            knuckle_radius: knuckle_radius - h,
        },
        HeadKind::Toriconical {
            half_angle,
            knuckle_radius,
        } => HeadKind::Toriconical {
            half_angle,
            knuckle_radius: knuckle_radius - h,
        },
        other => other,
    };
    Head {
        outside_diameter: head.outside_diameter - t,
        straight_flange: head.straight_flange,
        kind,
    }
}

fn head_blank(head: &Head, index: usize, id: &str, path: String, t: f64) -> Option<HeadBlank> {
    // A mid-surface head that fails its own checks (a knuckle thinner than
    // half the wall) gets no blank rather than a wrong one.
    let patches = mid_head(head, t).patches().ok()?;
    let area = surface_area(&patches);
    Some(HeadBlank {
        part: index,
        id: id.to_string(),
        path,
        thickness: t,
        mid_area: area,
        diameter: (4.0 * area / std::f64::consts::PI).sqrt(),
    })
}
