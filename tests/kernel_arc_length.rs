//! Arc length by Gauss–Legendre quadrature: circles, arcs of any sweep and lines
//! have their exact lengths to 1e-12 relative, and lengths add up over a split.

use std::f64::consts::{FRAC_PI_2, PI, TAU};

use glam::DVec3;
use vesselcad::nurbs::builders::{circle, circular_arc, line};

#[test]
fn arc_lengths_of_circles_arcs_and_lines() {
    for radius in [1e-3, 1.0, 1200.0, 5e5] {
        let c = circle(DVec3::new(1.0, 2.0, 3.0), DVec3::new(0.0, 1.0, 1.0), radius).unwrap();
        let expect = TAU * radius;
        assert!(
            (c.arc_length() - expect).abs() <= 1e-12 * expect,
            "r = {radius}"
        );
        // Knots at quarters: each 90° segment, and half the circle.
        assert!((c.arc_length_between(0.25, 0.75) - PI * radius).abs() <= 1e-12 * expect);
        assert!((c.arc_length_between(0.5, 0.25) - FRAC_PI_2 * radius).abs() <= 1e-12 * expect);
        // Additivity at an arbitrary parameter.
        let split = c.arc_length_between(0.0, 0.37) + c.arc_length_between(0.37, 1.0);
        assert!((split - expect).abs() <= 1e-12 * expect);
    }
    for sweep in [1e-3, 0.3, 1.0, FRAC_PI_2, 2.0, PI, 4.0, 5.5, TAU] {
        let r = 350.0;
        let arc = circular_arc(DVec3::ZERO, DVec3::Y, DVec3::Z, r, -0.4, -0.4 + sweep).unwrap();
        assert!(
            (arc.arc_length() - r * sweep).abs() <= 1e-12 * r * sweep,
            "θ = {sweep}"
        );
        let back = circular_arc(DVec3::ZERO, DVec3::Y, DVec3::Z, r, 1.0, 1.0 - sweep).unwrap();
        assert!(
            (back.arc_length() - r * sweep).abs() <= 1e-12 * r * sweep,
            "θ = −{sweep}"
        );
    }
    let (a, b) = (DVec3::new(1.0, -2.0, 3.0), DVec3::new(-4.0, 5.0, 0.5));
    let l = line(a, b).unwrap();
    assert!((l.arc_length() - (b - a).length()).abs() <= 1e-14 * (b - a).length());
    assert_eq!(line(a, a).unwrap().arc_length(), 0.0);
}
