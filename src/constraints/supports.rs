//! Attached parts: skirt, saddles, legs, lugs and boot, placed against the laid-out
//! stack and fitted to the course they stand on or hang from.
//!
//! The skirt top and the legs' shell diameter follow the bottom course; a saddle
//! fits the OD of the shell at its position and defaults to 0.2 L from its tangent
//! line (first saddle from the left, second from the right); lugs and boot fit the
//! course at their elevation or position. A support placed off every cylindrical
//! course is an error.

use std::f64::consts::FRAC_PI_2;

use glam::{DAffine3, DMat3, DVec3};

use super::frames::check_angle;
use super::part_error::report_part_error;
use super::stack::Course;
use super::{Report, ResolvedPart, orientation_direction};
use crate::format::{HeadShape, PartDesign, VesselDesign, VesselKind};
use crate::parts::PartGeometry;
use crate::parts::heads::HeadKind;
use crate::parts::tables::{Nps, pipe};
use crate::parts::{Boot, Legs, Lugs, Saddle, Skirt};

/// Default plate thickness where the design gives none, mm.
const DEFAULT_PLATE: f64 = 12.0;

fn translate_z(z: f64) -> DAffine3 {
    DAffine3::from_translation(DVec3::new(0.0, 0.0, z))
}

/// The cylindrical course holding the axial interval `[a, b]`, if any.
pub(crate) fn cylinder_at(courses: &[Course], a: f64, b: f64) -> Option<&Course> {
    courses
        .iter()
        .find(|c| c.cylindrical && a >= c.start - 1e-9 && b <= c.end + 1e-9)
}

/// Plan angle (degrees counter-clockwise from local +X) of an orientation angle.
fn local_angle(vessel: &VesselDesign, orientation: f64) -> f64 {
    let d = orientation_direction(vessel.kind, vessel.placement.rotation, orientation);
    d.y.atan2(d.x).to_degrees()
}

/// Depth of the bottom head below the datum (0 without one).
fn bottom_depth(parts: &[Option<ResolvedPart>]) -> f64 {
    parts
        .iter()
        .flatten()
        .filter(|p| matches!(p.geometry, PartGeometry::Head(_)))
        .map(|p| -p.span.0)
        .fold(0.0, f64::max)
}

/// Places every attached part into `parts`.
pub(crate) fn place(
    vessel: &VesselDesign,
    courses: &[Course],
    tangent_length: f64,
    parts: &mut [Option<ResolvedPart>],
    report: &mut Report,
) {
    let Some(bottom) = courses.first() else {
        return;
    };
    let vertical = vessel.kind != VesselKind::Horizontal;
    let depth = bottom_depth(parts);
    let saddles: Vec<usize> = (0..vessel.parts.len())
        .filter(|&i| matches!(vessel.parts[i], PartDesign::Saddle(_)))
        .collect();
    for (i, part) in vessel.parts.iter().enumerate() {
        let path = format!("parts[{i}].{}", part.kind());
        let id = part.id();
        let wrong_kind = |report: &mut Report, needs: &str| {
            report.push(
                &path,
                Some(id),
                part.kind(),
                id,
                format!("a {} belongs under a {needs} vessel", part.kind()),
            );
        };
        // Legs and lugs stand round a vertical vessel, the first at an
        // orientation: whether both hold (each broken rule reported).
        let round_a_vertical = |report: &mut Report, orientation: f64| {
            if !vertical {
                wrong_kind(report, "vertical");
                return false;
            }
            let orientation_path = format!("{path}.orientation");
            check_angle(
                report,
                &orientation_path,
                Some(id),
                "orientation",
                orientation,
            )
        };
        let resolved = match part {
            PartDesign::Skirt(s) => {
                if !vertical {
                    wrong_kind(report, "vertical");
                    continue;
                }
                if let Some(n) = s.anchor_bolts
                    && !(2..=1000).contains(&n)
                {
                    report.push(
                        format!("{path}.anchor_bolts"),
                        Some(id),
                        "anchor_bolts",
                        f64::from(n),
                        "must be a number of anchor bolts from 2 to 1000",
                    );
                }
                if let Some(t) = s.base_ring_thickness
                    && !(t.is_finite() && t > 0.0 && s.base_ring_width > 0.0)
                {
                    report.push(
                        format!("{path}.base_ring_thickness"),
                        Some(id),
                        "base_ring_thickness",
                        t,
                        "must be a finite thickness > 0 mm of a base ring with base_ring_width > 0",
                    );
                }
                let skirt = Skirt {
                    top_diameter: bottom.d_start,
                    height: s.height,
                    flare_angle: s.flare_angle,
                    thickness: s.thickness.unwrap_or(DEFAULT_PLATE),
                    base_ring_width: s.base_ring_width,
                };
                if let Err(e) = skirt.validate() {
                    report_part_error(
                        report,
                        &path,
                        id,
                        &e,
                        &[("top_diameter", "od of the bottom course")],
                    );
                    continue;
                }
                if s.height <= depth {
                    report.push(format!("{path}.height"), Some(id), "height", s.height, format!("must exceed the bottom head's depth ({depth:.1} mm) so the head clears the foundation"));
                    continue;
                }
                ResolvedPart {
                    id: id.to_string(),
                    frame: translate_z(-s.height),
                    geometry: PartGeometry::Skirt(skirt),
                    span: (-s.height, 0.0),
                    host: None,
                }
            }
            PartDesign::Saddle(s) => {
                if vertical {
                    wrong_kind(report, "horizontal");
                    continue;
                }
                let k = saddles.iter().position(|&j| j == i).unwrap_or(0);
                let position = match (s.position, saddles.len(), k) {
                    (Some(p), _, _) => p,
                    (None, 2, 0) => 0.2 * tangent_length,
                    (None, 2, _) => 0.8 * tangent_length,
                    (None, n, _) => {
                        report.push(format!("{path}.position"), Some(id), "position", "missing", format!("the default positions (0.2 L from each tangent line) need exactly two saddles, this vessel has {n}: give a position"));
                        continue;
                    }
                };
                if !position.is_finite() {
                    report.push(
                        format!("{path}.position"),
                        Some(id),
                        "position",
                        position,
                        "must be a finite number",
                    );
                    continue;
                }
                if let Some(w) = s.wear_plate
                    && !(w.is_finite() && w > 0.0)
                {
                    report.push(
                        format!("{path}.wear_plate"),
                        Some(id),
                        "wear_plate",
                        w,
                        "must be a finite thickness > 0 mm (leave it out for no wear plate)",
                    );
                    continue;
                }
                if !s.width.is_finite() || s.width >= tangent_length / 2.0 {
                    report.push(
                        format!("{path}.width"),
                        Some(id),
                        "width",
                        s.width,
                        format!(
                            "must be less than half the tangent length ({:.1} mm)",
                            tangent_length / 2.0
                        ),
                    );
                    continue;
                }
                let Some(course) =
                    cylinder_at(courses, position - s.width / 2.0, position + s.width / 2.0)
                else {
                    report.push(
                        format!("{path}.position"),
                        Some(id),
                        "position",
                        position,
                        "the saddle must stand wholly under one cylindrical shell course",
                    );
                    continue;
                };
                let web = s.web_thickness.unwrap_or(DEFAULT_PLATE);
                let half = (s.contact_angle.to_radians() / 2.0).min(FRAC_PI_2);
                let chord = course.d_start * half.sin();
                let saddle = Saddle {
                    shell_diameter: course.d_start,
                    contact_angle: s.contact_angle,
                    width: s.width,
                    height: s.height,
                    web_thickness: web,
                    base_length: chord + 2.0 * s.width.min(100.0),
                    base_width: s.width,
                    base_thickness: web,
                };
                if let Err(e) = saddle.validate() {
                    report_part_error(
                        report,
                        &path,
                        id,
                        &e,
                        &[("shell_diameter", "od of the shell it carries")],
                    );
                    continue;
                }
                ResolvedPart {
                    id: id.to_string(),
                    // On its course's axis (offset beyond an eccentric reducer).
                    frame: DAffine3::from_translation(course.axis_at(position)),
                    geometry: PartGeometry::Saddle(saddle),
                    span: (position - s.width / 2.0, position + s.width / 2.0),
                    host: None,
                }
            }
            PartDesign::Legs(l) => {
                if !round_a_vertical(report, l.orientation) {
                    continue;
                }
                let nps = match Nps::try_new(l.size) {
                    Ok(n) => n,
                    Err(e) => {
                        report.push(
                            format!("{path}.size"),
                            Some(id),
                            "size",
                            l.size,
                            e.to_string(),
                        );
                        continue;
                    }
                };
                let legs = Legs {
                    count: l.count,
                    pipe_diameter: pipe(nps).outside_diameter,
                    length: l.length,
                    shell_diameter: bottom.d_start,
                    first_angle: local_angle(vessel, l.orientation),
                };
                if let Err(e) = legs.validate() {
                    report_part_error(
                        report,
                        &path,
                        id,
                        &e,
                        &[
                            ("pipe_diameter", "size"),
                            ("shell_diameter", "od of the bottom course"),
                            ("first_angle", "orientation"),
                        ],
                    );
                    continue;
                }
                if l.length <= depth {
                    report.push(
                        format!("{path}.length"),
                        Some(id),
                        "length",
                        l.length,
                        format!("must exceed the bottom head's depth ({depth:.1} mm)"),
                    );
                    continue;
                }
                ResolvedPart {
                    id: id.to_string(),
                    frame: translate_z(-l.length),
                    geometry: PartGeometry::Legs(legs),
                    span: (-l.length, 0.0),
                    host: None,
                }
            }
            PartDesign::Lugs(l) => {
                if !round_a_vertical(report, l.orientation) {
                    continue;
                }
                let Some(course) =
                    cylinder_at(courses, l.elevation, l.elevation + l.height.max(0.0))
                else {
                    report.push(
                        format!("{path}.elevation"),
                        Some(id),
                        "elevation",
                        l.elevation,
                        "the lugs must sit wholly on one cylindrical shell course",
                    );
                    continue;
                };
                let lugs = Lugs {
                    count: l.count,
                    shell_diameter: course.d_start,
                    height: l.height,
                    projection: l.projection,
                    width: l.width,
                    first_angle: local_angle(vessel, l.orientation),
                };
                if let Err(e) = lugs.validate() {
                    report_part_error(
                        report,
                        &path,
                        id,
                        &e,
                        &[
                            ("shell_diameter", "od of the course they sit on"),
                            ("first_angle", "orientation"),
                        ],
                    );
                    continue;
                }
                ResolvedPart {
                    id: id.to_string(),
                    frame: DAffine3::from_translation(course.axis_at(l.elevation)),
                    geometry: PartGeometry::Lugs(lugs),
                    span: (l.elevation, l.elevation + l.height),
                    host: None,
                }
            }
            PartDesign::Boot(b) => {
                if vertical {
                    wrong_kind(report, "horizontal");
                    continue;
                }
                let Some(course) = cylinder_at(
                    courses,
                    b.position - b.od.abs() / 2.0,
                    b.position + b.od.abs() / 2.0,
                ) else {
                    report.push(
                        format!("{path}.position"),
                        Some(id),
                        "position",
                        b.position,
                        "the boot must hang wholly under one cylindrical shell course",
                    );
                    continue;
                };
                let head = match b.head {
                    HeadShape::Hemispherical => HeadKind::Hemispherical,
                    HeadShape::Ellipsoidal => HeadKind::TWO_TO_ONE,
                    HeadShape::Torispherical => HeadKind::asme_fd(b.od),
                    HeadShape::Toriconical => HeadKind::Toriconical {
                        half_angle: 30.0,
                        knuckle_radius: 0.06 * b.od,
                    },
                    HeadShape::Conical => HeadKind::Conical {
                        half_angle: 30.0,
                        small_diameter: 0.0,
                    },
                    HeadShape::Flat => HeadKind::Flat {
                        knuckle_radius: 0.0,
                    },
                };
                let boot = Boot::new(b.od, b.length, course.d_start).with_head(head);
                if let Err(e) = boot.validate() {
                    report_part_error(
                        report,
                        &path,
                        id,
                        &e,
                        &[
                            ("diameter", "od"),
                            ("host_diameter", "od of the shell it hangs from"),
                        ],
                    );
                    continue;
                }
                // Boot +Z points down (vessel −Y).
                let frame = DAffine3::from_mat3_translation(
                    DMat3::from_rotation_x(FRAC_PI_2),
                    course.axis_at(b.position),
                );
                ResolvedPart {
                    id: id.to_string(),
                    frame,
                    geometry: PartGeometry::Boot(boot),
                    span: (b.position - b.od / 2.0, b.position + b.od / 2.0),
                    host: Some(course.part),
                }
            }
            _ => continue,
        };
        parts[i] = Some(resolved);
    }
    check_saddles_apart(&saddles, parts, report);
}

/// Two saddles may not overlap along the axis (the default positions never do; two
/// given positions can).
fn check_saddles_apart(saddles: &[usize], parts: &[Option<ResolvedPart>], report: &mut Report) {
    let placed: Vec<(usize, &ResolvedPart)> = saddles
        .iter()
        .filter_map(|&i| parts[i].as_ref().map(|p| (i, p)))
        .collect();
    for (k, &(i, p)) in placed.iter().enumerate() {
        if let Some((_, q)) = placed[..k]
            .iter()
            .find(|(_, q)| p.span.0 < q.span.1 && q.span.0 < p.span.1)
        {
            report.push(
                format!("parts[{i}].saddle.position"),
                Some(&p.id),
                "position",
                0.5 * (p.span.0 + p.span.1),
                format!(
                    "the saddle (from {} to {} mm) overlaps saddle {} (from {} to {} mm)",
                    p.span.0, p.span.1, q.id, q.span.0, q.span.1
                ),
            );
        }
    }
}
