//! Openings in a round course, marched once whatever way the nozzle faces.
//!
//! A round course (a cylinder about its part-frame Z, built as `revolve` builds
//! it: four rational quarter arcs from +X, counter-clockwise) is its own image
//! under any turn about its axis. Turning a nozzle about that axis, to a new
//! orientation, turns its neck–host loop with it and changes nothing else: the
//! neck (u, v) stay, the points turn, the host v stays (it follows the axial
//! coordinate) and the host u follows the new angle, in closed form on the
//! quarter arcs ([`round_u`]).
//!
//! So `mesh::axial` marches an opening in a round course with the nozzle
//! turned to face −X (the middle of the course's u-domain, far from its seam),
//! its placement snapped to a fine grid ([`SNAP`]) so that the same nozzle
//! facing any way gets the very same canonical placement, bit for bit; then it
//! turns the result to the nozzle's own angle ([`Turn`]) and moves it along
//! the axis. A fresh cut and a kept one placed again go through the same
//! steps, so the incremental model stays byte-identical to a full build, and
//! every nozzle of one size, pad and host diameter shares one march and one
//! neck region: an orientation edit marches nothing and keeps the neck's mesh.
//! The snap moves the canonical nozzle by at most 2⁻³⁷ of a unit (a few 1e-11
//! of its size), far inside the model's 1e-9 of exactness.

use std::f64::consts::PI;

use glam::{DAffine3, DMat3, DVec3};

use crate::nurbs::NurbsSurface;
use crate::nurbs::builders::FULL_TURN_KNOTS;

/// The grid the canonical placement is snapped to: 2⁻³⁶ mm for its origin,
/// 2⁻³⁶ for its axes' components (both far below the model's resolution and
/// far above the rounding a turn leaves in them).
const SNAP: f64 = 68_719_476_736.0;

/// Largest relative departure of a round course's control net from the circle's.
const ROUND: f64 = 1e-12;

/// Whether `surface` is a round course: degree 1 along v with two control rows
/// (checked as an extrusion by the caller), and its v0 row the circle
/// `revolve` makes about Z: four quarter arcs on the full-turn knots, centred
/// on the axis, starting on +X and running counter-clockwise (corner control
/// points at √2 times the radius, weighted cos 45° relative to the others).
pub(super) fn is_round(surface: &NurbsSurface) -> bool {
    let knots = surface.u_knots();
    if knots.degree() != 2 || knots.as_slice() != FULL_TURN_KNOTS || surface.v_count() != 2 {
        return false;
    }
    let points = surface.homogeneous_points();
    if points.len() != 18 {
        return false;
    }
    let (first, w0) = (points[0], points[0].w);
    let radius = first.x / w0;
    if !(radius.is_finite() && radius > 0.0 && w0.is_finite() && w0 > 0.0) {
        return false;
    }
    let eps = ROUND * radius;
    let corner = std::f64::consts::FRAC_1_SQRT_2;
    (0..9).all(|i| {
        let p = points[2 * i];
        let (sin, cos) = (PI / 4.0 * i as f64).sin_cos();
        let (scale, w) = if i % 2 == 1 {
            (1.0 / corner, corner * w0)
        } else {
            (1.0, w0)
        };
        (p.w - w).abs() <= ROUND * w0
            && (p.x / p.w - radius * scale * cos).abs() <= eps
            && (p.y / p.w - radius * scale * sin).abs() <= eps
    })
}

/// The host u of a point of a round course (its angle about the axis, from +X
/// counter-clockwise), in the course's u-domain [0, 1], in closed form: on a
/// quarter arc with middle weight w = cos 45°, the point at angle φ from the
/// quarter's start has t = s / (w + s (1 − w)) with s = tan(φ/2), and
/// tan(φ/2) = b / (r + a) for the point (a, b) in the quarter's own axes.
pub(super) fn round_u(p: DVec3) -> f64 {
    let (x, y) = (p.x, p.y);
    // The quarter, and the point turned back into the first (exact swaps).
    let (q, a, b) = if x > 0.0 && y >= 0.0 {
        (0.0, x, y)
    } else if x <= 0.0 && y > 0.0 {
        (1.0, y, -x)
    } else if x < 0.0 && y <= 0.0 {
        (2.0, -x, -y)
    } else {
        (3.0, -y, x)
    };
    let r = a.hypot(b);
    if r.is_nan() || r <= 0.0 {
        return 0.0;
    }
    let w = std::f64::consts::FRAC_1_SQRT_2;
    let s = b / (r + a);
    let t = (s / (w + s * (1.0 - w))).clamp(0.0, 1.0);
    (q + t) / 4.0
}

/// A turn about the course's axis (Z), by its cosine and sine.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct Turn {
    cos: f64,
    sin: f64,
}

impl Turn {
    /// `p` turned.
    pub fn point(&self, p: DVec3) -> DVec3 {
        DVec3::new(
            self.cos * p.x - self.sin * p.y,
            self.sin * p.x + self.cos * p.y,
            p.z,
        )
    }
}

/// `across` (a nozzle's placement in a round course, its axial translation
/// zeroed) as a turn about the axis of a canonical placement: the nozzle's axis
/// turned to face −X, every number snapped to [`SNAP`]. `None` when the axis
/// runs along the course's (no turn faces it anywhere): then the placement is
/// its own canonical one.
pub(super) fn split_turn(across: &DAffine3) -> Option<(DAffine3, Turn)> {
    let axis = across.matrix3.z_axis;
    let across_axis = (axis.x * axis.x + axis.y * axis.y).sqrt();
    if across_axis.is_nan() || across_axis <= 1e-9 {
        return None;
    }
    // The turn from −X to the axis's direction across the course.
    let angle = axis.y.atan2(axis.x) - PI;
    let (sin, cos) = angle.sin_cos();
    let back = Turn { cos, sin: -sin };
    let snap = |v: DVec3| {
        let s = |x: f64| (x * SNAP).round() / SNAP;
        let v = back.point(v);
        DVec3::new(s(v.x), s(v.y), s(v.z))
    };
    let m = across.matrix3;
    let canonical = DAffine3::from_mat3_translation(
        DMat3::from_cols(snap(m.x_axis), snap(m.y_axis), snap(m.z_axis)),
        snap(across.translation),
    );
    // A tiny negative number snaps to −0.0: made 0.0, so that equal
    // placements hash alike.
    let canonical = DAffine3::from_cols_array(&canonical.to_cols_array().map(|x| x + 0.0));
    canonical
        .is_finite()
        .then_some((canonical, Turn { cos, sin }))
}

#[cfg(test)]
mod tests {
    use std::f64::consts::TAU;

    use glam::DVec3;

    use super::*;
    use crate::mesh::cut::turn::split_turn;
    use crate::mesh::test_parts::{OD, course, frame};

    #[test]
    fn a_course_is_round_and_its_u_is_its_angle() {
        let course = course().surface;
        assert!(is_round(&course));
        let ((_, _), (v0, _)) = course.domain();
        for k in 0..=997 {
            let angle = TAU * k as f64 / 997.0 - 0.5;
            let p = DVec3::new(angle.cos(), angle.sin(), 0.0) * (OD / 2.0);
            let u = round_u(p);
            assert!((0.0..=1.0).contains(&u), "{u}");
            let on = course.point(u, v0);
            let d = DVec3::new(on.x - p.x, on.y - p.y, 0.0).length();
            assert!(d <= 1e-12 * OD, "angle {angle}: {d} mm off");
        }
        // Quarter boundaries land on the knots.
        for (q, angle) in [0.0, 0.5 * PI, PI, 1.5 * PI].into_iter().enumerate() {
            let p = DVec3::new(angle.cos(), angle.sin(), 0.0);
            assert!((round_u(p) - q as f64 / 4.0).abs() <= 1e-15);
        }
    }

    #[test]
    fn a_turned_placement_has_one_canonical_placement() {
        // Radial, and off-centre and inclined (a hillside nozzle leaning up).
        for (offset, axis) in [
            (DVec3::ZERO, DVec3::new(1.0, 0.0, 0.0)),
            (DVec3::new(-120.0, 90.0, 0.0), DVec3::new(0.8, -0.6, 0.3)),
        ] {
            let (first, _) = split_turn(&frame(offset, axis)).unwrap();
            for k in 1..=24 {
                let turn = Turn {
                    cos: (TAU * k as f64 / 24.3).cos(),
                    sin: (TAU * k as f64 / 24.3).sin(),
                };
                let turned = frame(turn.point(offset), turn.point(axis));
                let (canonical, back) = split_turn(&turned).unwrap();
                assert_eq!(canonical.to_cols_array(), first.to_cols_array(), "{k}");
                // Turned back, the canonical placement is the nozzle's own.
                let again = DAffine3::from_mat3_translation(
                    DMat3::from_cols(
                        back.point(canonical.matrix3.x_axis),
                        back.point(canonical.matrix3.y_axis),
                        back.point(canonical.matrix3.z_axis),
                    ),
                    back.point(canonical.translation),
                );
                assert!(again.abs_diff_eq(turned, 1e-10), "{again:?} / {turned:?}");
            }
        }
        // Along the axis: no turn.
        assert!(split_turn(&DAffine3::IDENTITY).is_none());
    }

    #[test]
    fn a_head_patch_is_not_a_round_course() {
        use crate::parts::heads::{Head, HeadKind};
        let head = Head::new(OD, HeadKind::TWO_TO_ONE).with_straight_flange(50.0);
        for p in head.patches().unwrap() {
            assert_eq!(
                is_round(&p.surface),
                p.name == "straight flange",
                "{}",
                p.name
            );
        }
    }
}
