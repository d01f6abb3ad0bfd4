//! The development of an eccentric reducer (an oblique cone) is exact: its
//! area equals the exact area of the NURBS oblique cone through the same end
//! circles to 1e-9, and its outline is the plate of that area.

use vesselcad::fab::oblique::ObliqueCone;
use vesselcad::fab::openings::polygon_area;
use vesselcad::parts::{Reducer, ReducerAlignment, surface_area};

#[test]
fn an_oblique_cone_develops_to_its_exact_area() {
    let cases = [
        (1000.0, 600.0, 800.0, 0.0),
        (2400.0, 1800.0, 1200.0, 90.0),
        (1600.0, 400.0, 900.0, 225.0),
        (3000.0, 2900.0, 300.0, -30.0),
    ];
    for (large, small, length, flat) in cases {
        let t = 12.0;
        let cone = ObliqueCone::mid_surface(large, small, length, flat, t);
        let exact = surface_area(
            &Reducer {
                large_diameter: 2.0 * cone.large,
                small_diameter: 2.0 * cone.small,
                length,
                alignment: ReducerAlignment::Eccentric { flat_side: flat },
            }
            .patches()
            .unwrap(),
        );
        let area = cone.area();
        assert!(
            (area - exact).abs() <= 1e-9 * exact,
            "{large}/{small}×{length} at {flat}°: developed {area}, NURBS {exact}"
        );
        // The outline as a polygon: its area approaches the plate's as the
        // chords shorten (second order), and its two ends are the flat
        // side's generator (same length from the apex).
        let outline = cone.outline(4096);
        let polygon = polygon_area(&outline).abs();
        assert!((polygon - area).abs() < 1e-5 * area, "{polygon} vs {area}");
        let n = outline.len() / 2;
        assert!((outline[0].length() - outline[n - 1].length()).abs() < 1e-9 * large);
        // Less than a full turn: a cone, not a plane.
        assert!(cone.angle() < std::f64::consts::TAU, "{}", cone.angle());
    }
}
