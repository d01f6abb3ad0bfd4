//! Nozzles on their hosts: the nozzle-on-host relation.
//!
//! A shell (or reducer) nozzle is radial: its axis leaves the vessel axis at its
//! elevation in the direction of its orientation, and its projection is measured
//! from the vessel axis to the flange face. A head nozzle is parallel to the vessel
//! axis at `offset` from the head centreline, and its projection is measured from
//! the head's tangent line. Because the frame is derived from the host every time,
//! a nozzle stays on its host when the host's diameter, length or position changes:
//! orientation and elevation are kept and the neck length adapts to keep the
//! projection.

use glam::{DAffine3, DMat3, DVec3};

use super::clearances::Body;
use super::footprints::Footprint;
use super::frames::check_angle;
use super::part_error::report_part_error;
use super::shell_nozzle::{self, MAX_HILLSIDE, MAX_INCLINATION};
use super::stack::Course;
use super::support_clearances;
use super::{Report, ResolvedNozzle, ResolvedPart, ShowValue, orientation_direction};
use crate::format::{FacingDesign, FlangeDesign, NozzleDesign, VesselDesign};
use crate::parts::PartGeometry;
use crate::parts::tables::{FlangeClass, Nps, PipeSchedule, flange};
use crate::parts::{Facing, FlangeType, Nozzle};

/// Parses a schedule name as written in design files.
pub(crate) fn parse_schedule(name: &str) -> Option<PipeSchedule> {
    Some(match name.to_ascii_uppercase().as_str() {
        "STD" => PipeSchedule::Std,
        "XS" => PipeSchedule::Xs,
        "40" => PipeSchedule::S40,
        "80" => PipeSchedule::S80,
        "160" => PipeSchedule::S160,
        "XXS" => PipeSchedule::Xxs,
        _ => return None,
    })
}

/// The nozzle part parameters of a design nozzle, or `None` after reporting.
fn nozzle_part(n: &NozzleDesign, path: &str, report: &mut Report) -> Option<Nozzle> {
    let id = Some(n.mark.as_str());
    let nps = Nps::try_new(n.size)
        .map_err(|e| report.push(format!("{path}.size"), id, "size", n.size, e.to_string()))
        .ok();
    let class = FlangeClass::try_from_rating(n.rating)
        .map_err(|_| {
            report.push(
                format!("{path}.rating"),
                id,
                "rating",
                n.rating,
                "expected one of 150, 300, 600, 900",
            )
        })
        .ok();
    let schedule = parse_schedule(&n.schedule);
    if schedule.is_none() {
        report.push(
            format!("{path}.schedule"),
            id,
            "schedule",
            format!("{:?}", n.schedule),
            "expected one of STD, XS, 40, 80, 160, XXS",
        );
    }
    let flange = match n.flange {
        FlangeDesign::WeldNeck => FlangeType::WeldNeck,
        FlangeDesign::SlipOn => FlangeType::SlipOn,
        FlangeDesign::Blind => FlangeType::Blind,
    };
    let facing = match n.facing {
        FacingDesign::RaisedFace => Facing::RaisedFace,
        FacingDesign::FlatFace => Facing::FlatFace,
        FacingDesign::RingJoint => Facing::RingJoint,
    };
    Some(Nozzle {
        nps: nps?,
        schedule: schedule?,
        class: class?,
        flange,
        facing,
        projection: n.projection,
    })
}

/// The least clearance, mm, between an opening of reach `reach` (neck or pad
/// OD) and either end of its course: 5 % of the reach, at least 5 mm. An
/// opening touching the end leaves the course's region pinched to a point at
/// the seam, which cannot be meshed.
pub(crate) fn end_gap(reach: f64) -> f64 {
    (0.05 * reach).max(5.0)
}

/// The seams between a head's dished patches (each patch's start but the
/// first's, inside the head's radius: the knuckle–crown joint, not the tangent
/// line): their radii from the axis and whether a reinforcing pad may cross
/// them (a knuckle and the crown, cone or plate tangent to it, see
/// [`Analytic::knuckled`](crate::parts::Analytic::knuckled)).
fn head_seams(head: &crate::parts::heads::Head) -> Vec<(f64, bool)> {
    let radius = head.outside_diameter / 2.0;
    head.patches().map_or(Vec::new(), |patches| {
        patches
            .windows(2)
            .filter_map(|w| {
                let start = *w[1]
                    .surface
                    .boundary(crate::nurbs::Side::VMin)
                    .control_points()
                    .first()?;
                let r = start.truncate().length();
                let crossable =
                    crate::parts::Analytic::knuckled(&w[0].analytic, &w[1].analytic, start)
                        .is_some();
                (r < radius * (1.0 - 1e-9)).then_some((r, crossable))
            })
            .collect()
    })
}

/// Why a reinforcing pad of `pad_od` on a nozzle at `offset` from the axis of
/// `head` cannot be built across its seams, if it cannot (the end of a
/// sentence naming the pad first): it reaches a seam it may not cross, comes
/// within the end gap of one without crossing it by more, goes round the
/// centre across one, or crosses two.
fn pad_seam_refusal(head: &crate::parts::heads::Head, offset: f64, pad_od: f64) -> Option<String> {
    let gap = end_gap(pad_od);
    let (near, far) = (offset - pad_od / 2.0, offset + pad_od / 2.0);
    let reached: Vec<(f64, bool)> = head_seams(head)
        .into_iter()
        .filter(|&(r, _)| near.max(0.0) - gap <= r && r <= far + gap)
        .collect();
    match reached.as_slice() {
        [] => None,
        [(r, true)] if near > 0.0 && near + gap < *r && *r < far - gap => None,
        [(r, true)] if near <= 0.0 => Some(format!(
            "reaches the seam at {r:.1} mm from the axis and goes round the head's \
             centre: a pad may cross the knuckle's seam only off the centre (its inner \
             edge, offset − OD/2 = {near:.1} mm, must be > 0)"
        )),
        [(r, true)] => Some(format!(
            "comes within {gap} mm of the seam at {r:.1} mm from the axis (it spans \
             {near:.1} to {far:.1} mm): a pad must cross that seam by more than {gap} mm \
             on both sides or stay {gap} mm clear of it"
        )),
        [(r, false)] => Some(format!(
            "reaches across or within {gap} mm of the seam at {r:.1} mm from the axis, \
             between patches that are not a knuckle and the crown, cone or plate tangent \
             to it: a pad must lie on one patch there"
        )),
        _ => Some(format!(
            "reaches {} seams (it spans {near:.1} to {far:.1} mm from the axis): a pad may \
             cross one seam only",
            reached.len()
        )),
    }
}

/// A frame whose +Z is `axis` (unit) and whose +X is `x_hint` made orthogonal.
fn frame_along(origin: DVec3, axis: DVec3, x_hint: DVec3) -> DAffine3 {
    let x = (x_hint - axis * x_hint.dot(axis))
        .try_normalize()
        .unwrap_or_else(|| axis.any_orthonormal_vector());
    let y = axis.cross(x);
    DAffine3::from_mat3_translation(DMat3::from_cols(x, y, axis), origin)
}

/// Places a hillside or inclined nozzle `n` at elevation `z` on its cylindrical
/// `course` (see `shell_nozzle`), checking that its opening (of diameter
/// `reach`, the neck or pad OD) lies on the course's face and within its span
/// and that its flange is clear of it; `None` after reporting.
#[expect(
    clippy::too_many_arguments,
    reason = "one call site, all of its context"
)]
fn place_non_radial(
    n: &NozzleDesign,
    path: &str,
    vessel: &VesselDesign,
    course: &Course,
    z: f64,
    reach: f64,
    reach_name: &str,
    flange_length: f64,
    report: &mut Report,
) -> Option<shell_nozzle::Placement> {
    let id = Some(n.mark.as_str());
    let offset = n.offset.unwrap_or(0.0);
    let radius = course.d_start / 2.0;
    let rotation = vessel.placement.rotation;
    let dir = orientation_direction(vessel.kind, rotation, n.orientation);
    let side = orientation_direction(vessel.kind, rotation, n.orientation + 90.0);
    if offset.abs() + reach / 2.0 > MAX_HILLSIDE * radius {
        report.push(
            format!("{path}.offset"),
            id,
            "offset",
            offset,
            format!(
                "|offset| + half the {reach_name} ({} mm) must be at most {MAX_HILLSIDE} of \
                 the host {}'s radius {radius} mm (a tangential nozzle's neck must still \
                 cross the shell)",
                reach / 2.0,
                n.host
            ),
        );
        return None;
    }
    let inclination = n.inclination.unwrap_or(0.0);
    let placed = shell_nozzle::place(
        course.axis_at(z),
        radius,
        dir,
        side,
        offset,
        inclination,
        reach / 2.0,
    )?;
    let gap = end_gap(reach);
    if placed.axial.0 < course.start + gap || placed.axial.1 > course.end - gap {
        report.push(
            format!("{path}.elevation"),
            id,
            "elevation",
            z,
            format!(
                "the opening of the {reach_name} {reach} mm (offset {offset} mm, inclined \
                 {inclination}°) spans {:.1} to {:.1} mm, which must lie within its host {}, \
                 which spans {} to {} mm, at least {gap} mm clear of its ends",
                placed.axial.0, placed.axial.1, n.host, course.start, course.end
            ),
        );
        return None;
    }
    if n.projection - flange_length <= placed.depth {
        report.push(
            format!("{path}.projection"),
            id,
            "projection",
            n.projection,
            format!(
                "must exceed the opening's farthest point along the nozzle axis ({:.1} mm) \
                 plus the flange length {flange_length} mm",
                placed.depth
            ),
        );
        return None;
    }
    Some(placed)
}

/// Resolves every nozzle against the resolved parts.
pub(crate) fn place(
    vessel: &VesselDesign,
    parts: &[Option<ResolvedPart>],
    courses: &[Course],
    report: &mut Report,
) -> Vec<ResolvedNozzle> {
    let mut out = Vec::new();
    // The openings already cut into the vessel's parts: its boots', then each
    // placed nozzle's.
    let mut footprints: Vec<Footprint> =
        parts.iter().flatten().filter_map(Footprint::boot).collect();
    // The bodies (neck, flange) of each placed nozzle, by mark.
    let mut bodies: Vec<(String, [Body; 2])> = Vec::new();
    // What the nozzles must keep clear of: the supports' pieces.
    let supports = support_clearances::supports(vessel, parts);
    for (k, n) in vessel.nozzles.iter().enumerate() {
        let path = format!("nozzles[{k}]");
        let id = Some(n.mark.as_str());
        let Some(host) = vessel.parts.iter().position(|p| p.id() == n.host) else {
            report.push(
                format!("{path}.host"),
                id,
                "host",
                &n.host,
                "no part of this vessel has that id",
            );
            continue;
        };
        let part = nozzle_part(n, &path, report);
        if !check_angle(
            report,
            &format!("{path}.orientation"),
            id,
            "orientation",
            n.orientation,
        ) {
            continue;
        }
        let (Some(mut nozzle), Some(resolved_host)) = (part, parts[host].as_ref()) else {
            continue; // reported already
        };
        let flange_length = match nozzle.flange_length() {
            Ok(f) => f,
            Err(e) => {
                report_part_error(report, &path, &n.mark, &e, &[]);
                continue;
            }
        };
        let pipe_od = nozzle.outside_diameter();
        let pad = match n.pad {
            None => None,
            Some(p) => {
                if !(p.od.is_finite() && p.od > pipe_od && p.od <= 1e6) {
                    report.push(
                        format!("{path}.pad.od"),
                        id,
                        "od",
                        p.od,
                        format!("the pad OD must exceed the nozzle OD ({pipe_od} mm)"),
                    );
                    continue;
                }
                if !(p.thickness.is_finite() && p.thickness > 0.0 && p.thickness <= 1e3) {
                    report.push(
                        format!("{path}.pad.thickness"),
                        id,
                        "thickness",
                        p.thickness,
                        "must be a finite number between 0 and 1000 mm",
                    );
                    continue;
                }
                Some((p.od, p.thickness))
            }
        };
        // The footprint on the host: the pad where there is one, else the neck.
        let reach = pad.map_or(pipe_od, |p| p.0);
        let reach_name = if pad.is_some() { "pad OD" } else { "nozzle OD" };
        let dir = orientation_direction(vessel.kind, vessel.placement.rotation, n.orientation);
        // Height along the nozzle axis where it meets its host (for clearances).
        let surface_z: f64;
        // A non-radial shell nozzle's footprint (centre, radius), from its opening.
        let mut shell_footprint: Option<(DVec3, f64)> = None;
        let frame = match &resolved_host.geometry {
            PartGeometry::Shell(_) | PartGeometry::Reducer(_) => {
                let cylindrical = matches!(resolved_host.geometry, PartGeometry::Shell(_));
                let mut non_radial = false;
                let mut refused = false;
                for (field, value) in [("offset", n.offset), ("inclination", n.inclination)] {
                    let Some(value) = value else { continue };
                    if !cylindrical {
                        report.push(
                            format!("{path}.{field}"),
                            id,
                            field,
                            value,
                            "hillside and inclined nozzles mount on cylindrical shell \
                             courses only; a nozzle on a reducer is radial",
                        );
                        refused = true;
                        continue;
                    }
                    let (limit, rule) = if field == "offset" {
                        (1e6, "must be a finite number within ±1e6 mm".to_string())
                    } else {
                        (
                            MAX_INCLINATION,
                            format!(
                                "must be a finite angle between -{MAX_INCLINATION} and \
                                 {MAX_INCLINATION} degrees (from the course's cross-section)"
                            ),
                        )
                    };
                    if !(value.is_finite() && value.abs() <= limit) {
                        report.push(format!("{path}.{field}"), id, field, value, rule);
                        refused = true;
                    }
                    non_radial |= value != 0.0;
                }
                if refused {
                    continue;
                }
                let Some(z) = n.elevation.filter(|z| z.is_finite()) else {
                    report.push(
                        format!("{path}.elevation"),
                        id,
                        "elevation",
                        n.elevation.map_or("missing".to_string(), |z| z.show()),
                        "a shell nozzle needs a finite elevation (position along the axis)",
                    );
                    continue;
                };
                let Some(course) = courses.iter().find(|c| c.part == host) else {
                    continue;
                };
                let host_od = course.diameter_at(z);
                let smallest_od = course.d_start.min(course.d_end);
                if pipe_od >= smallest_od {
                    report.push(format!("{path}.size"), id, "size", n.size, format!("the nozzle OD {pipe_od} mm must be smaller than its host {}'s OD {smallest_od} mm", n.host));
                    continue;
                }
                if let Some((pad_od, _)) = pad
                    && pad_od >= smallest_od
                {
                    report.push(
                        format!("{path}.pad.od"),
                        id,
                        "od",
                        pad_od,
                        format!(
                            "the pad OD must be smaller than its host {}'s OD {smallest_od} mm",
                            n.host
                        ),
                    );
                    continue;
                }
                if non_radial {
                    let Some(placed) = place_non_radial(
                        n,
                        &path,
                        vessel,
                        course,
                        z,
                        reach,
                        reach_name,
                        flange_length,
                        report,
                    ) else {
                        continue;
                    };
                    shell_footprint = Some((placed.centre, placed.radius));
                    surface_z = (placed.centre - placed.frame.translation).length();
                    placed.frame
                } else {
                    let gap = end_gap(reach);
                    if z - reach / 2.0 < course.start + gap || z + reach / 2.0 > course.end - gap {
                        report.push(format!("{path}.elevation"), id, "elevation", z, format!("the {reach_name} {reach} mm centred here must lie within its host {}, which spans {} to {} mm, at least {gap} mm clear of its ends (an opening touching a course's end leaves no shell between it and the seam)", n.host, course.start, course.end));
                        continue;
                    }
                    if n.projection - flange_length <= host_od / 2.0 {
                        report.push(format!("{path}.projection"), id, "projection", n.projection, format!("must exceed the host radius {} mm plus the flange length {flange_length} mm", host_od / 2.0));
                        continue;
                    }
                    surface_z = host_od / 2.0;
                    // Radial from the course's own axis (offset beyond an eccentric
                    // reducer; along an eccentric reducer, its cross-section's centre).
                    frame_along(course.axis_at(z), dir, DVec3::Z)
                }
            }
            PartGeometry::Head(head) => {
                if n.elevation.is_some() {
                    report.push(
                        format!("{path}.elevation"),
                        id,
                        "elevation",
                        n.elevation.unwrap_or(0.0),
                        "applies to shell nozzles only; head nozzles take an offset",
                    );
                    continue;
                }
                if let Some(inclination) = n.inclination {
                    report.push(
                        format!("{path}.inclination"),
                        id,
                        "inclination",
                        inclination,
                        "applies to shell nozzles only; a head nozzle is parallel to the \
                         vessel axis",
                    );
                    continue;
                }
                let offset = n.offset.unwrap_or(0.0);
                let radius = head.outside_diameter / 2.0;
                if !(offset.is_finite() && offset >= 0.0) {
                    report.push(
                        format!("{path}.offset"),
                        id,
                        "offset",
                        offset,
                        "must be a finite number ≥ 0",
                    );
                    continue;
                }
                if pipe_od >= head.outside_diameter {
                    report.push(format!("{path}.size"), id, "size", n.size, format!("the nozzle OD {pipe_od} mm must be smaller than its host {}'s OD {} mm", n.host, head.outside_diameter));
                    continue;
                }
                if offset + reach / 2.0 >= radius {
                    report.push(format!("{path}.offset"), id, "offset", offset, format!("offset + half the {reach_name} ({} mm) must stay inside the head radius {radius} mm", reach / 2.0));
                    continue;
                }
                if let Some((pad_od, _)) = pad
                    && offset >= pipe_od / 2.0
                    && offset <= pad_od / 2.0
                {
                    report.push(format!("{path}.offset"), id, "offset", offset, format!("a reinforcing pad round the head's centre (pad OD {pad_od} mm) needs its nozzle round the centre too: the offset must be below the neck radius {} mm, or above the pad radius {} mm", pipe_od / 2.0, pad_od / 2.0));
                    continue;
                }
                // A pad is laid out on one patch of its head, or across the one
                // seam between a knuckle and the crown, cone or plate tangent to
                // it (the two joined: `mesh::cut`): its footprint may reach no
                // other seam (nor come within the end gap of one), and crosses
                // that one by more than the gap, off the head's centre.
                if let Some((pad_od, _)) = pad
                    && let Some(refusal) = pad_seam_refusal(head, offset, pad_od)
                {
                    report.push(format!("{path}.offset"), id, "offset", offset, format!("the reinforcing pad (OD {pad_od} mm) on head {} {refusal}: move the nozzle or change the pad's OD", n.host));
                    continue;
                }
                // The neck meets the head highest on its side nearest the axis
                // (the head's height falls with the radius): it must end above
                // that, not only above the centre of the opening.
                let highest = (offset - pipe_od / 2.0).max(0.0);
                let rise = head.height_at_radius(highest).unwrap_or(0.0) - head.straight_flange;
                if n.projection - flange_length <= rise {
                    report.push(format!("{path}.projection"), id, "projection", n.projection, format!("must exceed the head's height where the neck meets it highest ({rise:.1} mm, at {highest:.1} mm from the axis) plus the flange length {flange_length} mm"));
                    continue;
                }
                // Work in the head's local frame (dome towards +Z), then map.
                let inverse = resolved_host.frame.matrix3.inverse();
                let local_dir = inverse * dir;
                let origin = DVec3::new(
                    local_dir.x * offset,
                    local_dir.y * offset,
                    head.straight_flange,
                );
                surface_z = rise;
                resolved_host.frame * frame_along(origin, DVec3::Z, DVec3::X)
            }
            other => {
                report.push(
                    format!("{path}.host"),
                    id,
                    "host",
                    &n.host,
                    format!(
                        "nozzles mount on shells, reducers or heads, not on a {}",
                        other.kind()
                    ),
                );
                continue;
            }
        };
        if let Err(e) = nozzle.validate() {
            report_part_error(report, &path, &n.mark, &e, &[]);
            continue;
        }
        nozzle.projection = n.projection;
        let footprint = match shell_footprint {
            Some((centre, radius)) => Footprint::opening(&n.mark, centre, radius),
            None => {
                let centre = frame.transform_point3(DVec3::new(0.0, 0.0, surface_z));
                Footprint::nozzle(&n.mark, centre, reach)
            }
        };
        if let Some(other) = footprints.iter().find(|f| f.overlaps(&footprint)) {
            report.push(
                format!("{path}.mark"),
                id,
                "mark",
                &n.mark,
                format!(
                    "its opening (reach {reach} mm) overlaps the opening of {}: move one of them",
                    other.name
                ),
            );
            continue;
        }
        let axis = frame.matrix3 * DVec3::Z;
        let flange_od = flange(nozzle.nps, nozzle.class).map_or(pipe_od, |d| d.outside_diameter);
        let back = n.projection - flange_length;
        let body = |name, from, to, diameter: f64| Body {
            name,
            origin: frame.translation,
            axis: axis.normalize(),
            from,
            to,
            radius: diameter / 2.0,
        };
        let mine = [
            body("neck", surface_z, back, pipe_od),
            body("flange", back, n.projection, flange_od),
        ];
        if let Some((mark, theirs, ours)) =
            bodies
                .iter()
                .find_map(|(mark, theirs): &(String, [Body; 2])| {
                    theirs.iter().find_map(|t| {
                        mine.iter()
                            .find(|m| m.meets(t))
                            .map(|m| (mark, t.name, m.name))
                    })
                })
        {
            report.push(
                format!("{path}.mark"),
                id,
                "mark",
                &n.mark,
                format!(
                    "its {ours} collides with the {theirs} of nozzle {mark}: move one of them \
                     (change its orientation, elevation or offset, or its projection)"
                ),
            );
            continue;
        }
        if let Some((support, (ours, piece))) = supports
            .iter()
            .find_map(|s| s.clash(&footprint, &mine).map(|c| (s, c)))
        {
            let (field, value) = match resolved_host.geometry {
                PartGeometry::Head(_) => ("offset", n.offset.unwrap_or(0.0)),
                _ => ("elevation", n.elevation.unwrap_or(0.0)),
            };
            report.push(
                format!("{path}.{field}"),
                id,
                field,
                value,
                format!(
                    "its {ours} (the {reach_name} {reach} mm, flange OD {flange_od} mm) reaches \
                     the {piece} of {} ({}.{}): a nozzle must clear the supports; move the \
                     nozzle (its {field}, orientation or projection) or the support",
                    support.name, report.prefix, support.path
                ),
            );
            continue;
        }
        bodies.push((n.mark.clone(), mine));
        footprints.push(footprint);
        out.push(ResolvedNozzle {
            mark: n.mark.clone(),
            host,
            frame,
            geometry: nozzle,
            pad,
        });
    }
    out
}
