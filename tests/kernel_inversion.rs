//! Point inversion: parameters of points on every kind of part patch and on random
//! rational surfaces are recovered, and off-surface points project onto the true
//! closest point (known in closed form on spheres, cylinders, tori and circles, by
//! brute force elsewhere).

mod common;

use std::f64::consts::TAU;

use common::heads::head_kinds;
use glam::{DVec3, DVec4};
use vesselcad::nurbs::builders::{circle, circular_arc};
use vesselcad::nurbs::{KnotVector, NurbsError, NurbsSurface};
use vesselcad::parts::heads::{Head, HeadKind};
use vesselcad::parts::{Analytic, Patch, Reducer, ReducerAlignment, Shell};

const OD: f64 = 2400.0;
/// Tolerance on recovered parameters (domains are [0, 1]).
const PARAMETER_TOL: f64 = 1e-10;
/// Tolerance on recovered points, mm, for parts of size OD.
const POINT_TOL: f64 = 1e-12 * OD;

/// SplitMix64: a fixed-seed generator, so failures reproduce.
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> f64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        (z ^ (z >> 31)) as f64 / u64::MAX as f64
    }

    fn range(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * self.next()
    }
}

/// Every kind of head, with and without straight flange.
fn all_heads() -> Vec<Head> {
    let flanges = [0.0, 50.0];
    head_kinds(OD)
        .into_iter()
        .flat_map(|k| flanges.map(|sf| Head::new(OD, k).with_straight_flange(sf)))
        .collect()
}

/// Every part of the library with its patches: shell, all heads, three reducers.
fn all_parts() -> Vec<(String, Vec<Patch>)> {
    let mut parts = vec![(
        "shell".to_string(),
        Shell {
            outside_diameter: OD,
            length: 6000.0,
        }
        .patches()
        .unwrap(),
    )];
    for head in all_heads() {
        let name = format!("{} head, flange {}", head.kind.name(), head.straight_flange);
        parts.push((name, head.patches().unwrap()));
    }
    for alignment in [
        ReducerAlignment::Concentric,
        ReducerAlignment::Eccentric { flat_side: 0.0 },
        ReducerAlignment::Eccentric { flat_side: 270.0 },
    ] {
        let reducer = Reducer {
            large_diameter: OD,
            small_diameter: 1500.0,
            length: 900.0,
            alignment,
        };
        parts.push((format!("{alignment:?} reducer"), reducer.patches().unwrap()));
    }
    parts
}

/// Parameters at `fraction` of each direction of the domain.
fn at_fraction(s: &NurbsSurface, fu: f64, fv: f64) -> (f64, f64) {
    let ((u0, u1), (v0, v1)) = s.domain();
    (u0 + (u1 - u0) * fu, v0 + (v1 - v0) * fv)
}

#[test]
fn inversion_recovers_parameters_on_every_part() {
    let mut rng = Rng(0x5EED_0001);
    for (part, patches) in all_parts() {
        for patch in &patches {
            let s = &patch.surface;
            for _ in 0..60 {
                // Away from seams (u = 0 ≡ 1) and poles, where parameters are unique.
                let (u, v) = at_fraction(s, rng.range(0.01, 0.99), rng.range(0.01, 0.99));
                let p = s.point(u, v);
                let found = s.closest_point(p).unwrap();
                assert!(
                    (found.u - u).abs() <= PARAMETER_TOL && (found.v - v).abs() <= PARAMETER_TOL,
                    "{part} / {}: ({u}, {v}) recovered as ({}, {})",
                    patch.name,
                    found.u,
                    found.v
                );
                assert!(
                    found.distance <= POINT_TOL,
                    "{part}: distance {}",
                    found.distance
                );
            }
        }
    }
}

#[test]
fn inversion_finds_points_on_edges_poles_and_seams() {
    for (part, patches) in all_parts() {
        for patch in &patches {
            let s = &patch.surface;
            let edge = [0.0, 1e-9, 0.5, 1.0 - 1e-9, 1.0];
            for &fu in &edge {
                for &fv in &edge {
                    let (u, v) = at_fraction(s, fu, fv);
                    let p = s.point(u, v);
                    let found = s.closest_point(p).unwrap();
                    // Parameters need not be unique here: compare points.
                    assert!(
                        (found.point - p).length() <= POINT_TOL && found.distance <= POINT_TOL,
                        "{part} / {}: {p} at ({u}, {v}) found at {} ({}, {})",
                        patch.name,
                        found.point,
                        found.u,
                        found.v
                    );
                    let again = s.point(found.u, found.v);
                    assert!((again - found.point).length() <= POINT_TOL);
                }
            }
        }
    }
}

/// The closest point of the full analytic surface to `p`, for the kinds whose
/// projection is radial.
fn radial_projection(a: &Analytic, p: DVec3) -> Option<DVec3> {
    match *a {
        Analytic::Sphere { center, radius } => Some(center + (p - center).normalize() * radius),
        Analytic::Cylinder {
            point,
            axis,
            radius,
        } => {
            let foot = point + axis * (p - point).dot(axis);
            Some(foot + (p - foot).normalize() * radius)
        }
        Analytic::Torus {
            center,
            axis,
            major,
            minor,
        } => {
            let d = p - center;
            let radial = (d - axis * d.dot(axis)).normalize();
            let tube = center + radial * major;
            Some(tube + (p - tube).normalize() * minor)
        }
        _ => None,
    }
}

#[test]
fn off_surface_points_project_radially_on_spheres_cylinders_and_tori() {
    let mut rng = Rng(0x5EED_0002);
    let mut checked = 0;
    for (part, patches) in all_parts() {
        for patch in &patches {
            let s = &patch.surface;
            let limit = match patch.analytic {
                Analytic::Torus { minor, .. } => minor,
                Analytic::Sphere { radius, .. } | Analytic::Cylinder { radius, .. } => radius,
                _ => continue,
            };
            for _ in 0..30 {
                let (u, v) = at_fraction(s, rng.range(0.01, 0.99), rng.range(0.01, 0.99));
                let foot = s.point(u, v);
                // Along the normal, outwards any distance, inwards less than the
                // smallest radius of curvature.
                let t = rng.range(-0.9 * limit, 0.5 * OD);
                let p = foot + s.normal(u, v) * t;
                let Some(expect) = radial_projection(&patch.analytic, p) else {
                    continue;
                };
                assert!(
                    (expect - foot).length() <= 1e-9 * OD,
                    "{part}: bad test point"
                );
                let found = s.closest_point(p).unwrap();
                assert!(
                    (found.point - expect).length() <= 1e-9 * OD,
                    "{part} / {}: {p} projects to {}, expected {expect} ({} apart)",
                    patch.name,
                    found.point,
                    (found.point - expect).length()
                );
                assert!((found.distance - t.abs()).abs() <= 1e-9 * OD);
                checked += 1;
            }
        }
    }
    assert!(checked > 500, "only {checked} points checked");
}

/// Points of a 201 × 201 grid over the surface's domain.
fn dense_points(s: &NurbsSurface) -> Vec<DVec3> {
    let n = 200;
    (0..=n)
        .flat_map(|i| (0..=n).map(move |j| (i as f64 / n as f64, j as f64 / n as f64)))
        .map(|(fu, fv)| {
            let (u, v) = at_fraction(s, fu, fv);
            s.point(u, v)
        })
        .collect()
}

/// Asserts that no point of `dense` is closer to `p` than the projection found (for
/// a surface of about `size` mm), and that the projection is self-consistent.
fn assert_true_closest(s: &NurbsSurface, dense: &[DVec3], p: DVec3, size: f64, what: &str) {
    let found = s.closest_point(p).unwrap();
    let brute = dense
        .iter()
        .map(|q| (*q - p).length())
        .fold(f64::MAX, f64::min);
    assert!(
        found.distance <= brute + 1e-9 * size,
        "{what}: {p} found at {} but a grid point is at {brute}",
        found.distance
    );
    assert!((s.point(found.u, found.v) - found.point).length() <= 1e-12 * size);
    assert!(((found.point - p).length() - found.distance).abs() <= 1e-12 * size);
}

#[test]
fn off_surface_points_on_every_part_are_no_farther_than_brute_force() {
    let mut rng = Rng(0x5EED_0005);
    for (part, patches) in all_parts() {
        for patch in &patches {
            let s = &patch.surface;
            let dense = dense_points(s);
            for _ in 0..8 {
                let (x, y, z) = (
                    rng.range(-0.8, 0.8),
                    rng.range(-0.8, 0.8),
                    rng.range(-0.3, 1.5),
                );
                let what = format!("{part} / {}", patch.name);
                assert_true_closest(s, &dense, DVec3::new(x, y, z) * OD, OD, &what);
            }
        }
    }
}

#[test]
fn closest_point_on_a_boundary_or_a_pole() {
    let r = OD / 2.0;
    let hemisphere = &Head::new(OD, HeadKind::Hemispherical).patches().unwrap()[0].surface;
    // Below the rim, off to the side: the nearest point is on the rim circle.
    let found = hemisphere
        .closest_point(DVec3::new(0.0, 2.0 * r, -r))
        .unwrap();
    assert!((found.point - DVec3::new(0.0, r, 0.0)).length() <= 1e-9 * OD);
    assert!((found.v - 0.0).abs() <= PARAMETER_TOL && (found.u - 0.25).abs() <= PARAMETER_TOL);
    // On the axis above the pole: the pole, at any u.
    let found = hemisphere
        .closest_point(DVec3::new(0.0, 0.0, 3.0 * r))
        .unwrap();
    assert!((found.point - DVec3::new(0.0, 0.0, r)).length() <= 1e-9 * OD);
    assert!((found.distance - 2.0 * r).abs() <= 1e-9 * OD);
    // Just off the pole, on the far side of the seam meridian.
    let p = DVec3::new(-1e-3 * r, -1e-3 * r, 1.01 * r);
    let found = hemisphere.closest_point(p).unwrap();
    let expect = p.normalize() * r;
    assert!(
        (found.point - expect).length() <= 1e-9 * OD,
        "{}",
        found.point
    );
    // The centre: every point is at distance r.
    let found = hemisphere.closest_point(DVec3::ZERO).unwrap();
    assert!((found.distance - r).abs() <= 1e-9 * OD);
    // Non-finite query points are errors.
    for bad in [
        DVec3::new(f64::NAN, 0.0, 0.0),
        DVec3::new(0.0, f64::INFINITY, 0.0),
    ] {
        assert!(matches!(
            hemisphere.closest_point(bad),
            Err(NurbsError::QueryPointNotFinite { .. })
        ));
    }
}

/// A random rational bicubic patch over a perturbed grid (a graph over the XY
/// plane, so parameters are unique), with random interior knots and weights.
fn random_surface(rng: &mut Rng) -> NurbsSurface {
    let knots = |rng: &mut Rng, count: usize| {
        let mut interior: Vec<f64> = (0..count - 4).map(|_| rng.range(0.05, 0.95)).collect();
        interior.sort_by(f64::total_cmp);
        let mut k = vec![0.0; 4];
        k.extend(interior);
        k.extend([1.0; 4]);
        KnotVector::new(3, k)
    };
    let (nu, nv) = (6, 7);
    let (ku, kv) = (knots(rng, nu), knots(rng, nv));
    let mut points = Vec::new();
    for i in 0..nu {
        for j in 0..nv {
            let p = DVec3::new(
                i as f64 * 10.0 + rng.range(-2.0, 2.0),
                j as f64 * 10.0 + rng.range(-2.0, 2.0),
                rng.range(-15.0, 15.0),
            );
            let w = rng.range(0.5, 2.0);
            points.push(DVec4::new(p.x * w, p.y * w, p.z * w, w));
        }
    }
    NurbsSurface::try_new(ku, kv, points).unwrap()
}

#[test]
fn random_surfaces_recover_parameters_and_true_closest_points() {
    let mut rng = Rng(0x5EED_0003);
    for _ in 0..20 {
        let s = random_surface(&mut rng);
        for _ in 0..40 {
            let (u, v) = (rng.range(0.0, 1.0), rng.range(0.0, 1.0));
            let found = s.closest_point(s.point(u, v)).unwrap();
            assert!(
                (found.u - u).abs() <= PARAMETER_TOL && (found.v - v).abs() <= PARAMETER_TOL,
                "({u}, {v}) recovered as ({}, {})",
                found.u,
                found.v
            );
        }
        // Off the surface: no point of a dense grid is closer than the one found.
        let dense = dense_points(&s);
        for _ in 0..10 {
            let (x, y, z) = (
                rng.range(-20.0, 70.0),
                rng.range(-20.0, 80.0),
                rng.range(-40.0, 40.0),
            );
            assert_true_closest(&s, &dense, DVec3::new(x, y, z), 100.0, "random surface");
        }
    }
}

#[test]
fn curve_inversion_on_circles_and_arcs() {
    let mut rng = Rng(0x5EED_0004);
    let center = DVec3::new(10.0, -20.0, 5.0);
    let normal = DVec3::new(1.0, 2.0, 3.0).normalize();
    let radius = 700.0;
    let c = circle(center, normal, radius).unwrap();
    for _ in 0..200 {
        let u = rng.range(0.001, 0.999);
        let found = c.closest_point(c.point(u)).unwrap();
        assert!((found.u - u).abs() <= PARAMETER_TOL, "{u} → {}", found.u);
        // Off the circle: the radial projection within the plane.
        let p = center
            + DVec3::new(
                rng.range(-1.0, 1.0),
                rng.range(-1.0, 1.0),
                rng.range(-1.0, 1.0),
            ) * 2.0
                * radius;
        let d = p - center;
        let in_plane = d - normal * d.dot(normal);
        let expect = center + in_plane.normalize() * radius;
        let found = c.closest_point(p).unwrap();
        assert!((found.point - expect).length() <= 1e-9 * radius, "{p}");
        assert!((found.distance - (p - expect).length()).abs() <= 1e-9 * radius);
    }
    // An arc: points whose angle lies outside it project to the nearer end.
    let (start, end) = (0.3, 2.2);
    let arc = circular_arc(DVec3::ZERO, DVec3::X, DVec3::Y, radius, start, end).unwrap();
    for k in 0..72 {
        let angle = k as f64 * TAU / 72.0;
        let p = DVec3::new(angle.cos(), angle.sin(), 0.3) * 1.5 * radius;
        let expect = if (start..=end).contains(&angle) {
            DVec3::new(angle.cos(), angle.sin(), 0.0) * radius
        } else {
            let (a, b) = (arc.start(), arc.end());
            if (a - p).length() < (b - p).length() {
                a
            } else {
                b
            }
        };
        let found = arc.closest_point(p).unwrap();
        assert!(
            (found.point - expect).length() <= 1e-9 * radius,
            "angle {angle}"
        );
    }
    assert!(matches!(
        arc.closest_point(DVec3::splat(f64::NAN)),
        Err(NurbsError::QueryPointNotFinite { .. })
    ));
}
