//! Head seams: the meridian along which each head's surfaces of revolution close.
//!
//! A head's patches are revolutions that start at its local +X; the region
//! layout and the structured mesher treat each patch as its parameter rectangle
//! cut along that meridian, from the tangent line to the pole. An opening
//! astride that meridian is no hole of the rectangle: it sends the patch to the
//! general path (on an ellipsoidal crown that refinement ran past 4,000,000
//! vertices) or, with a nozzle round the pole, leaves the layout no place to
//! cut. So each head's seam is chosen here, once its nozzles are placed: a head
//! whose openings keep clear of its local +X keeps it (most heads: no frame
//! changes); any other is turned about its own axis to the one of its eight
//! seam angles (multiples of 45°, where every circle edge has a vertex, so its
//! tangent-line circle still conforms with its course's) farthest from its
//! off-centre openings. An opening is seen along the head's axis — a vertical neck or pad
//! cylinder of radius r whose axis is d from the head's: every point of it lies
//! within asin(r / d) of its centre's angle. An opening round the pole (a centre
//! nozzle) covers every angle near it; the layout cuts the seam where that
//! opening's loop meets it and runs it only up to there, so such openings do not
//! count. Turning a head about its own axis changes neither its shape nor any
//! nozzle's frame (nozzles are placed before), only where its patches'
//! parameters start. A head whose openings cover all eight seam angles (a ring
//! of eight nozzles) is left unturned: the layout then cuts each of its patches
//! at a vertex its circles share between two openings, the one farthest from
//! them, so the head still conforms with its course; with an opening round its
//! pole too (whose crown must be cut at a seam angle) it is refused. The
//! exchange model writes heads unturned ([`unturned_frame`]).

use std::f64::consts::TAU;

use glam::{DAffine3, DVec3};

use super::nozzles::end_gap;
use super::{Report, ResolvedNozzle, ResolvedPart};
use crate::format::VesselDesign;
use crate::parts::PartGeometry;

/// A gap narrower than this (radians) is none: spans that touch.
const MIN_GAP: f64 = 1e-9;

/// An opening's angular span about its head's axis, radians in the head's
/// local frame (from its +X towards +Y): `start` to `start + width`.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Span {
    start: f64,
    width: f64,
}

impl Span {
    /// The span of `half` either side of `centre`.
    fn about(centre: f64, half: f64) -> Self {
        Self {
            start: (centre - half).rem_euclid(TAU),
            width: 2.0 * half,
        }
    }

    /// Whether angle `a` lies strictly inside.
    fn holds(&self, a: f64) -> bool {
        let from = (a - self.start).rem_euclid(TAU);
        from > 0.0 && from < self.width
    }
}

/// The seam angles a head may be turned to: multiples of 1/`TURNS` of a
/// turn, the mesher's `SEAM_CUTS`. Every circle edge is sampled with a
/// multiple of `SEAM_CUTS` segments, evenly, so a head turned by one of these
/// keeps its tangent-line circle's vertices where the course below it has
/// them: the two stay conforming (watertight).
const TURNS: usize = 8;

/// Of the seam angles ([`TURNS`]), the one farthest from every one of `spans`
/// and clear of them all, with its clearance (radians); `None` when every one
/// lies in a span.
fn clearest_angle(spans: &[Span]) -> Option<(f64, f64)> {
    (0..TURNS)
        .map(|k| TAU * k as f64 / TURNS as f64)
        .filter(|&a| !spans.iter().any(|s| s.holds(a) || s.start == a))
        .map(|a| {
            let clearance = spans
                .iter()
                .map(|s| {
                    let after = (a - s.start - s.width).rem_euclid(TAU);
                    let before = (s.start - a).rem_euclid(TAU);
                    after.min(before)
                })
                .fold(TAU, f64::min);
            (a, clearance)
        })
        .filter(|&(_, clearance)| clearance > MIN_GAP)
        .max_by(|a, b| a.1.total_cmp(&b.1))
}

/// The angular spans of the off-centre openings on `head` (the resolved part at
/// `index`); with `widen`, each opening's radius is taken with its end gap
/// (`nozzles::end_gap`) added.
fn spans_on(
    head: &ResolvedPart,
    index: usize,
    nozzles: &[ResolvedNozzle],
    widen: bool,
) -> Vec<Span> {
    let to_local = head.frame.inverse();
    nozzles
        .iter()
        .filter(|n| n.host == index)
        .filter_map(|n| {
            let reach = n.pad.map_or(n.geometry.outside_diameter(), |p| p.0);
            let p = to_local.transform_point3(n.frame.translation);
            let (d, r) = (p.x.hypot(p.y), reach / 2.0);
            if d <= r {
                return None; // round the pole
            }
            let r = if widen { r + end_gap(reach) } else { r };
            let half = (r / d).min(1.0).asin();
            Some(Span::about(p.y.atan2(p.x), half))
        })
        .collect()
}

/// Turns every head of `parts` whose openings cover its seam meridian (local +X,
/// with each opening's end gap) about its axis, to the seam angle farthest
/// from them; a head whose openings cover every seam angle stays unturned,
/// unless it also has an opening round its pole: that is reported.
pub(super) fn choose(
    vessel: &VesselDesign,
    parts: &mut [Option<ResolvedPart>],
    nozzles: &[ResolvedNozzle],
    report: &mut Report,
) {
    for (index, slot) in parts.iter_mut().enumerate() {
        let Some(head) = slot.as_mut() else { continue };
        if !matches!(head.geometry, PartGeometry::Head(_)) {
            continue;
        }
        let wide = spans_on(head, index, nozzles, true);
        if !wide.iter().any(|s| s.holds(0.0) || s.start == 0.0) {
            continue;
        }
        let bare = spans_on(head, index, nozzles, false);
        // Openings on all eight steps (a ring of eight nozzles): the head
        // stays as it is, and the layout cuts each of its patches at a sample of
        // its circles between two openings (`mesh::layout`'s `other_cut`) —
        // unless an opening goes round its pole: a crown cut round its centre
        // is cut at its seam, which an opening covers.
        let Some((angle, _)) = clearest_angle(&wide).or_else(|| clearest_angle(&bare)) else {
            if let Some(centre) = round_the_pole(head, index, nozzles) {
                refuse(vessel, head, nozzles, index, centre, report);
            }
            continue;
        };
        head.frame *= DAffine3::from_rotation_z(angle);
    }
}

/// The mark of a nozzle on `head` (the resolved part at `index`) whose opening
/// goes round the head's pole, if any.
fn round_the_pole<'a>(
    head: &ResolvedPart,
    index: usize,
    nozzles: &'a [ResolvedNozzle],
) -> Option<&'a str> {
    let to_local = head.frame.inverse();
    nozzles
        .iter()
        .filter(|n| n.host == index)
        .find(|n| {
            let reach = n.pad.map_or(n.geometry.outside_diameter(), |p| p.0);
            let p = to_local.transform_point3(n.frame.translation);
            p.x.hypot(p.y) <= reach / 2.0
        })
        .map(|n| n.mark.as_str())
}

/// Reports that the off-centre openings of `head` cover each of its seam
/// angles while nozzle `centre` goes round its pole, on the last off-centre
/// nozzle's orientation.
fn refuse(
    vessel: &VesselDesign,
    head: &ResolvedPart,
    nozzles: &[ResolvedNozzle],
    index: usize,
    centre: &str,
    report: &mut Report,
) {
    let marks: Vec<&str> = nozzles
        .iter()
        .filter(|n| n.host == index && n.mark != centre)
        .map(|n| n.mark.as_str())
        .collect();
    let last = marks.last().copied().unwrap_or_default();
    let k = vessel
        .nozzles
        .iter()
        .position(|n| n.mark == last)
        .unwrap_or_default();
    report.push(
        format!("nozzles[{k}].orientation"),
        Some(last),
        "orientation",
        vessel.nozzles[k].orientation,
        format!(
            "the openings of nozzles {} on head {}, seen along its axis, cover each of the \
             head's {TURNS} seam angles (every {}° about its axis), and nozzle {centre} goes \
             round its centre: its crown is then cut along a seam (a meridian from the \
             centre nozzle's opening outwards) at one of those angles, which must stay clear; \
             turn or move one so that one of those meridians stays clear",
            marks.join(", "),
            head.id,
            360 / TURNS
        ),
    );
}

/// The frame a head `part` had before `choose` turned it about its axis (any
/// other part's frame as it is). Unturned, a head's local +X is the vessel's
/// +X: a top head's frame is a translation, a bottom head's a half turn about
/// X. The exchange model writes heads unturned: its faces keep their
/// surfaces' seams and cut openings across them (`exchange::seam`), and its
/// edges between a head and its course are shared only where both circles
/// start at one point.
pub fn unturned_frame(part: &ResolvedPart) -> DAffine3 {
    if !matches!(part.geometry, PartGeometry::Head(_)) {
        return part.frame;
    }
    let (x, z) = (part.frame.matrix3 * DVec3::X, part.frame.matrix3 * DVec3::Z);
    let turn = if z.z >= 0.0 {
        x.y.atan2(x.x)
    } else {
        (-x.y).atan2(x.x)
    };
    if turn == 0.0 {
        return part.frame;
    }
    part.frame * DAffine3::from_rotation_z(-turn)
}

#[cfg(test)]
mod tests {
    use std::f64::consts::{FRAC_PI_2, FRAC_PI_4, PI};

    use super::*;

    fn span_deg(centre: f64, half: f64) -> Span {
        Span::about(centre.to_radians(), half.to_radians())
    }

    #[test]
    fn the_seam_angle_is_the_one_clearest_of_the_openings() {
        assert_eq!(TURNS, crate::mesh::SEAM_CUTS);
        // A ring of four at 0, 90, 180, 270: the odd multiples of 45° are the
        // clearest, 35° from their neighbours.
        let ring: Vec<Span> = (0..4)
            .map(|k| span_deg(90.0 * f64::from(k), 10.0))
            .collect();
        let (angle, clearance) = clearest_angle(&ring).unwrap();
        assert!((clearance - 35f64.to_radians()).abs() < 1e-12);
        assert!(
            ((angle - FRAC_PI_4) / FRAC_PI_2 - ((angle - FRAC_PI_4) / FRAC_PI_2).round()).abs()
                < 1e-12
        );
        // One opening across 0: the angle opposite it.
        let (angle, _) = clearest_angle(&[span_deg(0.0, 20.0)]).unwrap();
        assert!((angle - PI).abs() < 1e-12);
        // Overlapping spans merge; the clearest angle wins.
        let spans = [
            span_deg(350.0, 20.0),
            span_deg(20.0, 15.0),
            span_deg(250.0, 5.0),
        ];
        let (angle, clearance) = clearest_angle(&spans).unwrap();
        assert!(
            (angle - 135f64.to_radians()).abs() < 1e-9,
            "{}",
            angle.to_degrees()
        );
        assert!((clearance - 100f64.to_radians()).abs() < 1e-9);
    }

    #[test]
    fn spans_covering_every_seam_angle_leave_none() {
        let spans: Vec<Span> = (0..3)
            .map(|k| span_deg(120.0 * f64::from(k), 61.0))
            .collect();
        assert_eq!(clearest_angle(&spans), None);
        // Eight small openings, one on each seam angle.
        let eight: Vec<Span> = (0..8).map(|k| span_deg(45.0 * f64::from(k), 1.0)).collect();
        assert_eq!(clearest_angle(&eight), None);
    }
}
