//! Shared helpers of the integration tests: the example designs, the comparison of
//! the incremental model with a full build, the head kinds every head suite sweeps,
//! dense sampling of patches and triangles against their analytic surfaces, and continuity across
//! patch joints.

#![expect(dead_code, reason = "each test binary uses a different subset")]

pub mod eccentric;
pub mod examples;
pub mod exchange;
pub mod fab;
pub mod fem;
pub mod fem_loads;
pub mod full_build;
pub mod glb;
pub mod heads;
pub mod numbers;
pub mod occt;
pub mod scan;
pub mod stores;
pub mod supports;
pub mod triangle;
pub mod unbuildable;
pub mod watertight;

use glam::DVec3;
use vesselcad::nurbs::NurbsSurface;
use vesselcad::parts::Patch;

/// Samples per direction for dense grid checks.
pub const GRID: usize = 41;

/// Parameters of a dense grid over the surface's domain, including the edges.
pub fn grid(surface: &NurbsSurface, n: usize) -> impl Iterator<Item = (f64, f64)> {
    let ((u0, u1), (v0, v1)) = surface.domain();
    (0..n).flat_map(move |i| {
        (0..n).map(move |j| {
            (
                u0 + (u1 - u0) * i as f64 / (n - 1) as f64,
                v0 + (v1 - v0) * j as f64 / (n - 1) as f64,
            )
        })
    })
}

/// Largest distance of grid points of every patch from its analytic surface.
pub fn max_analytic_deviation(patches: &[Patch]) -> f64 {
    patches
        .iter()
        .flat_map(|p| {
            grid(&p.surface, GRID).map(move |(u, v)| p.analytic.distance(p.surface.point(u, v)))
        })
        .fold(0.0, f64::max)
}

/// Asserts every grid point of every patch lies on its analytic surface within `tol`.
pub fn assert_on_analytic(patches: &[Patch], tol: f64) {
    for p in patches {
        for (u, v) in grid(&p.surface, GRID) {
            let x = p.surface.point(u, v);
            let d = p.analytic.distance(x);
            assert!(
                d <= tol,
                "patch {:?} at ({u}, {v}): point {x} is {d} mm off its analytic surface",
                p.name
            );
        }
    }
}

/// Asserts that consecutive patches `a` (its v = v1 edge) and `b` (its v = v0 edge)
/// meet: equal points (G0) within `tol`, and if `g1`, equal normals within `angle_tol`.
pub fn assert_joint(a: &Patch, b: &Patch, tol: f64, g1: bool, angle_tol: f64) {
    let ((u0, u1), (_, av1)) = a.surface.domain();
    let ((bu0, bu1), (bv0, _)) = b.surface.domain();
    for k in 0..=64 {
        let t = k as f64 / 64.0;
        let pa = a.surface.point(u0 + (u1 - u0) * t, av1);
        let pb = b.surface.point(bu0 + (bu1 - bu0) * t, bv0);
        assert!(
            (pa - pb).length() <= tol,
            "{} → {}: gap {} at t={t}",
            a.name,
            b.name,
            (pa - pb).length()
        );
        if g1 {
            let na = a.surface.normal(u0 + (u1 - u0) * t, av1);
            let nb = b.surface.normal(bu0 + (bu1 - bu0) * t, bv0);
            let angle = na.cross(nb).length().asin()
                + if na.dot(nb) < 0.0 {
                    std::f64::consts::PI
                } else {
                    0.0
                };
            assert!(
                angle <= angle_tol,
                "{} → {}: normals differ by {angle} rad at t={t}",
                a.name,
                b.name
            );
        }
    }
}

/// Asserts every normal of every patch points away from the axis point below it or
/// outward in the sense `(x − centre) · n ≥ 0` for the given interior point.
pub fn assert_outward(patches: &[Patch], interior: impl Fn(DVec3) -> DVec3) {
    for p in patches {
        for (u, v) in grid(&p.surface, 21) {
            let x = p.surface.point(u, v);
            let n = p.surface.normal(u, v);
            assert!(
                (n.length() - 1.0).abs() < 1e-9,
                "patch {} has a non-unit normal {n} at ({u},{v})",
                p.name
            );
            let c = interior(x);
            assert!(
                (x - c).dot(n) > -1e-9 * (x - c).length().max(1.0),
                "patch {} normal {n} points inward at {x}",
                p.name
            );
        }
    }
}

/// Asserts that two curves trace the same points at the same fractions of their
/// domains (`reversed`: `b` runs the other way), within `tol`. Used for shared
/// edges of patches, given as `surface.boundary(side)`.
pub fn assert_same_curve(
    a: &vesselcad::nurbs::NurbsCurve,
    b: &vesselcad::nurbs::NurbsCurve,
    reversed: bool,
    tol: f64,
    what: &str,
) {
    let (a0, a1) = a.domain();
    let (b0, b1) = b.domain();
    for k in 0..=64 {
        let t = k as f64 / 64.0;
        let s = if reversed { 1.0 - t } else { t };
        let pa = a.point(a0 + (a1 - a0) * t);
        let pb = b.point(b0 + (b1 - b0) * s);
        assert!(
            (pa - pb).length() <= tol,
            "{what}: {pa} and {pb} are {} apart at t={t}",
            (pa - pb).length()
        );
    }
}
