//! Notes follow their targets: a note's anchor is derived from its target (the
//! vessel, a part, a nozzle's flange face, or another note's text position) every
//! time the layout is resolved. Note-to-note references must not form a cycle.

use glam::DVec3;

use super::{NoteTarget, Report, ResolvedNote, ResolvedNozzle, ResolvedPart};
use crate::design::VesselDesign;
use crate::parts::MAX_DIMENSION;

/// Resolves every note's target and anchor; reports unknown targets and cycles.
pub(crate) fn place(
    vessel: &VesselDesign,
    parts: &[Option<ResolvedPart>],
    nozzles: &[ResolvedNozzle],
    report: &mut Report,
) -> Vec<ResolvedNote> {
    let n = vessel.notes.len();
    let mut targets = Vec::with_capacity(n);
    for (k, note) in vessel.notes.iter().enumerate() {
        let t = &note.target;
        let target = if *t == vessel.tag {
            Some(NoteTarget::Vessel)
        } else if let Some(i) = vessel.parts.iter().position(|p| p.id() == t) {
            Some(NoteTarget::Part(i))
        } else if let Some(i) = nozzles.iter().position(|z| z.mark == *t) {
            Some(NoteTarget::Nozzle(i))
        } else if let Some(i) = vessel.notes.iter().position(|m| m.id == *t) {
            Some(NoteTarget::Note(i))
        } else if vessel.nozzles.iter().any(|z| z.mark == *t) {
            None // the nozzle itself failed and was reported
        } else {
            report.push(
                format!("notes[{k}].target"),
                Some(&note.id),
                "target",
                t,
                "no vessel, part, nozzle or note has that id",
            );
            None
        };
        for (axis, v) in note.offset.iter().enumerate() {
            if !(v.is_finite() && v.abs() <= MAX_DIMENSION) {
                report.push(
                    format!("notes[{k}].offset[{axis}]"),
                    Some(&note.id),
                    "offset",
                    v,
                    format!("must be a finite number within ±{MAX_DIMENSION} mm"),
                );
            }
        }
        targets.push(target);
    }
    // Resolve in dependency order; whatever is left unresolved lies on a cycle.
    let mut positions: Vec<Option<DVec3>> = vec![None; n];
    let mut anchors: Vec<DVec3> = vec![DVec3::ZERO; n];
    let mut progress = true;
    while progress {
        progress = false;
        for k in 0..n {
            if positions[k].is_some() {
                continue;
            }
            let anchor = match targets[k] {
                None => continue,
                Some(NoteTarget::Vessel) => Some(DVec3::ZERO),
                Some(NoteTarget::Part(i)) => parts[i]
                    .as_ref()
                    // On the part's own axis (offset beyond an eccentric reducer).
                    .map(|p| {
                        let t = p.frame.translation;
                        DVec3::new(t.x, t.y, 0.5 * (p.span.0 + p.span.1))
                    }),
                Some(NoteTarget::Nozzle(i)) => Some(nozzles[i].frame.transform_point3(DVec3::new(
                    0.0,
                    0.0,
                    nozzles[i].geometry.projection,
                ))),
                Some(NoteTarget::Note(i)) => positions[i],
            };
            if let Some(a) = anchor {
                anchors[k] = a;
                positions[k] = Some(a + DVec3::from(vessel.notes[k].offset));
                progress = true;
            }
        }
    }
    let mut out = Vec::with_capacity(n);
    for (k, note) in vessel.notes.iter().enumerate() {
        match (targets[k], positions[k]) {
            (Some(target), Some(position)) => out.push(ResolvedNote {
                id: note.id.clone(),
                target,
                anchor: anchors[k],
                position,
            }),
            (Some(NoteTarget::Note(_)), None) => {
                report.push(
                    format!("notes[{k}].target"),
                    Some(&note.id),
                    "target",
                    &note.target,
                    "notes refer to each other in a cycle",
                );
            }
            _ => {}
        }
    }
    out
}
