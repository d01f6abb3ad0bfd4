//! Nozzles for every size, class, flange type and facing in the ASME tables: patches
//! lie on their analytic surfaces, meet G0, have outward normals, put the gasket face
//! at z = projection and the neck on the B36.10M OD; bad input is a typed error.

mod common;

use common::numbers::any_number_up_to;
use common::*;
use glam::DVec3;
use proptest::prelude::*;
use vesselcad::parts::tables::{
    FlangeClass, Nps, PipeSchedule, TableError, flange, pipe, raised_face_height,
};
use vesselcad::parts::{Analytic, Facing, FlangeType, Nozzle, PartError, Patch};

const FLANGE_TYPES: [FlangeType; 3] = [FlangeType::WeldNeck, FlangeType::SlipOn, FlangeType::Blind];
const FACINGS: [Facing; 3] = [Facing::RaisedFace, Facing::FlatFace, Facing::RingJoint];

/// Extra neck beyond the minimum in the standard test nozzles, mm.
const EXTRA_NECK: f64 = 137.5;

fn nozzle(nps: Nps, class: FlangeClass, flange: FlangeType, facing: Facing) -> Nozzle {
    Nozzle {
        nps,
        schedule: PipeSchedule::Std,
        class,
        flange,
        facing,
        projection: 0.0,
    }
}

/// The same nozzle with the shortest valid projection plus `extra` mm.
fn with_neck(n: Nozzle, extra: f64) -> Nozzle {
    let length = n.flange_length().expect("listed flange");
    Nozzle {
        projection: length + Nozzle::MIN_NECK_LENGTH + extra,
        ..n
    }
}

/// Every combination the tables cover, with the standard projection; the unlisted
/// ones are checked to be table errors.
fn all_listed() -> Vec<Nozzle> {
    let mut out = Vec::new();
    for nps in Nps::all() {
        for class in FlangeClass::ALL {
            for flange_type in FLANGE_TYPES {
                for facing in FACINGS {
                    let n = Nozzle {
                        projection: 500.0,
                        ..nozzle(nps, class, flange_type, facing)
                    };
                    match flange(nps, class) {
                        Ok(_) => out.push(with_neck(n, EXTRA_NECK)),
                        Err(e) => {
                            assert_eq!(n.flange_length(), Err(PartError::Table(e.clone())));
                            assert_eq!(n.validate(), Err(PartError::Table(e.clone())));
                            assert_eq!(n.patches(), Err(PartError::Table(e)));
                        }
                    }
                }
            }
        }
    }
    // 79 listed (size, class) pairs × 3 types × 3 facings.
    assert_eq!(out.len(), 79 * 9);
    out
}

fn flange_od(n: &Nozzle) -> f64 {
    flange(n.nps, n.class).expect("listed").outside_diameter
}

fn names(patches: &[Patch]) -> Vec<&'static str> {
    patches.iter().map(|p| p.name).collect()
}

fn expected_names(n: &Nozzle) -> Vec<&'static str> {
    let mut out = vec!["neck"];
    if n.flange == FlangeType::SlipOn {
        out.push("hub end");
    }
    out.extend(["hub", "flange back", "flange rim"]);
    if n.facing != Facing::FlatFace {
        out.extend(["flange face", "raised face rim"]);
    }
    out.push("gasket face");
    out
}

/// Normals point away from the axis on cylinders and cones, along the plane's
/// outward normal on faces: +Z on the front faces, −Z on the backs.
fn assert_outward_normals(patches: &[Patch]) {
    for p in patches {
        for (u, v) in grid(&p.surface, 21) {
            let x = p.surface.point(u, v);
            let n = p.surface.normal(u, v);
            assert!((n.length() - 1.0).abs() < 1e-9, "{}: normal {n}", p.name);
            match p.analytic {
                Analytic::Cylinder { .. } => {
                    let radial = DVec3::new(x.x, x.y, 0.0).normalize();
                    assert!(n.dot(radial) > 1.0 - 1e-9, "{}: {n} at {x}", p.name);
                }
                Analytic::Cone { .. } => {
                    let radial = DVec3::new(x.x, x.y, 0.0).normalize();
                    assert!(n.dot(radial) > 0.1 && n.z < 0.0, "{}: {n} at {x}", p.name);
                }
                Analytic::Plane { normal, .. } => {
                    let expected = match p.name {
                        "flange back" | "hub end" => DVec3::NEG_Z,
                        "flange face" | "gasket face" => DVec3::Z,
                        other => panic!("unexpected planar patch {other}"),
                    };
                    assert_eq!(normal, expected, "{}", p.name);
                    assert!(n.dot(expected) > 1.0 - 1e-9, "{}: {n} at {x}", p.name);
                }
                other => panic!("{}: unexpected analytic {other:?}", p.name),
            }
        }
    }
}

#[test]
fn every_listed_nozzle_is_exact_and_outward() {
    for n in all_listed() {
        let tol = 1e-9 * flange_od(&n);
        let patches = n.patches().unwrap();
        assert_eq!(names(&patches), expected_names(&n), "{n:?}");
        assert_on_analytic(&patches, tol);
        for pair in patches.windows(2) {
            assert_joint(&pair[0], &pair[1], tol, false, 0.0);
        }
        assert_outward_normals(&patches);
    }
}

#[test]
fn gasket_face_is_at_the_projection_and_neck_on_the_pipe_od() {
    for n in all_listed() {
        let tol = 1e-9 * flange_od(&n);
        let patches = n.patches().unwrap();
        let face = patches.last().unwrap();
        assert_eq!(face.name, "gasket face");
        assert_eq!(
            face.analytic,
            Analytic::Plane {
                point: DVec3::new(0.0, 0.0, n.projection),
                normal: DVec3::Z
            }
        );
        for c in face.surface.control_points() {
            assert!((c.z - n.projection).abs() <= f64::EPSILON * n.projection);
        }
        for (u, v) in grid(&face.surface, GRID) {
            assert!((face.surface.point(u, v).z - n.projection).abs() <= tol);
        }

        let od = pipe(n.nps).outside_diameter;
        assert_eq!(n.outside_diameter(), od);
        let neck = &patches[0];
        assert_eq!(neck.name, "neck");
        assert_eq!(
            neck.analytic,
            Analytic::Cylinder {
                point: DVec3::ZERO,
                axis: DVec3::Z,
                radius: od / 2.0
            }
        );
        let neck_length = n.neck_length().unwrap();
        assert!((neck_length - Nozzle::MIN_NECK_LENGTH - EXTRA_NECK).abs() < tol);
        for k in 0..=16 {
            let u = k as f64 / 16.0;
            let start = neck.surface.point(u, 0.0);
            let end = neck.surface.point(u, 1.0);
            assert!(start.z.abs() <= tol && (end.z - neck_length).abs() <= tol);
            assert!((start.truncate().length() - od / 2.0).abs() <= tol);
        }
        // The flange body spans Y (+ raised face) from its back to the face.
        let dims = flange(n.nps, n.class).unwrap();
        let y = match n.flange {
            FlangeType::SlipOn => dims.slip_on_length,
            FlangeType::WeldNeck | FlangeType::Blind => dims.weld_neck_length,
        };
        let rf = match n.facing {
            Facing::FlatFace => 0.0,
            Facing::RaisedFace | Facing::RingJoint => raised_face_height(n.class),
        };
        assert_eq!(n.flange_length(), Ok(y + rf));
    }
}

#[test]
fn gasket_face_stops_at_the_bore_or_closes_for_a_blind() {
    for nps in Nps::all() {
        for schedule in PipeSchedule::ALL {
            for flange_type in FLANGE_TYPES {
                let n = Nozzle {
                    schedule,
                    ..with_neck(
                        nozzle(nps, FlangeClass::C300, flange_type, Facing::RaisedFace),
                        0.0,
                    )
                };
                let wall = match pipe(nps).wall(schedule) {
                    Ok(wall) => wall,
                    Err(e) => {
                        assert_eq!(n.patches(), Err(PartError::Table(e)));
                        continue;
                    }
                };
                let patches = n.patches().unwrap();
                let face = &patches.last().unwrap().surface;
                let inner = match flange_type {
                    FlangeType::Blind => 0.0,
                    _ => pipe(nps).outside_diameter / 2.0 - wall,
                };
                let tol = 1e-9 * flange_od(&n);
                for k in 0..=16 {
                    let p = face.point(k as f64 / 16.0, 1.0);
                    assert!((p.truncate().length() - inner).abs() <= tol, "{n:?}");
                }
            }
        }
    }
}

#[test]
fn well_known_flange_lengths() {
    let nps = Nps::try_new(4.0).unwrap();
    let wn = nozzle(
        nps,
        FlangeClass::C150,
        FlangeType::WeldNeck,
        Facing::RaisedFace,
    );
    assert_eq!(wn.flange_length(), Ok(75.0 + 2.0));
    let so = nozzle(
        nps,
        FlangeClass::C600,
        FlangeType::SlipOn,
        Facing::RingJoint,
    );
    assert_eq!(so.flange_length(), Ok(54.0 + 7.0));
    let ff = nozzle(nps, FlangeClass::C300, FlangeType::Blind, Facing::FlatFace);
    assert_eq!(ff.flange_length(), Ok(84.0));
    let n = Nozzle {
        projection: 300.0,
        ..wn
    };
    assert_eq!(n.neck_length(), Ok(223.0));
}

fn projection_error(result: Result<Vec<Patch>, PartError>) -> String {
    match result {
        Err(PartError::InvalidParameter {
            part, field, rule, ..
        }) => {
            assert_eq!((part, field), ("nozzle", "projection"));
            rule
        }
        other => panic!("expected a projection error, got {other:?}"),
    }
}

#[test]
fn bad_projections_are_typed_errors() {
    let nps = Nps::try_new(2.0).unwrap();
    let base = nozzle(
        nps,
        FlangeClass::C600,
        FlangeType::WeldNeck,
        Facing::RaisedFace,
    );
    for bad in [-1.0, 0.0, -0.0, f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
        let n = Nozzle {
            projection: bad,
            ..base
        };
        projection_error(n.patches());
        assert!(n.validate().is_err());
    }
    // Exactly the minimum is fine; a hair less is too short, and the rule says why.
    let shortest = with_neck(base, 0.0);
    assert!(shortest.patches().is_ok());
    let short = Nozzle {
        projection: shortest.projection - 1e-6,
        ..base
    };
    let rule = projection_error(short.patches());
    assert!(rule.contains("flange length (80 mm)") && rule.contains("minimum neck (50 mm)"));
}

#[test]
fn unlisted_sizes_schedules_and_classes_are_table_errors() {
    assert!(matches!(
        Nps::try_new(7.0).map_err(PartError::from),
        Err(PartError::Table(TableError::UnknownNps { .. }))
    ));
    let nps = Nps::try_new(3.5).unwrap();
    let n = with_neck(
        nozzle(nps, FlangeClass::C600, FlangeType::SlipOn, Facing::FlatFace),
        0.0,
    );
    let n = Nozzle {
        schedule: PipeSchedule::S160,
        ..n
    };
    assert!(matches!(
        n.patches(),
        Err(PartError::Table(TableError::ScheduleNotListed { .. }))
    ));
    let n = Nozzle {
        class: FlangeClass::C900,
        ..n
    };
    assert!(matches!(
        n.patches(),
        Err(PartError::Table(TableError::FlangeNotListed { .. }))
    ));
}

/// A size in inches: a table size, a near miss or junk.
fn any_size() -> impl Strategy<Value = f64> {
    prop_oneof![
        prop::sample::select(Nps::ALL.map(Nps::inches).to_vec()),
        Just(7.0),
        Just(3.25),
        any_number_up_to(2000.0, 360.0),
    ]
}

fn build(
    inches: f64,
    schedule: PipeSchedule,
    class: FlangeClass,
    flange: FlangeType,
    facing: Facing,
    projection: f64,
) -> Result<(Nozzle, Vec<Patch>), PartError> {
    let n = Nozzle {
        nps: Nps::try_new(inches)?,
        schedule,
        class,
        flange,
        facing,
        projection,
    };
    Ok((n, n.patches()?))
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(512))]

    #[test]
    fn any_input_gives_geometry_or_a_typed_error(
        inches in any_size(),
        schedule in prop::sample::select(PipeSchedule::ALL.to_vec()),
        class in prop::sample::select(FlangeClass::ALL.to_vec()),
        flange in prop::sample::select(FLANGE_TYPES.to_vec()),
        facing in prop::sample::select(FACINGS.to_vec()),
        projection in any_number_up_to(2000.0, 360.0),
    ) {
        match build(inches, schedule, class, flange, facing, projection) {
            Ok((n, patches)) => {
                prop_assert!(n.neck_length()? >= Nozzle::MIN_NECK_LENGTH - 1e-12 * projection);
                for p in &patches {
                    prop_assert!(p
                        .surface
                        .homogeneous_points()
                        .iter()
                        .all(|q| q.is_finite() && q.w > 0.0));
                }
                let face = &patches[patches.len() - 1];
                prop_assert_eq!(face.name, "gasket face");
                let z = face.surface.point(0.3, 0.6).z;
                prop_assert!((z - projection).abs() <= 1e-12 * projection);
            }
            Err(PartError::InvalidParameter { part, field, rule, .. }) => {
                prop_assert_eq!((part, field), ("nozzle", "projection"));
                prop_assert!(!rule.is_empty());
            }
            Err(PartError::Table(_)) => {}
            Err(other) => prop_assert!(false, "unexpected error {other}"),
        }
    }
}
