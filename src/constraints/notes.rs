//! Notes follow their targets: a note's anchor is derived from its target (the
//! vessel, a part, a nozzle's flange face, or another note's text position) every
//! time the layout is resolved. Note-to-note references must not form a cycle.

use glam::DVec3;
use rustc_hash::{FxHashMap, FxHashSet};

use super::{NoteTarget, Report, ResolvedNote, ResolvedNozzle, ResolvedPart};
use crate::format::VesselDesign;
use crate::parts::MAX_DIMENSION;

/// Resolves every note's target and anchor; reports unknown targets and cycles.
pub(crate) fn place(
    vessel: &VesselDesign,
    parts: &[Option<ResolvedPart>],
    nozzles: &[ResolvedNozzle],
    report: &mut Report,
) -> Vec<ResolvedNote> {
    let n = vessel.notes.len();
    // Ids to places, the first of each (duplicates are reported elsewhere), so
    // that finding a target costs the same however many there are.
    let mut part_at: FxHashMap<&str, usize> = FxHashMap::default();
    for (i, p) in vessel.parts.iter().enumerate() {
        part_at.entry(p.id()).or_insert(i);
    }
    let mut nozzle_at: FxHashMap<&str, usize> = FxHashMap::default();
    for (i, z) in nozzles.iter().enumerate() {
        nozzle_at.entry(z.mark.as_str()).or_insert(i);
    }
    let designed: FxHashSet<&str> = vessel.nozzles.iter().map(|z| z.mark.as_str()).collect();
    let mut note_at: FxHashMap<&str, usize> = FxHashMap::default();
    for (i, m) in vessel.notes.iter().enumerate() {
        note_at.entry(m.id.as_str()).or_insert(i);
    }
    let mut targets = Vec::with_capacity(n);
    for (k, note) in vessel.notes.iter().enumerate() {
        let t = &note.target;
        let target = if *t == vessel.tag {
            Some(NoteTarget::Vessel)
        } else if let Some(&i) = part_at.get(t.as_str()) {
            Some(NoteTarget::Part(i))
        } else if let Some(&i) = nozzle_at.get(t.as_str()) {
            Some(NoteTarget::Nozzle(i))
        } else if let Some(&i) = note_at.get(t.as_str()) {
            Some(NoteTarget::Note(i))
        } else if designed.contains(t.as_str()) {
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
    // Resolve along each chain of notes once: walk from a note to the first
    // target that is no note (or is resolved already), then place the notes
    // walked back from it. A walk that meets itself is a cycle: the notes on it,
    // and those leading into it, stay unresolved. Linear in the notes.
    let direct = |k: usize| -> Option<DVec3> {
        match targets[k]? {
            NoteTarget::Vessel => Some(DVec3::ZERO),
            NoteTarget::Part(i) => parts[i]
                .as_ref()
                // On the part's own axis (offset beyond an eccentric reducer).
                .map(|p| {
                    let t = p.frame.translation;
                    DVec3::new(t.x, t.y, 0.5 * (p.span.0 + p.span.1))
                }),
            NoteTarget::Nozzle(i) => Some(nozzles[i].frame.transform_point3(DVec3::new(
                0.0,
                0.0,
                nozzles[i].geometry.projection,
            ))),
            NoteTarget::Note(_) => None,
        }
    };
    let mut positions: Vec<Option<DVec3>> = vec![None; n];
    let mut anchors: Vec<DVec3> = vec![DVec3::ZERO; n];
    /// Where a note is in the walk.
    #[derive(Clone, Copy, PartialEq)]
    enum Walk {
        Unseen,
        OnChain,
        Done,
    }
    let mut walk = vec![Walk::Unseen; n];
    let mut chain = Vec::new();
    for start in 0..n {
        let mut k = start;
        let mut anchor = loop {
            match walk[k] {
                Walk::Done => break positions[k],
                Walk::OnChain => break None,
                Walk::Unseen => {}
            }
            walk[k] = Walk::OnChain;
            chain.push(k);
            match targets[k] {
                Some(NoteTarget::Note(i)) => k = i,
                _ => {
                    chain.pop();
                    walk[k] = Walk::Done;
                    if let Some(a) = direct(k) {
                        anchors[k] = a;
                        positions[k] = Some(a + DVec3::from(vessel.notes[k].offset));
                    }
                    break positions[k];
                }
            }
        };
        while let Some(j) = chain.pop() {
            walk[j] = Walk::Done;
            anchor = anchor.map(|a| {
                anchors[j] = a;
                let at = a + DVec3::from(vessel.notes[j].offset);
                positions[j] = Some(at);
                at
            });
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

#[cfg(test)]
mod tests {
    use crate::constraints::resolve_vessel;
    use crate::design::{NoteDesign, parse_unchecked};

    fn vessel() -> crate::format::VesselDesign {
        let text = r#"{"format": "vesselcad/1", "vessels": [{"tag": "V-1", "kind": "vertical",
            "parts": [{"head": {"id": "H1", "shape": "ellipsoidal"}},
                      {"shell": {"id": "S1", "od": 1000, "length": 3000}},
                      {"head": {"id": "H2", "shape": "ellipsoidal"}}]}]}"#;
        parse_unchecked(text).unwrap().vessels.remove(0)
    }

    fn note(id: String, target: String, dz: f64) -> NoteDesign {
        NoteDesign {
            id,
            text: String::new(),
            target,
            offset: [0.0, 0.0, dz],
        }
    }

    /// A chain of 50,000 notes, each on the next (listed first to last, so the
    /// last is the only one anchored to a part): each note's position is its
    /// anchor plus its offset, all the way down. The old fixed-point loop
    /// resolved one note per sweep of the list, 6.3 s for this chain; the walk
    /// resolves each note once.
    #[test]
    fn a_long_chain_of_notes_resolves_each_note_once() {
        let mut v = vessel();
        let n = 50_000;
        for k in 0..n {
            let target = if k + 1 < n {
                format!("T{}", k + 1)
            } else {
                "S1".to_string()
            };
            v.notes.push(note(format!("T{k}"), target, 1.0));
        }
        let resolved = resolve_vessel(&v, 0).unwrap();
        assert_eq!(resolved.notes.len(), n);
        // S1's anchor is its mid-length, 1500 mm; note k sits n − k mm above.
        for (k, r) in resolved.notes.iter().enumerate() {
            assert_eq!(r.position.z, 1500.0 + (n - k) as f64, "{}", r.id);
            assert_eq!(r.anchor.z, r.position.z - 1.0);
        }
    }

    /// Notes on a cycle, and a note leading into one, are refused as a cycle;
    /// a note on a note outside it is placed.
    #[test]
    fn cycles_and_notes_leading_into_them_are_refused() {
        let mut v = vessel();
        v.notes.push(note("A".into(), "B".into(), 1.0));
        v.notes.push(note("B".into(), "A".into(), 1.0));
        v.notes.push(note("C".into(), "A".into(), 1.0));
        v.notes.push(note("D".into(), "E".into(), 1.0));
        v.notes.push(note("E".into(), "V-1".into(), 2.0));
        v.notes.push(note("F".into(), "F".into(), 1.0));
        let violations = resolve_vessel(&v, 0).unwrap_err();
        let cyclic: Vec<&str> = violations
            .iter()
            .filter(|x| x.rule.contains("cycle"))
            .map(|x| x.path.as_str())
            .collect();
        assert_eq!(
            cyclic,
            [
                "vessels[0].notes[0].target",
                "vessels[0].notes[1].target",
                "vessels[0].notes[2].target",
                "vessels[0].notes[5].target"
            ]
        );
        assert_eq!(violations.len(), 4, "{violations:?}");
    }
}
