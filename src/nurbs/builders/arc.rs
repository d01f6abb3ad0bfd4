//! Exact circular and elliptical arcs as rational quadratic B-splines (P&T A7.1).
//!
//! An arc of sweep θ is split into n = ⌈|θ| / 90°⌉ equal segments. Each segment has its
//! end points on the curve with weight 1 and its middle control point at the
//! intersection of the end tangents with weight cos(Δθ / 2). An ellipse is the affine
//! image of a circle: the same weights and knots on a scaled polygon.

use std::f64::consts::{FRAC_PI_2, TAU};

use glam::DVec3;

use super::{direction, finite_vec, positive};
use crate::nurbs::{KnotVector, NurbsCurve, NurbsError, homogeneous};

/// Tolerance on the orthogonality of the two in-plane axes (|cos| of their angle).
const AXIS_ORTHOGONALITY: f64 = 1e-9;

/// The elliptical arc `C(θ) = center + rx cos θ · x_axis + ry sin θ · y_axis` for θ from
/// `start` to `end` (radians; `end < start` runs clockwise). `x_axis` and `y_axis` are
/// normalized and must be orthogonal. The sweep must be non-zero and at most 2π.
pub fn elliptical_arc(
    center: DVec3,
    x_axis: DVec3,
    y_axis: DVec3,
    rx: f64,
    ry: f64,
    start: f64,
    end: f64,
) -> Result<NurbsCurve, NurbsError> {
    let center = finite_vec("arc centre", center)?;
    let x = direction("arc x axis", x_axis)?;
    let y = direction("arc y axis", y_axis)?;
    if x.dot(y).abs() > AXIS_ORTHOGONALITY {
        return Err(NurbsError::InvalidGeometry {
            what: "arc axes angle cosine",
            value: x.dot(y),
            rule: "x and y axes must be orthogonal",
        });
    }
    let rx = positive("arc x radius", rx)?;
    let ry = positive("arc y radius", ry)?;
    for (what, a) in [("arc start angle", start), ("arc end angle", end)] {
        if !a.is_finite() {
            return Err(NurbsError::InvalidGeometry {
                what,
                value: a,
                rule: "must be finite",
            });
        }
    }
    let sweep = end - start;
    if sweep == 0.0 || sweep.abs() > TAU * (1.0 + 1e-12) {
        return Err(NurbsError::InvalidGeometry {
            what: "arc sweep",
            value: sweep,
            rule: "must be non-zero and at most 2π",
        });
    }
    let segments = ((sweep.abs() / FRAC_PI_2) - 1e-9).ceil().max(1.0) as usize;
    let delta = sweep / segments as f64;
    let w1 = (delta / 2.0).cos();
    let at = |theta: f64, scale: f64| {
        center + x * (rx * scale * theta.cos()) + y * (ry * scale * theta.sin())
    };
    let mut points = Vec::with_capacity(2 * segments + 1);
    points.push(homogeneous(at(start, 1.0), 1.0));
    let mut knots = vec![0.0; 3];
    for s in 0..segments {
        let a0 = start + delta * s as f64;
        let a1 = if s + 1 == segments { end } else { a0 + delta };
        points.push(homogeneous(at(0.5 * (a0 + a1), 1.0 / w1), w1));
        points.push(homogeneous(at(a1, 1.0), 1.0));
        if s + 1 < segments {
            let k = (s + 1) as f64 / segments as f64;
            knots.extend([k, k]);
        }
    }
    knots.extend([1.0; 3]);
    NurbsCurve::try_new(KnotVector::try_new(2, knots)?, points)
}

/// The circular arc of `radius` about `center` in the plane of `x_axis`, `y_axis`,
/// from angle `start` to `end` (radians, measured from `x_axis` towards `y_axis`).
pub fn circular_arc(
    center: DVec3,
    x_axis: DVec3,
    y_axis: DVec3,
    radius: f64,
    start: f64,
    end: f64,
) -> Result<NurbsCurve, NurbsError> {
    elliptical_arc(center, x_axis, y_axis, radius, radius, start, end)
}

/// The full circle of `radius` about `center` with the given plane `normal`: the
/// 9-point, 4-segment rational quadratic starting on the circle, running
/// counter-clockwise about `normal`.
pub fn circle(center: DVec3, normal: DVec3, radius: f64) -> Result<NurbsCurve, NurbsError> {
    let n = direction("circle normal", normal)?;
    let x = n.any_orthonormal_vector();
    let y = n.cross(x);
    circular_arc(center, x, y, radius, 0.0, TAU)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn full_circle_is_the_nine_point_circle() {
        let c = circular_arc(DVec3::ZERO, DVec3::X, DVec3::Y, 1.0, 0.0, TAU).unwrap();
        assert_eq!(c.homogeneous_points().len(), 9);
        assert_eq!(
            c.knots().as_slice(),
            &[
                0.0, 0.0, 0.0, 0.25, 0.25, 0.5, 0.5, 0.75, 0.75, 1.0, 1.0, 1.0
            ]
        );
        let w = std::f64::consts::FRAC_1_SQRT_2;
        for (i, p) in c.homogeneous_points().iter().enumerate() {
            let expect = if i % 2 == 0 { 1.0 } else { w };
            assert!((p.w - expect).abs() < 1e-15);
        }
        for k in 0..=1000 {
            let p = c.point(k as f64 / 1000.0);
            assert!((p.length() - 1.0).abs() < 1e-15, "{p}");
        }
        assert_eq!(c.start(), DVec3::X);
    }

    #[test]
    fn rejects_bad_numbers() {
        assert!(circular_arc(DVec3::ZERO, DVec3::X, DVec3::Y, -1.0, 0.0, 1.0).is_err());
        assert!(circular_arc(DVec3::ZERO, DVec3::X, DVec3::Y, f64::NAN, 0.0, 1.0).is_err());
        assert!(circular_arc(DVec3::ZERO, DVec3::X, DVec3::X, 1.0, 0.0, 1.0).is_err());
        assert!(circular_arc(DVec3::ZERO, DVec3::X, DVec3::Y, 1.0, 0.0, 0.0).is_err());
        assert!(circular_arc(DVec3::ZERO, DVec3::X, DVec3::Y, 1.0, 0.0, 7.0).is_err());
    }
}
