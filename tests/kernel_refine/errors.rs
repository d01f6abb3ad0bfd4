//! Every rejected request returns its typed error.

use glam::{DAffine3, DVec3};
use vesselcad::nurbs::builders::ruled;
use vesselcad::nurbs::{KnotVector, MAX_DEGREE, NurbsCurve, NurbsError, ParallelProjection};

/// The quadratic on [0, 2] with knots {0³, 0.5, 1, 1.5, 2³} through a spatial polygon.
fn sample_curve() -> NurbsCurve {
    let knots = KnotVector::try_new(2, vec![0.0, 0.0, 0.0, 0.5, 1.0, 1.5, 2.0, 2.0, 2.0]).unwrap();
    let points = [
        DVec3::new(0.0, 0.0, 0.0),
        DVec3::new(1.0, 2.0, 0.0),
        DVec3::new(3.0, 2.0, 1.0),
        DVec3::new(4.0, 0.0, 1.0),
        DVec3::new(5.0, -1.0, 0.0),
        DVec3::new(6.0, 0.0, 2.0),
    ];
    NurbsCurve::try_from_weighted(knots, &points, &[1.0, 0.5, 2.0, 1.0, 0.7, 1.0]).unwrap()
}

#[test]
fn insertion_outside_the_domain_is_rejected() {
    let c = sample_curve();
    for u in [-0.5, 2.5, f64::NAN] {
        let is_rejected = matches!(
            c.insert_knot(u, 1),
            Err(NurbsError::ParameterOutOfDomain { .. })
        );
        assert!(is_rejected, "u = {u}");
    }
    let s = ruled(&c, &c.reversed()).unwrap();
    assert!(matches!(
        s.insert_knot_v(1.5, 1),
        Err(NurbsError::ParameterOutOfDomain { .. })
    ));
}

#[test]
fn insertion_beyond_the_degree_is_rejected() {
    let c = sample_curve();
    assert_eq!(
        c.insert_knot(0.5, 2),
        Err(NurbsError::InsertionExceedsDegree {
            knot: 0.5,
            multiplicity: 3,
            degree: 2
        })
    );
    assert!(c.insert_knot(0.5, 1).is_ok());
    assert!(matches!(
        c.insert_knot(0.0, 1),
        Err(NurbsError::InsertionExceedsDegree { .. })
    ));
    assert!(matches!(
        c.refine_knots(&[0.7, 0.7, 0.7]),
        Err(NurbsError::InsertionExceedsDegree { .. })
    ));
    assert_eq!(c.insert_knot(0.7, 0).unwrap(), c);
}

#[test]
fn unsorted_or_outside_refinement_knots_are_rejected() {
    let c = sample_curve();
    assert_eq!(
        c.refine_knots(&[0.25, 0.75, 0.6]),
        Err(NurbsError::RefinementKnotsUnsorted {
            index: 2,
            previous: 0.75,
            next: 0.6
        })
    );
    assert!(matches!(
        c.refine_knots(&[0.25, 3.0]),
        Err(NurbsError::ParameterOutOfDomain { .. })
    ));
    assert_eq!(c.refine_knots(&[]).unwrap(), c);
}

#[test]
fn splitting_at_or_beyond_the_ends_is_rejected() {
    let c = sample_curve();
    for u in [0.0, 2.0, -1.0, f64::NAN] {
        assert!(
            matches!(c.split_at(u), Err(NurbsError::ParameterOutOfDomain { .. })),
            "u = {u}"
        );
    }
}

#[test]
fn elevation_beyond_max_degree_is_rejected() {
    let c = sample_curve();
    assert_eq!(
        c.elevate_degree(MAX_DEGREE),
        Err(NurbsError::DegreeOutOfRange {
            degree: MAX_DEGREE + 2,
            max: MAX_DEGREE
        })
    );
    assert_eq!(
        c.elevate_degree(MAX_DEGREE - 2).unwrap().degree(),
        MAX_DEGREE
    );
    assert_eq!(c.elevate_degree(0).unwrap(), c);
}

#[test]
fn projection_along_the_plane_is_rejected() {
    assert!(matches!(
        ParallelProjection::try_new(DVec3::ZERO, DVec3::Z, DVec3::X),
        Err(NurbsError::ProjectionParallelToPlane { .. })
    ));
    assert!(matches!(
        ParallelProjection::try_new(DVec3::ZERO, DVec3::Z, DVec3::new(1.0, 0.0, 1e-12)),
        Err(NurbsError::ProjectionParallelToPlane { .. })
    ));
    assert!(matches!(
        ParallelProjection::try_new(DVec3::ZERO, DVec3::ZERO, DVec3::X),
        Err(NurbsError::InvalidGeometry { .. })
    ));
    assert!(matches!(
        ParallelProjection::try_new(DVec3::new(f64::NAN, 0.0, 0.0), DVec3::Z, DVec3::Z),
        Err(NurbsError::InvalidGeometry { .. })
    ));
    assert!(matches!(
        ParallelProjection::try_new(DVec3::ZERO, DVec3::Z, DVec3::new(0.0, f64::INFINITY, 1.0)),
        Err(NurbsError::InvalidGeometry { .. })
    ));
}

#[test]
fn non_finite_transforms_are_rejected() {
    let c = sample_curve();
    let bad = DAffine3::from_translation(DVec3::new(0.0, f64::NAN, 0.0));
    assert!(matches!(
        c.transformed(&bad),
        Err(NurbsError::InvalidGeometry { .. })
    ));
    let s = ruled(&c, &c.reversed()).unwrap();
    assert!(matches!(
        s.transformed(&DAffine3::from_scale(DVec3::splat(f64::INFINITY))),
        Err(NurbsError::InvalidGeometry { .. })
    ));
}
