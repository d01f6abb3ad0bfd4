//! The axial stack: heads, shell courses and reducers laid out along the vessel
//! axis in design order, with the diameters they inherit from each other.
//!
//! The datum (z = 0) is the bottom (or left) tangent line: the tangent line of the
//! first head if there is one, else the start of the first course. Each course
//! starts where the previous one ends, so lengthening a course moves everything
//! above it. Heads take the OD of the course they close; a reducer's ends take the
//! ODs of the two courses it joins.
//!
//! An eccentric reducer moves the axis: its small end is offset (D − d)/2 towards
//! its flat side, so every course and head beyond it sits on that offset axis
//! (each [`Course`] carries where its axis runs, [`Course::axis_at`]). The datum
//! stays on the first course's axis.

use std::f64::consts::PI;

use glam::{DAffine3, DMat3, DVec3};

use super::frames::check_angle;
use super::part_error::report_part_error;
use super::{Report, ResolvedPart, orientation_direction};
use crate::format::{HeadDesign, HeadShape, PartDesign, VesselDesign};
use crate::parts::PartGeometry;
use crate::parts::heads::{Head, HeadKind};
use crate::parts::{Reducer, ReducerAlignment, Shell};

/// A course (shell or reducer) of the stack, for looking up the OD at a position.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Course {
    /// Index of the part in the design.
    pub part: usize,
    /// True for a cylindrical shell course.
    pub cylindrical: bool,
    /// Axial start and end, vessel frame, mm.
    pub start: f64,
    /// End of the course.
    pub end: f64,
    /// OD at the start and at the end.
    pub d_start: f64,
    /// OD at the end.
    pub d_end: f64,
    /// Where the course's axis crosses its start plane, vessel frame, mm (z = 0:
    /// the lateral offset from the vessel axis, left by eccentric reducers below).
    pub shift_start: DVec3,
    /// Where the course's axis crosses its end plane (z = 0, as `shift_start`):
    /// differs from `shift_start` only on an eccentric reducer.
    pub shift_end: DVec3,
}

impl Course {
    /// OD at axial position `z` (linear along a reducer).
    pub fn diameter_at(&self, z: f64) -> f64 {
        let t = ((z - self.start) / (self.end - self.start)).clamp(0.0, 1.0);
        self.d_start + (self.d_end - self.d_start) * t
    }

    /// The centre of the course's cross-section at axial position `z`, vessel
    /// frame (linear along a reducer: the sections of an oblique circular cone
    /// parallel to its base are circles whose centres lie on a line).
    pub fn axis_at(&self, z: f64) -> DVec3 {
        let t = ((z - self.start) / (self.end - self.start)).clamp(0.0, 1.0);
        self.shift_start + (self.shift_end - self.shift_start) * t + DVec3::Z * z
    }

    /// The larger end OD.
    pub fn diameter_max(&self) -> f64 {
        self.d_start.max(self.d_end)
    }
}

/// The laid-out stack.
pub(crate) struct StackLayout {
    /// One slot per design part; stack parts resolved, others `None` for now.
    pub parts: Vec<Option<ResolvedPart>>,
    /// Courses bottom to top.
    pub courses: Vec<Course>,
    /// Tangent-to-tangent length.
    pub tangent_length: f64,
}

fn translate_z(z: f64) -> DAffine3 {
    DAffine3::from_translation(DVec3::new(0.0, 0.0, z))
}

/// The translation to `shift + z` along the vessel axis (`shift` lateral).
fn translate_at(shift: DVec3, z: f64) -> DAffine3 {
    DAffine3::from_translation(shift + DVec3::Z * z)
}

fn flipped_at(z: f64) -> DAffine3 {
    DAffine3::from_mat3_translation(DMat3::from_rotation_x(PI), DVec3::new(0.0, 0.0, z))
}

/// Lays out the stack and checks its structure and every stack part's parameters.
pub(crate) fn layout(vessel: &VesselDesign, report: &mut Report) -> StackLayout {
    let mut parts: Vec<Option<ResolvedPart>> = vec![None; vessel.parts.len()];
    let stack: Vec<usize> = (0..vessel.parts.len())
        .filter(|&i| vessel.parts[i].in_stack())
        .collect();
    let mut courses = Vec::new();
    if !stack
        .iter()
        .any(|&i| matches!(vessel.parts[i], PartDesign::Shell(_)))
    {
        report.push(
            "parts",
            None,
            "parts",
            vessel.parts.len(),
            "a vessel needs at least one shell course",
        );
        return StackLayout {
            parts,
            courses,
            tangent_length: 0.0,
        };
    }
    // Structure: heads only at the ends, reducers between two shells.
    for (k, &i) in stack.iter().enumerate() {
        let path = format!("parts[{i}].{}", vessel.parts[i].kind());
        let id = Some(vessel.parts[i].id());
        match &vessel.parts[i] {
            PartDesign::Head(_) if k != 0 && k + 1 != stack.len() => {
                report.push(
                    &path,
                    id,
                    "head",
                    vessel.parts[i].id(),
                    "a head must be the first or last part of the stack",
                );
            }
            PartDesign::Head(_) if stack.len() == 1 => {}
            PartDesign::Reducer(_) => {
                let shell_at = |j: Option<usize>| {
                    j.is_some_and(|j| matches!(vessel.parts[stack[j]], PartDesign::Shell(_)))
                };
                if !shell_at(k.checked_sub(1))
                    || !shell_at(Some(k + 1).filter(|&j| j < stack.len()))
                {
                    report.push(
                        &path,
                        id,
                        "reducer",
                        vessel.parts[i].id(),
                        "a reducer must join two shell courses",
                    );
                }
            }
            _ => {}
        }
    }
    let first_head = match vessel.parts[stack[0]] {
        PartDesign::Head(ref h) => Some((stack[0], h)),
        _ => None,
    };
    let last_head = match vessel.parts[stack[stack.len() - 1]] {
        PartDesign::Head(ref h) if stack.len() > 1 => Some((stack[stack.len() - 1], h)),
        _ => None,
    };
    // Courses.
    let mut z = first_head.map_or(0.0, |(_, h)| h.straight_flange.max(0.0));
    // Lateral offset of the current course's axis (left by eccentric reducers).
    let mut shift = DVec3::ZERO;
    let body: Vec<usize> = stack
        .iter()
        .copied()
        .filter(|&i| !matches!(vessel.parts[i], PartDesign::Head(_)))
        .collect();
    for (k, &i) in body.iter().enumerate() {
        let path = format!("parts[{i}].{}", vessel.parts[i].kind());
        match &vessel.parts[i] {
            PartDesign::Shell(s) => {
                let shell = Shell {
                    outside_diameter: s.od,
                    length: s.length,
                };
                match shell.validate() {
                    Ok(()) => {
                        courses.push(Course {
                            part: i,
                            cylindrical: true,
                            start: z,
                            end: z + s.length,
                            d_start: s.od,
                            d_end: s.od,
                            shift_start: shift,
                            shift_end: shift,
                        });
                        parts[i] = Some(ResolvedPart {
                            id: s.id.clone(),
                            frame: translate_at(shift, z),
                            geometry: PartGeometry::Shell(shell),
                            span: (z, z + s.length),
                            host: None,
                        });
                        z += s.length;
                    }
                    Err(e) => {
                        report_part_error(report, &path, &s.id, &e, &[("outside_diameter", "od")])
                    }
                }
                // Adjacent shells of different OD need a reducer between them.
                if let Some(&next) = body.get(k + 1)
                    && let PartDesign::Shell(n) = &vessel.parts[next]
                    && n.od != s.od
                    && n.od.is_finite()
                    && s.od.is_finite()
                {
                    report.push(
                        format!("parts[{next}].shell.od"),
                        Some(&n.id),
                        "od",
                        n.od,
                        format!("differs from the OD {} of the course {} below it: join them with a reducer", s.od, s.id),
                    );
                }
            }
            PartDesign::Reducer(r) => {
                let od = |j: Option<&usize>| match j.map(|&j| &vessel.parts[j]) {
                    Some(PartDesign::Shell(s)) => Some(s.od),
                    _ => None,
                };
                let (Some(below), Some(above)) = (
                    od(k.checked_sub(1).and_then(|j| body.get(j))),
                    od(body.get(k + 1)),
                ) else {
                    continue; // reported above
                };
                if below == above {
                    report.push(
                        &path,
                        Some(&r.id),
                        "reducer",
                        &r.id,
                        format!(
                            "joins two courses of the same OD {below} mm: a reducer needs \
                             courses of different diameters (remove it or change an OD)"
                        ),
                    );
                    continue;
                }
                if let Some(angle) = r.eccentric
                    && !check_angle(
                        report,
                        &format!("{path}.eccentric"),
                        Some(&r.id),
                        "eccentric",
                        angle,
                    )
                {
                    continue;
                }
                // The frame before its lateral placement (fixed below, once the
                // small end's centre is known).
                let (large, small, frame) = if below >= above {
                    (below, above, translate_z(z))
                } else {
                    (above, below, flipped_at(z + r.length))
                };
                let alignment = match r.eccentric {
                    None => ReducerAlignment::Concentric,
                    Some(angle) => {
                        let d =
                            orientation_direction(vessel.kind, vessel.placement.rotation, angle);
                        let local = frame.matrix3.inverse() * d;
                        ReducerAlignment::Eccentric {
                            flat_side: local.y.atan2(local.x).to_degrees(),
                        }
                    }
                };
                let reducer = Reducer {
                    large_diameter: large,
                    small_diameter: small,
                    length: r.length,
                    alignment,
                };
                match reducer.validate() {
                    Ok(()) => {
                        // Place the end that meets the course below on its axis:
                        // the large end (the part's origin) or, turned over, the
                        // small end's centre.
                        let (frame, next_shift) = if below >= above {
                            let frame = translate_at(shift, 0.0) * frame;
                            let top = frame.transform_point3(reducer.small_end_center());
                            (frame, DVec3::new(top.x, top.y, 0.0))
                        } else {
                            let bottom = frame.transform_point3(reducer.small_end_center());
                            let delta = shift - DVec3::new(bottom.x, bottom.y, 0.0);
                            (translate_at(delta, 0.0) * frame, delta)
                        };
                        courses.push(Course {
                            part: i,
                            cylindrical: false,
                            start: z,
                            end: z + r.length,
                            d_start: below,
                            d_end: above,
                            shift_start: shift,
                            shift_end: next_shift,
                        });
                        shift = next_shift;
                        parts[i] = Some(ResolvedPart {
                            id: r.id.clone(),
                            frame,
                            geometry: PartGeometry::Reducer(reducer),
                            span: (z, z + r.length),
                            host: None,
                        });
                        z += r.length;
                    }
                    Err(e) => report_part_error(
                        report,
                        &path,
                        &r.id,
                        &e,
                        &[
                            ("small_diameter", "od of the smaller adjoining course"),
                            ("large_diameter", "od of the larger adjoining course"),
                            ("flat_side", "eccentric"),
                        ],
                    ),
                }
            }
            _ => {}
        }
    }
    let mut tangent_length = z;
    if let (Some((i, h)), Some(c)) = (first_head, courses.first())
        && let Some(head) = head_part(i, h, c.d_start, report)
    {
        {
            let sf = h.straight_flange;
            let height = head.height().unwrap_or(0.0);
            parts[i] = Some(ResolvedPart {
                id: h.id.clone(),
                frame: flipped_at(sf),
                geometry: PartGeometry::Head(head),
                span: (sf - height, sf),
                host: None,
            });
        }
    }
    if let (Some((i, h)), Some(c)) = (last_head, courses.last())
        && let Some(head) = head_part(i, h, c.d_end, report)
    {
        {
            let height = head.height().unwrap_or(0.0);
            parts[i] = Some(ResolvedPart {
                id: h.id.clone(),
                frame: translate_at(c.shift_end, z),
                geometry: PartGeometry::Head(head),
                span: (z, z + height),
                host: None,
            });
            tangent_length = z + h.straight_flange;
        }
    }
    StackLayout {
        parts,
        courses,
        tangent_length,
    }
}

/// The head's kind from its design with defaults filled in, or `None` after
/// reporting fields that do not apply to its shape.
pub(crate) fn head_kind(
    h: &HeadDesign,
    od: f64,
    path: &str,
    report: &mut Report,
) -> Option<HeadKind> {
    let given = [
        ("ratio", h.ratio),
        ("crown_radius", h.crown_radius),
        ("knuckle_radius", h.knuckle_radius),
        ("half_angle", h.half_angle),
        ("small_od", h.small_od),
    ];
    let shape = format!("{:?}", h.shape).to_lowercase();
    let article = if shape.starts_with(['a', 'e', 'i', 'o', 'u']) {
        "an"
    } else {
        "a"
    };
    let allowed: &[&str] = match h.shape {
        HeadShape::Hemispherical => &[],
        HeadShape::Ellipsoidal => &["ratio"],
        HeadShape::Torispherical => &["crown_radius", "knuckle_radius"],
        HeadShape::Toriconical => &["half_angle", "knuckle_radius"],
        HeadShape::Conical => &["half_angle", "small_od"],
        HeadShape::Flat => &["knuckle_radius"],
    };
    let mut ok = true;
    for (name, value) in given {
        if let Some(v) = value
            && !allowed.contains(&name)
        {
            report.push(
                format!("{path}.{name}"),
                Some(&h.id),
                name,
                v,
                if allowed.is_empty() {
                    format!("does not apply to {article} {shape} head (it takes no shape fields)")
                } else {
                    format!(
                        "does not apply to {article} {shape} head (it takes {})",
                        allowed.join(", ")
                    )
                },
            );
            ok = false;
        }
    }
    if !ok {
        return None;
    }
    Some(match h.shape {
        HeadShape::Hemispherical => HeadKind::Hemispherical,
        HeadShape::Ellipsoidal => HeadKind::Ellipsoidal {
            ratio: h.ratio.unwrap_or(2.0),
        },
        HeadShape::Torispherical => {
            let crown = h.crown_radius.unwrap_or(od);
            HeadKind::Torispherical {
                crown_radius: crown,
                knuckle_radius: h.knuckle_radius.unwrap_or(0.06 * crown),
            }
        }
        HeadShape::Toriconical => HeadKind::Toriconical {
            half_angle: h.half_angle.unwrap_or(30.0),
            knuckle_radius: h.knuckle_radius.unwrap_or(0.06 * od),
        },
        HeadShape::Conical => HeadKind::Conical {
            half_angle: h.half_angle.unwrap_or(30.0),
            small_diameter: h.small_od.unwrap_or(0.0),
        },
        HeadShape::Flat => HeadKind::Flat {
            knuckle_radius: h.knuckle_radius.unwrap_or(0.0),
        },
    })
}

fn head_part(i: usize, h: &HeadDesign, od: f64, report: &mut Report) -> Option<Head> {
    let path = format!("parts[{i}].head");
    let kind = head_kind(h, od, &path, report)?;
    let head = Head {
        outside_diameter: od,
        straight_flange: h.straight_flange,
        kind,
    };
    match head.validate() {
        Ok(()) => {
            // The head exists; then the ranges its geometry is built over.
            let before = report.violations.len();
            super::head_limits::check(&kind, od, &path, &h.id, report);
            (report.violations.len() == before).then_some(head)
        }
        Err(e) => {
            report_part_error(
                report,
                &path,
                &h.id,
                &e,
                &[
                    ("outside_diameter", "od of the course it closes"),
                    ("small_diameter", "small_od"),
                ],
            );
            None
        }
    }
}
