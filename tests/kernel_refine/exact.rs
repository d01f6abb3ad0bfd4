//! Hand-made cases with exact expectations: a break surviving degree elevation, and
//! the ruled surface between a line and an arc.

use std::f64::consts::PI;

use glam::DVec3;
use vesselcad::nurbs::builders::{circular_arc, line, ruled};
use vesselcad::nurbs::{KnotVector, NurbsCurve, Side};

use crate::random::curve_deviation;

#[test]
fn elevation_keeps_a_break_at_full_multiplicity() {
    let knots = KnotVector::try_new(2, vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0, 2.0, 2.0, 2.0]).unwrap();
    let points: Vec<DVec3> = (0..6)
        .map(|i| DVec3::new(i as f64, (i * i % 5) as f64, (i % 2) as f64))
        .collect();
    let c = NurbsCurve::try_from_weighted(knots, &points, &[1.0, 2.0, 1.0, 0.5, 3.0, 1.0]).unwrap();
    let e = c.elevate_degree(2).unwrap();
    assert_eq!(e.degree(), 4);
    assert_eq!(e.knots().multiplicity(1.0), 5);
    assert!(curve_deviation(&e, &c) <= 1e-12);
    assert!((e.point(1.0 - 1e-12) - points[2]).length() < 1e-9);
}

/// A line and a half circle in one tilted plane: the ruled surface between them
/// stays in the plane, its v-boundaries are the two curves with their own
/// parametrizations, and every ruling is the straight segment between them.
#[test]
fn ruled_surface_between_a_line_and_an_arc_is_exact() {
    let origin = DVec3::new(10.0, -5.0, 3.0);
    let x = DVec3::new(1.0, 1.0, 0.0).normalize();
    let y = DVec3::new(-1.0, 1.0, 1.0).normalize();
    let normal = x.cross(y);
    let segment = line(origin + x, origin - x).unwrap();
    let arc = circular_arc(origin, x, y, 2.0, 0.0, PI).unwrap();
    assert_ne!(segment.degree(), arc.degree());
    let s = ruled(&segment, &arc).unwrap();
    let tol = 1e-12;
    let near = s.boundary(Side::VMin);
    let far = s.boundary(Side::VMax);
    for i in 0..=200 {
        let t = i as f64 / 200.0;
        assert!(
            (near.point(t) - segment.point(t)).length() <= tol,
            "t = {t}"
        );
        assert!((far.point(t) - arc.point(t)).length() <= tol, "t = {t}");
        assert!(((far.point(t) - origin).length() - 2.0).abs() <= tol);
        let (a, b) = (s.point(t, 0.0), s.point(t, 1.0));
        for j in 0..=20 {
            let p = s.point(t, j as f64 / 20.0);
            assert!(
                normal.dot(p - origin).abs() <= tol,
                "({t}, {j}) off the plane"
            );
            let along = (p - a).dot(b - a) / (b - a).length_squared();
            assert!((-tol..=1.0 + tol).contains(&along));
            assert!(
                (a + (b - a) * along - p).length() <= tol,
                "({t}, {j}) off the ruling"
            );
        }
    }
}
