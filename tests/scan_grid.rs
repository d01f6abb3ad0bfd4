//! Exact grid interpolation (the seed's equation (12)) on analytic surfaces: the
//! surface passes through every grid point, its deviation from the analytic
//! surface falls as the grid grows (fourth order for cubics), and a grid with
//! coincident rows is refused by the Schoenberg–Whitney check.

use std::f64::consts::FRAC_PI_2;

use glam::DVec3;
use vesselcad::scan::ScanError;
use vesselcad::scan::grid::{Parametrization, interpolate_grid};

/// A sphere of radius 1000 between latitudes 10° and 80°, a quarter turn of
/// longitude: (longitude, latitude) fractions in [0, 1].
fn sphere(s: f64, t: f64) -> DVec3 {
    let lon = FRAC_PI_2 * s;
    let lat = (10.0 + 70.0 * t).to_radians();
    1000.0 * DVec3::new(lat.cos() * lon.cos(), lat.cos() * lon.sin(), lat.sin())
}

/// A cylinder of radius 1000, a quarter turn, 2000 long.
fn cylinder(s: f64, t: f64) -> DVec3 {
    let a = FRAC_PI_2 * s;
    DVec3::new(1000.0 * a.cos(), 1000.0 * a.sin(), 2000.0 * t)
}

fn grid(f: fn(f64, f64) -> DVec3, nu: usize, nv: usize) -> Vec<DVec3> {
    let mut out = Vec::new();
    for i in 0..nu {
        for j in 0..nv {
            out.push(f(i as f64 / (nu - 1) as f64, j as f64 / (nv - 1) as f64));
        }
    }
    out
}

/// Largest distance of the surface from the analytic one (its radius 1000 about
/// the origin or the z axis), over a 60 × 60 sample.
fn deviation(surface: &vesselcad::nurbs::NurbsSurface, sphere: bool) -> f64 {
    let ((u0, u1), (v0, v1)) = surface.domain();
    let mut worst: f64 = 0.0;
    for i in 0..=60 {
        for j in 0..=60 {
            let p = surface.point(
                u0 + (u1 - u0) * i as f64 / 60.0,
                v0 + (v1 - v0) * j as f64 / 60.0,
            );
            let r = if sphere {
                p.length()
            } else {
                p.truncate().length()
            };
            worst = worst.max((r - 1000.0).abs());
        }
    }
    worst
}

#[test]
fn a_grid_is_interpolated_exactly_and_converges_to_its_surface() {
    for (name, f, is_sphere) in [
        ("sphere", sphere as fn(f64, f64) -> DVec3, true),
        ("cylinder", cylinder, false),
    ] {
        let mut last = f64::INFINITY;
        for n in [5, 9, 17, 33] {
            let points = grid(f, n, n + 2);
            for parametrization in [Parametrization::ChordLength, Parametrization::Centripetal] {
                let fit = interpolate_grid(&points, (n, n + 2), (3, 3), parametrization).unwrap();
                for (i, &u) in fit.u.iter().enumerate() {
                    for (j, &v) in fit.v.iter().enumerate() {
                        let gap = (fit.surface.point(u, v) - points[i * (n + 2) + j]).length();
                        assert!(gap < 1e-9, "{name} {n}: point {i},{j} off by {gap}");
                    }
                }
            }
            let fit = interpolate_grid(&points, (n, n + 2), (3, 3), Parametrization::ChordLength)
                .unwrap();
            let d = deviation(&fit.surface, is_sphere);
            // Cubic interpolation: the error falls about 16× per halving of the
            // spacing; hold at least 8×.
            assert!(d < last / 8.0, "{name} {n}: {d} mm after {last} mm");
            last = d;
        }
        assert!(last < 1e-3, "{name}: {last} mm at 33 points");
    }
}

#[test]
fn degrees_and_coincident_rows_are_refused() {
    let points = grid(cylinder, 6, 6);
    match interpolate_grid(&points, (6, 6), (6, 3), Parametrization::ChordLength) {
        Err(ScanError::Options { field, .. }) => assert_eq!(field, "degree u"),
        other => panic!("{other:?}"),
    }
    match interpolate_grid(&points[..30], (6, 6), (3, 3), Parametrization::ChordLength) {
        Err(ScanError::Options { field, .. }) => assert_eq!(field, "grid"),
        other => panic!("{other:?}"),
    }
    // Two equal rows: two data parameters coincide and the system is singular.
    let mut twice = points.clone();
    for j in 0..6 {
        twice[2 * 6 + j] = twice[6 + j];
    }
    match interpolate_grid(&twice, (6, 6), (3, 3), Parametrization::ChordLength) {
        Err(ScanError::Singular { rule, .. }) => {
            assert!(
                rule.contains("Schoenberg") || rule.contains("pivot"),
                "{rule}"
            )
        }
        other => panic!("{other:?}"),
    }
    // The paper's own choice, uniform parameters, interpolates as well.
    let fit = interpolate_grid(&points, (6, 6), (2, 2), Parametrization::Uniform).unwrap();
    assert!((fit.surface.point(fit.u[3], fit.v[2]) - points[3 * 6 + 2]).length() < 1e-9);
}
