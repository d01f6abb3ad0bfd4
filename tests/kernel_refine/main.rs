//! The kernel's shape-preserving operations leave the geometry where it was.
//!
//! Property tests over random rational curves and surfaces (degrees 1–4, interior
//! knots with multiplicity up to the degree, weights in [0.2, 5], control points in
//! a box of side 1000): knot insertion, refinement, degree elevation, splitting and
//! reversal move no point; affine maps and parallel projections commute with
//! evaluation; the bounding box contains the geometry. Then the error cases, and an
//! exact ruled surface between a line and an arc.

mod errors;
mod exact;
mod random;

use glam::{DAffine3, DMat3, DVec3};
use proptest::prelude::*;
use random::*;
use vesselcad::nurbs::{NurbsError, ParallelProjection, make_compatible};

proptest! {
    #![proptest_config(config())]

    #[test]
    fn curve_knot_insertion_keeps_shape(
        c in curve(), f in 0.001..0.999f64, on_knot: bool, times in 1usize..=4,
    ) {
        let u = pick_parameter(c.knots(), f, on_knot);
        let before = c.knots().multiplicity(u);
        let result = c.insert_knot(u, times);
        if before + times > c.degree() {
            let is_rejected = matches!(result, Err(NurbsError::InsertionExceedsDegree { .. }));
            prop_assert!(is_rejected);
        } else {
            let r = result.unwrap();
            prop_assert_eq!(r.knots().multiplicity(u), before + times);
            prop_assert_eq!(r.homogeneous_points().len(), c.homogeneous_points().len() + times);
            prop_assert!(curve_deviation(&r, &c) <= TOL);
        }
    }

    #[test]
    fn curve_refinement_keeps_shape(
        c in curve(), fortieths in prop::collection::vec(1u32..40, 0..10),
    ) {
        let (a, b) = c.domain();
        let mut new: Vec<f64> = fortieths.iter().map(|&k| a + (b - a) * (k as f64 / 40.0)).collect();
        new.sort_by(f64::total_cmp);
        let too_many = new.iter().any(|&x| {
            c.knots().multiplicity(x) + new.iter().filter(|&&y| y == x).count() > c.degree()
        });
        match c.refine_knots(&new) {
            Ok(r) => {
                prop_assert!(!too_many);
                prop_assert_eq!(r.knots().len(), c.knots().len() + new.len());
                prop_assert!(curve_deviation(&r, &c) <= TOL);
            }
            Err(e) => {
                prop_assert!(too_many, "unexpected {e}");
                let is_rejected = matches!(e, NurbsError::InsertionExceedsDegree { .. });
                prop_assert!(is_rejected);
            }
        }
    }

    #[test]
    fn curve_degree_elevation_keeps_shape(c in curve(), times in 1usize..=3) {
        let r = c.elevate_degree(times).unwrap();
        prop_assert_eq!(r.degree(), c.degree() + times);
        prop_assert_eq!(r.domain(), c.domain());
        let (a, b) = c.domain();
        for k in c.knots().distinct().into_iter().filter(|&k| k > a && k < b) {
            prop_assert_eq!(r.knots().multiplicity(k), c.knots().multiplicity(k) + times);
        }
        prop_assert!(curve_deviation(&r, &c) <= TOL);
    }

    #[test]
    fn curve_split_keeps_shape(c in curve(), f in 0.001..0.999f64, on_knot: bool) {
        let u = pick_parameter(c.knots(), f, on_knot);
        let (left, right) = c.split_at(u).unwrap();
        prop_assert_eq!(left.domain(), (c.domain().0, u));
        prop_assert_eq!(right.domain(), (u, c.domain().1));
        prop_assert!(curve_deviation(&c, &left) <= TOL);
        prop_assert!(curve_deviation(&c, &right) <= TOL);
        prop_assert!((left.end() - right.start()).length() <= TOL);
    }

    #[test]
    fn compatible_curves_share_a_basis_and_keep_their_shapes(a in curve(), b in curve()) {
        let (ca, cb) = make_compatible(&a, &b).unwrap();
        prop_assert_eq!(ca.knots(), cb.knots());
        prop_assert_eq!(ca.domain(), (0.0, 1.0));
        for (original, compatible) in [(&a, &ca), (&b, &cb)] {
            let (t0, t1) = original.domain();
            for i in 0..=SAMPLES {
                let s = i as f64 / SAMPLES as f64;
                let d = (compatible.point(s) - original.point(t0 + (t1 - t0) * s)).length();
                prop_assert!(d <= TOL, "deviation {d} at {s}");
            }
        }
    }

    #[test]
    fn surface_operations_keep_shape(
        s in surface(), f in 0.001..0.999f64, g in 0.001..0.999f64, on_knot: bool,
    ) {
        let u = pick_parameter(s.u_knots(), f, on_knot);
        let v = pick_parameter(s.v_knots(), g, on_knot);
        if s.u_knots().multiplicity(u) < s.u_degree() {
            prop_assert!(surface_deviation(&s.insert_knot_u(u, 1).unwrap(), &s) <= TOL);
        }
        if s.v_knots().multiplicity(v) < s.v_degree() {
            prop_assert!(surface_deviation(&s.insert_knot_v(v, 1).unwrap(), &s) <= TOL);
        }
        let ((u0, u1), (v0, v1)) = s.domain();
        let ru = s.refine_knots_u(&[u0 + (u1 - u0) * 0.31, u0 + (u1 - u0) * 0.77]).unwrap();
        prop_assert!(surface_deviation(&ru, &s) <= TOL);
        let rv = s.refine_knots_v(&[v0 + (v1 - v0) * 0.13, v0 + (v1 - v0) * 0.59]).unwrap();
        prop_assert!(surface_deviation(&rv, &s) <= TOL);
        let eu = s.elevate_degree_u(2).unwrap();
        prop_assert_eq!(eu.u_degree(), s.u_degree() + 2);
        prop_assert!(surface_deviation(&eu, &s) <= TOL);
        let ev = s.elevate_degree_v(1).unwrap();
        prop_assert_eq!(ev.v_degree(), s.v_degree() + 1);
        prop_assert!(surface_deviation(&ev, &s) <= TOL);
        for (low, high) in [s.split_u(u).unwrap(), s.split_v(v).unwrap()] {
            prop_assert!(surface_deviation(&s, &low) <= TOL);
            prop_assert!(surface_deviation(&s, &high) <= TOL);
        }
        let (a, b) = s.split_u(u).unwrap();
        prop_assert_eq!(a.domain().0, (u0, u));
        prop_assert_eq!(b.domain().0, (u, u1));
        let (a, b) = s.split_v(v).unwrap();
        prop_assert_eq!(a.domain().1, (v0, v));
        prop_assert_eq!(b.domain().1, (v, v1));
    }

    #[test]
    fn surface_reversal_runs_backwards(s in surface(), f in 0.0..=1.0f64, g in 0.0..=1.0f64) {
        let ((u0, u1), (v0, v1)) = s.domain();
        let (u, v) = (u0 + (u1 - u0) * f, v0 + (v1 - v0) * g);
        let p = s.point(u, v);
        prop_assert!((s.reversed_u().point(u0 + u1 - u, v) - p).length() <= TOL);
        prop_assert!((s.reversed_v().point(u, v0 + v1 - v) - p).length() <= TOL);
    }

    #[test]
    fn affine_maps_commute_with_evaluation(
        c in curve(), s in surface(),
        m in prop::array::uniform9(-2.0..2.0f64), t in prop::array::uniform3(-BOX..BOX),
        f in 0.0..=1.0f64, g in 0.0..=1.0f64,
    ) {
        let affine = DAffine3::from_mat3_translation(DMat3::from_cols_array(&m), t.into());
        let tol = TOL * (1.0 + DMat3::from_cols_array(&m).abs().to_cols_array().iter().sum::<f64>());
        let tc = c.transformed(&affine).unwrap();
        prop_assert_eq!(tc.weights(), c.weights());
        let (a, b) = c.domain();
        for i in 0..=SAMPLES {
            let x = a + (b - a) * i as f64 / SAMPLES as f64;
            prop_assert!((tc.point(x) - affine.transform_point3(c.point(x))).length() <= tol);
        }
        let ts = s.transformed(&affine).unwrap();
        let ((u0, u1), (v0, v1)) = s.domain();
        let (u, v) = (u0 + (u1 - u0) * f, v0 + (v1 - v0) * g);
        prop_assert!((ts.point(u, v) - affine.transform_point3(s.point(u, v))).length() <= tol);
    }

    #[test]
    fn parallel_projection_lands_on_the_plane_along_the_direction(
        c in curve(), s in surface(),
        q in prop::array::uniform3(-BOX..BOX), n in prop::array::uniform3(-1.0..1.0f64),
        slant in prop::array::uniform3(-3.0..3.0f64), f in 0.0..=1.0f64, g in 0.0..=1.0f64,
    ) {
        let n = DVec3::from(n);
        prop_assume!(n.length() > 0.1);
        // W = N + a slant within the plane: |cos(N, W)| ≥ 1/√(1 + 27).
        let slant = DVec3::from(slant);
        let w = n.normalize() + (slant - n.normalize() * slant.dot(n.normalize()));
        let proj = ParallelProjection::try_new(q.into(), n, w).unwrap();
        // Points move by up to |BOX| / cos ≈ 5.3 BOX.
        let tol = 10.0 * TOL;
        let check = |before: DVec3, after: DVec3| {
            let off_plane = proj.plane_normal().dot(after - proj.plane_point()).abs();
            let off_direction = (after - before).cross(proj.direction()).length();
            off_plane <= tol && off_direction <= tol
        };
        let pc = c.projected(&proj).unwrap();
        prop_assert_eq!(pc.weights(), c.weights());
        let (a, b) = c.domain();
        for i in 0..=SAMPLES {
            let x = a + (b - a) * i as f64 / SAMPLES as f64;
            prop_assert!(check(c.point(x), pc.point(x)));
        }
        let ps = s.projected(&proj).unwrap();
        let ((u0, u1), (v0, v1)) = s.domain();
        let (u, v) = (u0 + (u1 - u0) * f, v0 + (v1 - v0) * g);
        prop_assert!(check(s.point(u, v), ps.point(u, v)));
        prop_assert!((ps.point(u, v) - proj.project_point(s.point(u, v))).length() <= tol);
    }

    #[test]
    fn bounding_box_contains_the_geometry(c in curve(), s in surface()) {
        let cb = c.bounding_box().expanded(TOL);
        let (a, b) = c.domain();
        for t in params(a, b, c.knots()) {
            prop_assert!(cb.contains(c.point(t)));
        }
        let sb = s.bounding_box().expanded(TOL);
        let ((u0, u1), (v0, v1)) = s.domain();
        for u in params(u0, u1, s.u_knots()).into_iter().step_by(4) {
            for v in params(v0, v1, s.v_knots()).into_iter().step_by(4) {
                prop_assert!(sb.contains(s.point(u, v)));
            }
        }
    }
}
