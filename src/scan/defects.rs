//! Defects a simulated scan carries, parsed from `--defects` and applied to points
//! of the exact surfaces.
//!
//! ```text
//! ovality=0.8%@course:S2[/30°]      D_max − D_min = 0.8 % of D on course S2, major axis at 30°
//! dent=25mm@EL4000/90°[/600mm]      inward, 25 mm deep at elevation 4000, orientation 90°, 600 mm across
//! bulge=10mm@EL2500/180°[/800mm]    the same outward
//! peaking=8mm@seam[:S1][/45°]       a ridge 8 mm high along the long seam at 45° (every course, or S1)
//! tilt=0.3°[/90°]                   the vessel out of plumb by 0.3°, leaning towards 90°
//! settlement=cosine:40mm[@180°]     planar (cosine) settlement of a tank, 40 mm down at 180°
//! sag=20mm@60°[/3000mm]             out-of-plane settlement: the shell's bottom edge 20 mm down
//!                                   at 60°, over 3000 mm of arc, fading up the shell as much
//! ```
//!
//! Local defects move a point along the design normal; tilt and settlement are
//! rigid turns of the whole vessel about a horizontal axis through its datum.
//! Elevations are along the vessel axis from its datum, orientations by the plant
//! convention of the vessel's kind.

use glam::{DAffine3, DMat3, DVec3};
use serde::Serialize;

use super::ScanError;
use super::envelope::{Envelope, Role};
use crate::design::VesselKind;

/// Half-width of a simulated peak across its seam, mm: inside half the 900 mm
/// sweep board, so the board reads the full height.
pub const PEAKING_HALF_WIDTH: f64 = 300.0;

/// Default dent or bulge diameter, mm.
pub const DENT_DIAMETER: f64 = 600.0;

/// One defect.
#[derive(Clone, Debug, PartialEq, Serialize)]
#[serde(tag = "kind", rename_all = "snake_case")]
pub enum Defect {
    /// D_max − D_min = `fraction` × D over a course, major axis at `orientation`.
    Ovality {
        /// Course id.
        course: String,
        /// (D_max − D_min) / D.
        fraction: f64,
        /// Orientation of the major axis, degrees.
        orientation: f64,
    },
    /// A local dent (depth > 0, inward) or bulge (depth < 0, outward).
    Dent {
        /// Depth inward, mm (negative: a bulge).
        depth: f64,
        /// Elevation of its centre, mm.
        elevation: f64,
        /// Orientation of its centre, degrees.
        orientation: f64,
        /// Diameter of the affected area, mm.
        diameter: f64,
    },
    /// A ridge along a longitudinal seam.
    Peaking {
        /// Height outward, mm.
        height: f64,
        /// Orientation of the seam, degrees.
        orientation: f64,
        /// The one course it is on; every course when `None`.
        course: Option<String>,
    },
    /// Out of plumb: the axis turned by `angle` degrees, top towards `orientation`.
    Tilt {
        /// Degrees.
        angle: f64,
        /// Degrees.
        orientation: f64,
    },
    /// Out-of-plane settlement: the shell's bottom edge moved down by `depth`
    /// at `orientation`, (1 − s²)² over `width` mm of arc (s the distance over
    /// half of it), fading with height above the bottom edge over `width / 2`.
    Sag {
        /// mm, downward.
        depth: f64,
        /// Orientation of the deepest point, degrees.
        orientation: f64,
        /// Arc length affected, mm.
        width: f64,
    },
    /// Planar (cosine) settlement of a tank's bottom edge: `amplitude` mm down at
    /// `orientation`, as much up opposite.
    Settlement {
        /// mm.
        amplitude: f64,
        /// Orientation of the lowest point, degrees.
        orientation: f64,
    },
}

fn error(item: &str, field: &str, value: &str, rule: &str) -> ScanError {
    ScanError::Defect {
        item: item.to_string(),
        field: field.to_string(),
        value: value.to_string(),
        rule: rule.to_string(),
    }
}

/// A number with an optional unit suffix among `units`.
fn number(item: &str, field: &str, text: &str, units: &[&str]) -> Result<f64, ScanError> {
    let mut t = text.trim();
    for u in units {
        if let Some(s) = t.strip_suffix(u) {
            t = s;
            break;
        }
    }
    t.parse::<f64>()
        .ok()
        .filter(|v| v.is_finite())
        .ok_or_else(|| error(item, field, text, "must be a finite number"))
}

const MM: &[&str] = &["mm"];
const DEG: &[&str] = &["°", "deg"];

/// Parses a `--defects` list against the vessel's parts.
///
/// # Errors
///
/// [`ScanError::Defect`] naming the item, field, value and rule.
pub fn parse_defects(text: &str, envelope: &Envelope) -> Result<Vec<Defect>, ScanError> {
    let mut out = Vec::new();
    for item in text.split(',').map(str::trim).filter(|s| !s.is_empty()) {
        let (name, rest) = item
            .split_once('=')
            .ok_or_else(|| error(item, "item", item, "must be name=value"))?;
        let (value, place) = rest.split_once('@').unwrap_or((rest, ""));
        let course_of = |id: &str| -> Result<String, ScanError> {
            match envelope.part_index(id).map(|i| envelope.parts[i].role) {
                Some(Role::Course) => Ok(id.to_string()),
                _ => Err(error(
                    item,
                    "course",
                    id,
                    "must name a shell course of the vessel",
                )),
            }
        };
        let defect = match name {
            "ovality" => {
                let fraction = number(item, "ovality", value, &["%"])? / 100.0;
                if !(0.0..0.2).contains(&fraction) {
                    return Err(error(item, "ovality", value, "must be between 0 and 20 %"));
                }
                let (target, angle) = place.split_once('/').unwrap_or((place, "0"));
                let id = target
                    .strip_prefix("course:")
                    .ok_or_else(|| error(item, "@", place, "must be course:ID"))?;
                Defect::Ovality {
                    course: course_of(id)?,
                    fraction,
                    orientation: number(item, "orientation", angle, DEG)?,
                }
            }
            "dent" | "bulge" => {
                let depth = number(item, name, value, MM)?;
                if depth <= 0.0 {
                    return Err(error(item, name, value, "must be a depth > 0 mm"));
                }
                let fields: Vec<&str> = place.split('/').collect();
                let elevation = fields
                    .first()
                    .and_then(|e| e.strip_prefix("EL"))
                    .ok_or_else(|| error(item, "@", place, "must be ELz/orientation[/diameter]"))?;
                let orientation = fields
                    .get(1)
                    .ok_or_else(|| error(item, "@", place, "must be ELz/orientation[/diameter]"))?;
                let diameter = match fields.get(2) {
                    Some(d) => number(item, "diameter", d, MM)?,
                    None => DENT_DIAMETER,
                };
                if diameter <= 0.0 {
                    return Err(error(
                        item,
                        "diameter",
                        &diameter.to_string(),
                        "must be > 0 mm",
                    ));
                }
                Defect::Dent {
                    depth: if name == "dent" { depth } else { -depth },
                    elevation: number(item, "elevation", elevation, MM)?,
                    orientation: number(item, "orientation", orientation, DEG)?,
                    diameter,
                }
            }
            "peaking" => {
                let height = number(item, name, value, MM)?;
                let (seam, angle) = place.split_once('/').unwrap_or((place, "0"));
                let course = match seam.strip_prefix("seam") {
                    Some("") => None,
                    Some(c) => Some(course_of(c.trim_start_matches(':'))?),
                    None => return Err(error(item, "@", place, "must be seam[:ID][/orientation]")),
                };
                Defect::Peaking {
                    height,
                    orientation: number(item, "orientation", angle, DEG)?,
                    course,
                }
            }
            "sag" => {
                if envelope.kind == VesselKind::Horizontal {
                    return Err(error(
                        item,
                        name,
                        value,
                        "applies to vertical vessels and tanks only",
                    ));
                }
                let depth = number(item, name, value, MM)?;
                if depth <= 0.0 {
                    return Err(error(item, name, value, "must be a depth > 0 mm"));
                }
                let (angle, width) = place.split_once('/').unwrap_or((place, "3000"));
                if angle.is_empty() {
                    return Err(error(item, "@", place, "must be orientation[/width]"));
                }
                let width = number(item, "width", width, MM)?;
                if width <= 0.0 {
                    return Err(error(item, "width", &width.to_string(), "must be > 0 mm"));
                }
                Defect::Sag {
                    depth,
                    orientation: number(item, "orientation", angle, DEG)?,
                    width,
                }
            }
            "tilt" | "settlement" => {
                if envelope.kind == VesselKind::Horizontal {
                    return Err(error(
                        item,
                        name,
                        value,
                        "applies to vertical vessels and tanks only",
                    ));
                }
                if name == "tilt" {
                    let (angle, toward) = value.split_once('/').unwrap_or((value, "0"));
                    let angle = number(item, "tilt", angle, DEG)?;
                    if angle.abs() > 10.0 {
                        return Err(error(item, "tilt", value, "must be at most 10°"));
                    }
                    Defect::Tilt {
                        angle,
                        orientation: number(item, "orientation", toward, DEG)?,
                    }
                } else {
                    let amount = value.strip_prefix("cosine:").ok_or_else(|| {
                        error(item, "settlement", value, "must be cosine:AMPLITUDE")
                    })?;
                    Defect::Settlement {
                        amplitude: number(item, "settlement", amount, MM)?,
                        orientation: if place.is_empty() {
                            0.0
                        } else {
                            number(item, "orientation", place, DEG)?
                        },
                    }
                }
            }
            _ => {
                return Err(error(
                    item,
                    "name",
                    name,
                    "must be ovality, dent, bulge, peaking, tilt, settlement or sag",
                ));
            }
        };
        out.push(defect);
    }
    Ok(out)
}

/// Angle in (−π, π].
pub fn wrap(a: f64) -> f64 {
    let t = a.rem_euclid(std::f64::consts::TAU);
    if t > std::f64::consts::PI {
        t - std::f64::consts::TAU
    } else {
        t
    }
}

/// The normal displacement (mm, outward) the local defects give a point `p`
/// (vessel frame) of part `part`.
pub fn normal_displacement(envelope: &Envelope, defects: &[Defect], part: usize, p: DVec3) -> f64 {
    let info = &envelope.parts[part];
    let local = info.frame.inverse().transform_point3(p);
    let theta = local.y.atan2(local.x);
    let radius = DVec3::new(local.x, local.y, 0.0).length();
    let mut d = 0.0;
    for defect in defects {
        match defect {
            Defect::Ovality {
                course,
                fraction,
                orientation,
            } if *course == info.id => {
                let t0 = envelope.angle_of_orientation(*orientation);
                d += fraction * info.diameter / 4.0 * (2.0 * (theta - t0)).cos();
            }
            Defect::Dent {
                depth,
                elevation,
                orientation,
                diameter,
            } if info.role.is_envelope() => {
                let t0 = envelope.angle_of_orientation(*orientation);
                let vessel_theta = p.y.atan2(p.x);
                let r = DVec3::new(p.x, p.y, 0.0).length();
                let s = (r * wrap(vessel_theta - t0)).hypot(p.z - elevation) / (diameter / 2.0);
                if s < 1.0 {
                    d -= depth * (1.0 - s * s).powi(2);
                }
            }
            Defect::Peaking {
                height,
                orientation,
                course,
            } if info.role == Role::Course && course.as_ref().is_none_or(|c| *c == info.id) => {
                let t0 = envelope.angle_of_orientation(*orientation);
                let arc = (radius * wrap(theta - t0)).abs();
                d += height * (1.0 - arc / PEAKING_HALF_WIDTH).max(0.0);
            }
            _ => {}
        }
    }
    d
}

/// The downward displacement (mm) the sag defects give a point `p` (vessel
/// frame) of part `part`: only the shell courses settle with their bottom edge.
pub fn vertical_displacement(
    envelope: &Envelope,
    defects: &[Defect],
    part: usize,
    p: DVec3,
) -> f64 {
    if envelope.parts[part].role != Role::Course {
        return 0.0;
    }
    let Some(bottom) = envelope
        .parts
        .iter()
        .filter(|p| p.role == Role::Course)
        .min_by(|a, b| a.span.0.total_cmp(&b.span.0))
    else {
        return 0.0;
    };
    let mut d = 0.0;
    for defect in defects {
        if let Defect::Sag {
            depth,
            orientation,
            width,
        } = *defect
        {
            let t0 = envelope.angle_of_orientation(orientation);
            let r = DVec3::new(p.x, p.y, 0.0).length();
            let s = (r * wrap(p.y.atan2(p.x) - t0)).abs() / (width / 2.0);
            let h = (p.z - bottom.span.0).max(0.0) / (width / 2.0);
            if s < 1.0 && h < 1.0 {
                d += depth * (1.0 - s * s).powi(2) * (1.0 - h * h).powi(2);
            }
        }
    }
    d
}

/// The rigid motion (vessel frame) of the tilt and settlement defects.
pub fn rigid_motion(envelope: &Envelope, defects: &[Defect]) -> DAffine3 {
    let mut motion = DAffine3::IDENTITY;
    let bottom_radius = envelope
        .parts
        .iter()
        .filter(|p| p.role == Role::Course)
        .min_by(|a, b| a.span.0.total_cmp(&b.span.0))
        .map_or(1.0, |p| p.diameter / 2.0);
    for defect in defects {
        let (angle, orientation) = match *defect {
            Defect::Tilt { angle, orientation } => (angle.to_radians(), orientation),
            Defect::Settlement {
                amplitude,
                orientation,
            } => (
                (amplitude / bottom_radius).clamp(-1.0, 1.0).asin(),
                orientation,
            ),
            _ => continue,
        };
        let t = envelope.angle_of_orientation(orientation);
        let toward = DVec3::new(t.cos(), t.sin(), 0.0);
        let toward = (toward - envelope.up * toward.dot(envelope.up)).normalize();
        let axis = envelope.up.cross(toward).normalize();
        motion = DAffine3::from_mat3(DMat3::from_axis_angle(axis, angle)) * motion;
    }
    motion
}
