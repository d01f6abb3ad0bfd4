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
//! changes); any other is turned about its own axis so that the seam runs
//! through the middle of the widest angular gap between its off-centre
//! openings. An opening is seen along the head's axis — a vertical neck or pad
//! cylinder of radius r whose axis is d from the head's: every point of it lies
//! within asin(r / d) of its centre's angle. An opening round the pole (a centre
//! nozzle) covers every angle near it; the layout cuts the seam where that
//! opening's loop meets it and runs it only up to there, so such openings do not
//! count. Turning a head about its own axis changes neither its shape nor any
//! nozzle's frame (nozzles are placed before), only where its patches'
//! parameters start. Openings that leave no meridian clear are refused.

use std::f64::consts::TAU;

use glam::DAffine3;

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

/// The angle in the middle of the widest gap between `spans`, with the gap's
/// width; `None` when they cover the whole turn.
fn widest_gap(spans: &[Span]) -> Option<(f64, f64)> {
    if spans.is_empty() {
        return Some((0.0, TAU));
    }
    if spans.iter().any(|s| s.width >= TAU) {
        return None;
    }
    spans
        .iter()
        .map(|s| (s.start + s.width).rem_euclid(TAU))
        .filter(|&end| !spans.iter().any(|s| s.holds(end)))
        .map(|end| {
            let gap = spans
                .iter()
                .map(|s| (s.start - end).rem_euclid(TAU))
                .fold(TAU, f64::min);
            ((end + 0.5 * gap).rem_euclid(TAU), gap)
        })
        .filter(|&(_, gap)| gap > MIN_GAP)
        .max_by(|a, b| a.1.total_cmp(&b.1))
}

/// The angular spans of the off-centre openings on `head` (the resolved part at
/// `index`), with their nozzles; with `widen`, each opening's radius is taken
/// with its end gap (`nozzles::end_gap`) added.
fn spans_on<'a>(
    head: &ResolvedPart,
    index: usize,
    nozzles: &'a [ResolvedNozzle],
    widen: bool,
) -> Vec<(Span, &'a ResolvedNozzle)> {
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
            Some((Span::about(p.y.atan2(p.x), half), n))
        })
        .collect()
}

/// Turns every head of `parts` whose openings cover its seam meridian (local +X,
/// with each opening's end gap) about its axis, to the middle of the widest gap
/// between them; reports a head whose openings leave no meridian clear.
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
        let widened = spans_on(head, index, nozzles, true);
        if !widened.iter().any(|(s, _)| s.holds(0.0) || s.start == 0.0) {
            continue;
        }
        let plain = spans_on(head, index, nozzles, false);
        let bare: Vec<Span> = plain.iter().map(|(s, _)| *s).collect();
        let wide: Vec<Span> = widened.iter().map(|(s, _)| *s).collect();
        let Some((angle, _)) = widest_gap(&wide).or_else(|| widest_gap(&bare)) else {
            let marks: Vec<&str> = plain.iter().map(|(_, n)| n.mark.as_str()).collect();
            let last = plain.last().map(|(_, n)| n.mark.as_str()).unwrap_or_default();
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
                    "the openings of nozzles {} on head {}, seen along its axis, cover every \
                     angle about it: the head's seam (a meridian from its tangent line to the \
                     pole, or to a centre nozzle's opening) must pass between two of them; \
                     turn or move one so that a meridian stays clear",
                    marks.join(", "),
                    head.id
                ),
            );
            continue;
        };
        head.frame = head.frame * DAffine3::from_rotation_z(angle);
    }
}

#[cfg(test)]
mod tests {
    use std::f64::consts::{FRAC_PI_2, FRAC_PI_4, PI};


    use super::*;

    fn span_deg(centre: f64, half: f64) -> Span {
        Span::about(centre.to_radians(), half.to_radians())
    }

    #[test]
    fn the_widest_gap_is_found_across_the_turn() {
        // A ring of four at 0, 90, 180, 270: four equal gaps, each centred at 45°
        // plus a multiple of 90°.
        let ring: Vec<Span> = (0..4).map(|k| span_deg(90.0 * f64::from(k), 10.0)).collect();
        let (angle, gap) = widest_gap(&ring).unwrap();
        assert!((gap - 70f64.to_radians()).abs() < 1e-12);
        assert!(((angle - FRAC_PI_4).rem_euclid(FRAC_PI_2)).min(
            FRAC_PI_2 - (angle - FRAC_PI_4).rem_euclid(FRAC_PI_2)
        ) < 1e-12);
        // One opening across 0: the gap is opposite it.
        let (angle, _) = widest_gap(&[span_deg(0.0, 20.0)]).unwrap();
        assert!((angle - PI).abs() < 1e-12);
        // Overlapping spans merge; the widest gap wins.
        let spans = [span_deg(350.0, 20.0), span_deg(20.0, 15.0), span_deg(200.0, 5.0)];
        let (angle, gap) = widest_gap(&spans).unwrap();
        assert!((gap - 160f64.to_radians()).abs() < 1e-9, "{}", gap.to_degrees());
        assert!((angle - 115f64.to_radians()).abs() < 1e-9, "{}", angle.to_degrees());
        // No span: the seam stays.
        assert_eq!(widest_gap(&[]), Some((0.0, TAU)));
    }

    #[test]
    fn spans_covering_the_turn_leave_no_gap() {
        let spans: Vec<Span> = (0..3).map(|k| span_deg(120.0 * f64::from(k), 61.0)).collect();
        assert_eq!(widest_gap(&spans), None);
        assert_eq!(widest_gap(&[span_deg(10.0, 180.0)]), None);
        // Touching spans leave no gap either.
        let touching: Vec<Span> = (0..4).map(|k| span_deg(90.0 * f64::from(k), 45.0)).collect();
        assert_eq!(widest_gap(&touching), None);
    }
}
