//! Frames: the vessel's placement in the plant, and the plant-design convention for
//! orientation angles.
//!
//! Vertical vessels and tanks: local +Z is plant up; the local frame is the plant
//! frame turned clockwise in plan by `rotation`. Orientation angles are plan angles
//! from plant north, clockwise.
//!
//! Horizontal vessels: local +Z is the axis, pointing along the plan bearing
//! `rotation` (clockwise from north); local +Y is plant up and +X = Y × Z.
//! Orientation angles are measured about the axis from the top, clockwise looking
//! from the left end (along +Z).

use rustc_hash::FxHashMap;

use glam::{DAffine3, DMat3, DVec3};

use super::Report;
use crate::format::{VesselDesign, VesselKind};

/// Vessel local frame → plant frame, for a placement already known to be finite.
pub fn vessel_frame(kind: VesselKind, position: [f64; 3], rotation_deg: f64) -> DAffine3 {
    let r = rotation_deg.to_radians();
    let (s, c) = r.sin_cos();
    let linear = match kind {
        VesselKind::Vertical | VesselKind::Tank => DMat3::from_rotation_z(-r),
        VesselKind::Horizontal => {
            DMat3::from_cols(DVec3::new(-c, s, 0.0), DVec3::Z, DVec3::new(s, c, 0.0))
        }
    };
    DAffine3::from_mat3_translation(linear, DVec3::from(position))
}

/// Unit direction, in the vessel's local XY plane, of an orientation angle (degrees)
/// by the plant convention for the vessel's kind (see the module doc).
pub fn orientation_direction(kind: VesselKind, rotation_deg: f64, orientation_deg: f64) -> DVec3 {
    match kind {
        VesselKind::Vertical | VesselKind::Tank => {
            let a = (orientation_deg - rotation_deg).to_radians();
            DVec3::new(a.sin(), a.cos(), 0.0)
        }
        VesselKind::Horizontal => {
            let a = orientation_deg.to_radians();
            DVec3::new(-a.sin(), a.cos(), 0.0)
        }
    }
}

/// Checks an angle given in degrees (an orientation, a rotation): finite and within
/// one turn either way, so that every angle has one obvious meaning. Reports and
/// returns `false` otherwise.
pub(super) fn check_angle(
    report: &mut Report,
    path: &str,
    entity: Option<&str>,
    field: &str,
    degrees: f64,
) -> bool {
    let ok = degrees.is_finite() && degrees.abs() <= 360.0;
    if !ok {
        report.push(
            path,
            entity,
            field,
            degrees,
            "must be a finite angle between -360 and 360 degrees",
        );
    }
    ok
}

/// The vessel frame, reporting non-finite placement numbers.
pub(super) fn checked_vessel_frame(vessel: &VesselDesign, report: &mut Report) -> DAffine3 {
    let p = vessel.placement;
    let mut ok = true;
    for (i, v) in p.position.iter().enumerate() {
        if !v.is_finite() || v.abs() > 1e9 {
            report.push(
                format!("placement.position[{i}]"),
                None,
                "position",
                v,
                "must be a finite number within ±1e9 mm",
            );
            ok = false;
        }
    }
    ok &= check_angle(report, "placement.rotation", None, "rotation", p.rotation);
    if vessel.tag.trim().is_empty() {
        report.push("tag", None, "tag", "\"\"", "a vessel needs a non-empty tag");
    }
    if ok {
        vessel_frame(vessel.kind, p.position, p.rotation)
    } else {
        DAffine3::IDENTITY
    }
}

/// Ids of parts, nozzles and notes share one namespace in a vessel (notes can target
/// any of them) and must be unique and non-empty.
pub(super) fn check_unique_ids(vessel: &VesselDesign, report: &mut Report) {
    /// Where an id sits: its list and index (its JSON path is only written
    /// for a violation).
    #[derive(Clone, Copy)]
    enum At<'a> {
        Part(usize, &'a str),
        Nozzle(usize),
        Note(usize),
    }
    let path = |at: At| match at {
        At::Part(i, kind) => format!("parts[{i}].{kind}.id"),
        At::Nozzle(i) => format!("nozzles[{i}].mark"),
        At::Note(i) => format!("notes[{i}].id"),
    };
    let mut seen: FxHashMap<&str, At> = FxHashMap::default();
    let ids = vessel
        .parts
        .iter()
        .enumerate()
        .map(|(i, p)| (p.id(), At::Part(i, p.kind()), "id"))
        .chain(
            vessel
                .nozzles
                .iter()
                .enumerate()
                .map(|(i, n)| (n.mark.as_str(), At::Nozzle(i), "mark")),
        )
        .chain(
            vessel
                .notes
                .iter()
                .enumerate()
                .map(|(i, n)| (n.id.as_str(), At::Note(i), "id")),
        );
    for (id, at, field) in ids {
        if id.trim().is_empty() {
            report.push(path(at), None, field, "\"\"", "must not be empty");
            continue;
        }
        if super::names::too_long(id) {
            // Named by its place: the entity would repeat the whole id.
            report.push(
                path(at),
                Some(""),
                field,
                super::names::shown(id),
                super::names::rule(),
            );
            continue;
        }
        if id == vessel.tag {
            report.push(
                path(at),
                Some(id),
                field,
                id,
                "must differ from the vessel tag",
            );
        }
        if let Some(&first) = seen.get(id) {
            report.push(
                path(at),
                Some(id),
                field,
                id,
                format!("duplicate id: already used at {}", path(first)),
            );
        } else {
            seen.insert(id, at);
        }
    }
}
