//! The orientation circle: in the view where nozzle angles are true (the plan of
//! a vertical vessel or tank, the end view of a horizontal one), a dash-dot
//! circle about the vessel axis with ticks and labels at 0°, 90°, 180° and 270°
//! by the plant convention (`constraints::orientation_direction`: plan angles
//! from north clockwise; for horizontal vessels, about the axis from the top),
//! and every nozzle's mark and angle on a leader to its face. The plan of a
//! horizontal vessel gets the marks only.
//!
//! The labels are handed to the label placer as movable texts with targets.

use glam::{DVec2, DVec3};

use super::data::VesselData;
use super::labels::Movable;
use super::layout::Placement;
use super::sheet::{Align, Item, Layer};
use super::text::text_width;
use crate::constraints::orientation_direction;
use crate::design::VesselKind;

/// The view index (in `ViewKind::ALL` order) where orientation angles are true.
pub fn angle_view(data: &VesselData) -> usize {
    if data.design.kind == VesselKind::Horizontal {
        2
    } else {
        1
    }
}

/// Paper margin round the angle view for the circle's labels, mm.
pub fn label_margin(h: f64) -> f64 {
    7.0 * h + 6.0
}

/// A nozzle's axis, its face centre (vessel frame) and whether it runs along the
/// vessel's axis (a head nozzle on the axis or parallel to it).
fn nozzle_ends(n: &super::data::NozzleData) -> (DVec3, DVec3, bool) {
    let axis = (n.frame.matrix3 * DVec3::Z).normalize();
    let face = n.frame.translation + axis * n.design.projection;
    (axis, face, axis.cross(DVec3::Z).length() < 1e-6)
}

/// Draws the circle, its ticks and labels, and the nozzle labels (on the plan
/// of a horizontal vessel too when the sheet `shown` it); returns the labels for
/// the placer.
pub fn draw(
    data: &VesselData,
    placement: &Placement,
    h: f64,
    shown: [bool; 4],
    items: &mut Vec<Item>,
) -> Vec<Movable> {
    let mut movable = Vec::new();
    let k = angle_view(data);
    let projection = data.views[k].projection;
    let to_sheet = |p: DVec3| placement.to_sheet(k, projection.project(p));
    let centre = to_sheet(DVec3::ZERO);
    let rotation = data.design.placement.rotation;
    let kind = data.design.kind;
    // The circle clears the shell and every nozzle face.
    let reach = data
        .nozzles
        .iter()
        .map(|n| (to_sheet(nozzle_ends(n).1) - centre).length())
        .chain(std::iter::once(
            0.5 * data.summary.max_diameter * placement.factors[k] / placement.scale,
        ))
        .fold(0.0, f64::max);
    let radius = reach + 2.0;
    items.push(Item::Circle {
        layer: Layer::Centre,
        centre,
        radius,
    });
    let direction = |angle: f64| {
        let d = projection.project(orientation_direction(kind, rotation, angle));
        d.normalize_or(DVec2::Y)
    };
    let label = |items: &mut Vec<Item>, at: DVec2, dir: DVec2, text: String| {
        // The text's box just beyond `at` along `dir`.
        let w = text_width(&text, h);
        let c = at + dir * (1.0 + 0.5 * (dir.x.abs() * w + dir.y.abs() * 1.45 * h));
        items.push(Item::Text {
            at: c - DVec2::Y * 0.42 * h,
            height: h,
            align: Align::Middle,
            rotation: 0.0,
            text,
        });
        items.len() - 1
    };
    for angle in [0.0, 90.0, 180.0, 270.0] {
        let d = direction(angle);
        items.push(Item::Line {
            layer: Layer::Centre,
            points: vec![centre + d * (radius - 2.0), centre + d * (radius + 2.0)],
            closed: false,
        });
        let item = label(items, centre + d * (radius + 2.0), d, format!("{angle}°"));
        movable.push(Movable {
            item,
            target: None,
            outside_views: false,
        });
    }
    // Nozzle marks and angles, on leaders from outside the circle.
    for n in &data.nozzles {
        let (_, face, along) = nozzle_ends(n);
        let at = to_sheet(face);
        let radial = at - centre;
        let (dir, text) = if along || radial.length() < 1e-6 {
            (DVec2::new(1.0, 1.0).normalize(), n.design.mark.clone())
        } else {
            (
                radial.normalize(),
                format!(
                    "{} {}°",
                    n.design.mark,
                    super::dimensions::format_mm(n.design.orientation)
                ),
            )
        };
        let item = label(items, centre + dir * (radius + 2.0 * h + 3.0), dir, text);
        movable.push(Movable {
            item,
            target: Some(at),
            outside_views: false,
        });
    }
    // The plan of a horizontal vessel: marks at the nozzle faces.
    if k != 1 && shown[1] {
        let plan = data.views[1].projection;
        for n in &data.nozzles {
            let at = placement.to_sheet(1, plan.project(nozzle_ends(n).1));
            let item = label(
                items,
                at + DVec2::new(2.0, 2.0),
                DVec2::new(1.0, 1.0).normalize(),
                n.design.mark.clone(),
            );
            movable.push(Movable {
                item,
                target: Some(at),
                outside_views: false,
            });
        }
    }
    movable
}
