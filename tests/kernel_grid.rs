//! Batched grid evaluation equals pointwise evaluation: points and normals of
//! `evaluate_grid` / `evaluate_grid_with_normals` match `NurbsSurface::point` and
//! `NurbsSurface::normal` on shells, every head kind (including the pole of a
//! hemispherical head and the apex of a conical one, where the normal is a limit), at
//! knot values exactly and at the domain ends, and on random rational surfaces of
//! degree 1–4 with repeated knots.

mod common;

use common::heads::head_kinds;
use glam::{DVec3, DVec4};
use proptest::prelude::*;
use proptest::test_runner::RngSeed;
use vesselcad::nurbs::grid::{GridBasis, GridError};
use vesselcad::nurbs::{KnotVector, NurbsSurface};
use vesselcad::parts::heads::{Head, HeadKind};
use vesselcad::parts::{Patch, Shell};

const OD: f64 = 2400.0;
/// Largest point deviation from pointwise evaluation, relative to the surface's size.
const POINT_REL: f64 = 1e-12;
/// Largest deviation of a unit normal from the pointwise one on vessel patches.
const NORMAL_TOL: f64 = 1e-12;
/// The same for random surfaces, whose normals are only as well conditioned as the
/// random net happens to make them (the grid recomputes the worst ones pointwise).
const RANDOM_NORMAL_TOL: f64 = 1e-10;
/// Evenly spaced grid parameters per direction (knot values are added to them).
const SAMPLES: usize = 41;

fn all_heads() -> Vec<Head> {
    let kinds = head_kinds(OD);
    kinds
        .into_iter()
        .flat_map(|k| {
            [
                Head::new(OD, k),
                Head::new(OD, k).with_straight_flange(50.0),
            ]
        })
        .collect()
}

fn shell() -> Vec<Patch> {
    Shell {
        outside_diameter: OD,
        length: 6000.0,
    }
    .patches()
    .unwrap()
}

/// `n` evenly spaced parameters over the domain (both ends exactly) and every distinct
/// knot value exactly, increasing.
fn params(knots: &KnotVector, n: usize) -> Vec<f64> {
    let (a, b) = knots.domain();
    let mut out: Vec<f64> = (0..n)
        .map(|i| a + (b - a) * i as f64 / (n - 1) as f64)
        .chain(knots.distinct())
        .collect();
    out.sort_by(f64::total_cmp);
    out.dedup();
    out
}

/// Largest distance of a control point from the origin: the scale of point errors.
fn size(surface: &NurbsSurface) -> f64 {
    surface
        .control_points()
        .iter()
        .map(|p| p.length())
        .fold(1.0, f64::max)
}

/// Largest point error (relative to the surface's size) and normal error of the grid
/// evaluators against pointwise evaluation on `us × vs`.
fn grid_errors(surface: &NurbsSurface, us: &[f64], vs: &[f64]) -> (f64, f64) {
    let (mut points, mut with_normals, mut normals) = (Vec::new(), Vec::new(), Vec::new());
    surface.evaluate_grid(us, vs, &mut points);
    surface.evaluate_grid_with_normals(us, vs, &mut with_normals, &mut normals);
    assert_eq!(points.len(), us.len() * vs.len());
    assert_eq!(points, with_normals, "both evaluators give the same points");
    assert_eq!(normals.len(), points.len());
    let scale = size(surface);
    let (mut point_error, mut normal_error) = (0.0f64, 0.0f64);
    for (i, &u) in us.iter().enumerate() {
        for (j, &v) in vs.iter().enumerate() {
            let k = i * vs.len() + j;
            point_error = point_error.max((points[k] - surface.point(u, v)).length() / scale);
            normal_error = normal_error.max((normals[k] - surface.normal(u, v)).length());
            assert!(
                (normals[k].length() - 1.0).abs() < 1e-12,
                "non-unit normal {} at ({u}, {v})",
                normals[k]
            );
        }
    }
    (point_error, normal_error)
}

/// Asserts the grid evaluators match pointwise evaluation on the default grid of
/// every patch.
fn assert_patches_match(part: &str, patches: &[Patch]) {
    for patch in patches {
        let s = &patch.surface;
        let (us, vs) = (params(s.u_knots(), SAMPLES), params(s.v_knots(), SAMPLES));
        let (point_error, normal_error) = grid_errors(s, &us, &vs);
        assert!(
            point_error <= POINT_REL,
            "{part} {}: point error {point_error:e} (relative)",
            patch.name
        );
        assert!(
            normal_error <= NORMAL_TOL,
            "{part} {}: normal error {normal_error:e}",
            patch.name
        );
    }
}

#[test]
fn shell_grid_matches_pointwise() {
    assert_patches_match("shell", &shell());
}

#[test]
fn every_head_grid_matches_pointwise() {
    for head in all_heads() {
        let name = format!(
            "{} head (flange {})",
            head.kind.name(),
            head.straight_flange
        );
        assert_patches_match(&name, &head.patches().unwrap());
    }
}

/// The last patch of a head (the crown or cone) ends at the pole or apex, v = v1.
fn top_patch(kind: HeadKind) -> NurbsSurface {
    let patches = Head::new(OD, kind).patches().unwrap();
    patches.last().unwrap().surface.clone()
}

#[test]
fn pole_and_apex_normals_are_the_pointwise_limits() {
    let cone = HeadKind::Conical {
        half_angle: 30.0,
        small_diameter: 0.0,
    };
    for (kind, expected_z) in [(HeadKind::Hemispherical, Some(1.0)), (cone, None)] {
        let s = top_patch(kind);
        let us = params(s.u_knots(), 17);
        let v1 = s.v_knots().domain().1;
        let (mut points, mut normals) = (Vec::new(), Vec::new());
        s.evaluate_grid_with_normals(&us, &[v1], &mut points, &mut normals);
        for (k, &u) in us.iter().enumerate() {
            assert_eq!(points[k], s.point(u, v1), "{} top point", kind.name());
            assert_eq!(normals[k], s.normal(u, v1), "{} top normal", kind.name());
            assert!(normals[k].is_finite() && (normals[k].length() - 1.0).abs() < 1e-12);
            if let Some(z) = expected_z {
                assert!((normals[k] - DVec3::Z * z).length() < 1e-12, "pole normal");
            }
        }
    }
}

#[test]
fn parameters_are_clamped_and_may_come_in_any_order() {
    let s = &top_patch(HeadKind::asme_fd(OD));
    let ((u0, u1), (v0, v1)) = s.domain();
    let us = [u1 + 0.5, 0.7 * u1, u0, f64::NAN, 0.3 * u1, u0 - 2.0, u1];
    let vs = [v1, v0 - 1.0, 0.5 * (v0 + v1), v0, v1 + 1e-3, 0.25 * v1];
    let (mut points, mut normals) = (Vec::new(), Vec::new());
    s.evaluate_grid_with_normals(&us, &vs, &mut points, &mut normals);
    for (i, &u) in us.iter().enumerate() {
        for (j, &v) in vs.iter().enumerate() {
            let k = i * vs.len() + j;
            assert!((points[k] - s.point(u, v)).length() <= POINT_REL * size(s));
            assert!((normals[k] - s.normal(u, v)).length() <= NORMAL_TOL);
        }
    }
    let basis = GridBasis::new(s.u_knots(), &us);
    assert_eq!(basis.params()[3], u0, "NaN maps to the domain start");
    assert!(basis.params().iter().all(|&u| (u0..=u1).contains(&u)));
}

#[test]
fn bases_are_reusable_and_checked() {
    let shell = &shell()[0].surface;
    let crown = top_patch(HeadKind::Hemispherical);
    let u = GridBasis::new(shell.u_knots(), &params(shell.u_knots(), 33));
    let v = GridBasis::new(shell.v_knots(), &params(shell.v_knots(), 9));
    assert!(shell.can_evaluate_grid_on(&u, &v));
    let (mut a, mut b) = (Vec::new(), Vec::new());
    shell.try_evaluate_grid_on(&u, &v, &mut a).unwrap();
    shell.evaluate_grid(u.params(), v.params(), &mut b);
    assert_eq!(a, b);
    // Same circle along u, but an arc instead of a line along v.
    assert!(!crown.can_evaluate_grid_on(&u, &v));
    assert_eq!(
        crown.try_evaluate_grid_with_normals_on(&u, &v, &mut a, &mut b),
        Err(GridError::KnotsMismatch { direction: "v" })
    );
}

#[test]
fn buffers_are_resized_and_empty_grids_are_empty() {
    let s = &shell()[0].surface;
    let us = params(s.u_knots(), 5);
    let vs = params(s.v_knots(), 3);
    let mut points = vec![DVec3::NAN; 1000];
    let mut normals = vec![DVec3::NAN; 2];
    s.evaluate_grid_with_normals(&us, &vs, &mut points, &mut normals);
    assert_eq!(points.len(), us.len() * vs.len());
    assert_eq!(normals.len(), us.len() * vs.len());
    assert!(points.iter().chain(&normals).all(|p| p.is_finite()));
    s.evaluate_grid(&us, &[], &mut points);
    assert!(points.is_empty());
    s.evaluate_grid_with_normals(&[], &vs, &mut points, &mut normals);
    assert!(points.is_empty() && normals.is_empty());
}

/// A random clamped knot vector of degree 1–4 on a random domain, with interior knots
/// on a grid of twentieths of the domain, each repeated up to `degree` times.
fn knot_vector() -> impl Strategy<Value = KnotVector> {
    (
        1usize..=4,
        -10.0..10.0f64,
        0.5..20.0f64,
        prop::collection::btree_set(1u32..20, 0..=4),
        prop::collection::vec(0usize..4, 4),
    )
        .prop_map(|(degree, start, length, positions, multiplicities)| {
            let mut knots = vec![start; degree + 1];
            for (&position, m) in positions.iter().zip(multiplicities) {
                let knot = start + length * position as f64 / 20.0;
                knots.extend(std::iter::repeat_n(knot, m % degree + 1));
            }
            knots.extend(std::iter::repeat_n(start + length, degree + 1));
            KnotVector::new(degree, knots)
        })
}

/// A random rational surface: control points in a 1000 mm box, weights in [0.2, 5].
fn surface() -> impl Strategy<Value = NurbsSurface> {
    (knot_vector(), knot_vector()).prop_flat_map(|(u, v)| {
        let count = u.basis_count() * v.basis_count();
        let coordinate = -500.0..500.0f64;
        let point = (
            coordinate.clone(),
            coordinate.clone(),
            coordinate,
            0.2..5.0f64,
        )
            .prop_map(|(x, y, z, w)| DVec4::new(x * w, y * w, z * w, w));
        prop::collection::vec(point, count)
            .prop_map(move |points| NurbsSurface::try_new(u.clone(), v.clone(), points).unwrap())
    })
}

proptest! {
    #![proptest_config(ProptestConfig {
        cases: 128,
        rng_seed: RngSeed::Fixed(0x6121d),
        failure_persistence: None,
        ..ProptestConfig::default()
    })]

    #[test]
    fn random_surface_grid_matches_pointwise(s in surface()) {
        let (us, vs) = (params(s.u_knots(), 13), params(s.v_knots(), 13));
        let (point_error, normal_error) = grid_errors(&s, &us, &vs);
        prop_assert!(point_error <= POINT_REL, "point error {point_error:e}");
        prop_assert!(normal_error <= RANDOM_NORMAL_TOL, "normal error {normal_error:e}");
    }
}

/// The first-order evaluation (the intersection's Newton path) gives exactly the
/// point and first derivatives of the full one, on every head and the shell, and
/// on a degree-5 surface (the general-size path).
#[test]
fn first_derivatives_equal_the_full_evaluation() {
    let mut surfaces: Vec<NurbsSurface> = shell().into_iter().map(|p| p.surface).collect();
    for head in all_heads() {
        surfaces.extend(head.patches().unwrap().into_iter().map(|p| p.surface));
    }
    let knots = KnotVector::new(
        5,
        vec![0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0],
    );
    let lin = KnotVector::new(1, vec![0.0, 0.0, 1.0, 1.0]);
    let points: Vec<DVec4> = (0..12)
        .map(|k| {
            let (i, j) = ((k / 2) as f64, (k % 2) as f64);
            DVec4::new(i * 10.0, j * 7.0 + i * i, (i * j).sin(), 1.0 + 0.1 * i)
        })
        .collect();
    surfaces.push(NurbsSurface::try_new(knots, lin, points).unwrap());
    for s in &surfaces {
        let (us, vs) = (params(s.u_knots(), 9), params(s.v_knots(), 9));
        for &u in &us {
            for &v in &vs {
                let full = s.derivatives(u, v);
                let first = s.first_derivatives(u, v);
                assert_eq!(
                    (first.point, first.du, first.dv),
                    (full.point, full.du, full.dv)
                );
            }
        }
    }
}
