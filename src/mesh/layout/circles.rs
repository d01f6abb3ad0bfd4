//! Full circles sampled in closed form: the edge parameters of a circle built as
//! four rational quarter arcs (every course end, head tangent line, knuckle–crown
//! line and flange edge), without fitting the speed.
//!
//! Part of `edges`: a patch's sides are sampled from its edge curves when its
//! region is laid out, and after a diameter edit or a head swap every circle of
//! the new patches is new. The general sampler fits a Legendre series to the
//! speed on eight pieces and searches the curvature (some 15 µs a circle, plus a
//! Newton solve per vertex); for a circle the arc length is the angle times the
//! radius, and on a symmetric rational quarter arc with middle weight cos 45°
//! the angle φ from its start is φ = 2·atan(w t / (1 − t + w t)), so the
//! parameter of angle φ is t = s / (w + s (1 − w)) with s = tan(φ/2). Vertices
//! uniform in angle are then uniform in arc length, as the general sampler makes
//! them, and the segment count comes from the same rule.

use std::f64::consts::{FRAC_PI_2, TAU};

use glam::DVec3;

use crate::MODEL_EPSILON;
use crate::nurbs::NurbsCurve;
use crate::nurbs::builders::FULL_TURN_KNOTS;

/// Largest relative departure of the control net from a circle's.
const CIRCLE: f64 = 1e-12;

/// A full circle as four symmetric rational quarter arcs.
pub(super) struct Circle {
    /// Its radius.
    pub radius: f64,
}

impl Circle {
    /// `curve` when it is a full circle of four quarter arcs on knots
    /// 0, ¼, ½, ¾, 1 (each quarter's middle control point at the corner of its
    /// ends' tangents, weighted cos 45° relative to them); `None` otherwise.
    pub fn of(curve: &NurbsCurve) -> Option<Self> {
        let knots = curve.knots().as_slice();
        let points = curve.homogeneous_points();
        if curve.degree() != 2 || knots != FULL_TURN_KNOTS || points.len() != 9 {
            return None;
        }
        let euclid = |k: usize| points[k].truncate() / points[k].w;
        let centre = (euclid(0) + euclid(2) + euclid(4) + euclid(6)) / 4.0;
        let radius = (euclid(0) - centre).length();
        // A circle shorter than the model's resolution is a point to the
        // general sampler (its two end parameters): left to it.
        if !(radius.is_finite() && TAU * radius > MODEL_EPSILON) {
            return None;
        }
        let eps = CIRCLE * radius;
        let w = std::f64::consts::FRAC_1_SQRT_2;
        let normal = (euclid(0) - centre)
            .cross(euclid(2) - centre)
            .normalize_or_zero();
        for q in 0..4 {
            let (a, m, b) = (euclid(2 * q), euclid(2 * q + 1), euclid(2 * q + 2));
            let (wa, wm, wb) = (points[2 * q].w, points[2 * q + 1].w, points[2 * q + 2].w);
            let (ra, rb) = (a - centre, b - centre);
            let corner = centre + ra + rb;
            let ok = (ra.length() - radius).abs() <= eps
                && (rb.length() - radius).abs() <= eps
                && ra.dot(rb).abs() <= eps * radius
                && ra.cross(rb).dot(normal) > 0.0
                && (m - corner).length() <= eps
                && (wa - wb).abs() <= CIRCLE * wa.abs()
                && (wm - w * wa).abs() <= CIRCLE * wa.abs();
            if !ok {
                return None;
            }
        }
        // Closed: the last point is the first.
        ((euclid(8) - euclid(0)).length() <= eps && normal != DVec3::ZERO)
            .then_some(Self { radius })
    }

    /// Its length.
    pub fn length(&self) -> f64 {
        TAU * self.radius
    }

    /// The parameters of `n` segments uniform in angle (and so in arc length),
    /// both ends included; quarter boundaries land exactly on the knots.
    pub fn parameters(&self, n: usize) -> Vec<f64> {
        let w = std::f64::consts::FRAC_1_SQRT_2;
        let n = n.max(1);
        (0..=n)
            .map(|k| {
                // Angle k/n of the turn: quarter q and the share within it, exact.
                let (q, r) = ((4 * k) / n, (4 * k) % n);
                if q >= 4 {
                    return 1.0;
                }
                let phi = FRAC_PI_2 * r as f64 / n as f64;
                let s = (0.5 * phi).tan();
                let t = s / (w + s * (1.0 - w));
                (q as f64 + t) / 4.0
            })
            .collect()
    }
}
