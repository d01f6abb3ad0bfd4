//! The four projections of a vessel, in its own frame.
//!
//! Views follow third-angle (ANSI) practice: the front elevation looks at the
//! vessel from the south for vertical vessels and tanks (plant east to the right),
//! and across the axis from the side at orientation 90° for horizontal ones (the
//! axis runs left to right); the plan looks down with the front side at the
//! bottom; the side view looks from the front view's right; the isometric looks
//! from front-right-above. Everything downstream works in these view coordinates
//! (mm, model scale).

use glam::{DAffine3, DVec2, DVec3};

use super::{Projection, ViewKind};
use crate::design::VesselKind;

/// The front view's right and up directions in the vessel frame.
fn front_axes(kind: VesselKind, frame: &DAffine3) -> (DVec3, DVec3) {
    match kind {
        VesselKind::Vertical | VesselKind::Tank => {
            // Plant east brought into the vessel frame (the frame is a rotation).
            let east = frame.matrix3.transpose() * DVec3::X;
            (east.normalize(), DVec3::Z)
        }
        VesselKind::Horizontal => (DVec3::Z, DVec3::Y),
    }
}

/// A projection from its kind and its right and up unit vectors.
fn projection(kind: ViewKind, right: DVec3, up: DVec3) -> Projection {
    Projection {
        kind,
        right,
        up,
        toward_viewer: right.cross(up),
    }
}

/// The four projections of a vessel of `kind` placed by `frame` (vessel → plant),
/// in [`ViewKind::ALL`](crate::project::ViewKind::ALL) order.
pub fn projections(kind: VesselKind, frame: &DAffine3) -> [Projection; 4] {
    let (right, up) = front_axes(kind, frame);
    let toward = right.cross(up);
    let iso_toward = (toward + right + up).normalize();
    let iso_up = (up - iso_toward * up.dot(iso_toward)).normalize();
    let iso_right = iso_up.cross(iso_toward);
    [
        projection(ViewKind::Front, right, up),
        projection(ViewKind::Top, right, -toward),
        projection(ViewKind::Side, -toward, up),
        projection(ViewKind::Iso, iso_right, iso_up),
    ]
}

/// The direction of plant north in the plan view (unit, view coordinates).
pub fn plan_north(top: &Projection, frame: &DAffine3) -> DVec2 {
    let north = frame.matrix3.transpose() * DVec3::Y;
    let v = top.project(north);
    if v.length() > 1e-12 {
        v.normalize()
    } else {
        DVec2::Y
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::constraints::vessel_frame;

    #[test]
    fn projections_are_orthonormal_and_right_handed() {
        for kind in [VesselKind::Vertical, VesselKind::Horizontal] {
            let f = vessel_frame(kind, [1.0, 2.0, 3.0], 30.0);
            for p in projections(kind, &f) {
                assert!((p.right.length() - 1.0).abs() < 1e-12);
                assert!(p.right.dot(p.up).abs() < 1e-12);
                assert!((p.right.cross(p.up) - p.toward_viewer).length() < 1e-12);
            }
        }
    }

    #[test]
    fn vertical_front_looks_north_and_plan_has_north_up() {
        let f = vessel_frame(VesselKind::Vertical, [0.0; 3], 0.0);
        let [front, top, ..] = projections(VesselKind::Vertical, &f);
        assert!((front.toward_viewer + DVec3::Y).length() < 1e-12);
        assert!((plan_north(&top, &f) - DVec2::Y).length() < 1e-12);
    }
}
