//! Every part builder answers any numbers — negative, zero, NaN, infinite, huge,
//! tiny, impossible combinations — with either valid finite geometry or a
//! `PartError::InvalidParameter` naming the field; it never panics.

mod common;

use common::numbers::any_number_up_to;
use proptest::prelude::*;
use vesselcad::parts::heads::{Head, HeadKind};
use vesselcad::parts::{PartError, Patch, Reducer, ReducerAlignment, Shell};

/// Valid geometry (all control points finite) or a parameter error.
fn check(result: Result<Vec<Patch>, PartError>) -> Result<(), TestCaseError> {
    match result {
        Ok(patches) => {
            prop_assert!(!patches.is_empty());
            for p in &patches {
                prop_assert!(
                    p.surface
                        .homogeneous_points()
                        .iter()
                        .all(|q| q.is_finite() && q.w > 0.0)
                );
            }
        }
        Err(PartError::InvalidParameter { field, rule, .. }) => {
            prop_assert!(!field.is_empty() && !rule.is_empty());
        }
        Err(other) => prop_assert!(false, "not a parameter error: {other}"),
    }
    Ok(())
}

fn head_kind() -> impl Strategy<Value = HeadKind> {
    prop_oneof![
        Just(HeadKind::Hemispherical),
        any_number_up_to(5000.0, 90.0).prop_map(|ratio| HeadKind::Ellipsoidal { ratio }),
        (
            any_number_up_to(5000.0, 90.0),
            any_number_up_to(5000.0, 90.0)
        )
            .prop_map(|(crown_radius, knuckle_radius)| {
                HeadKind::Torispherical {
                    crown_radius,
                    knuckle_radius,
                }
            }),
        (
            any_number_up_to(5000.0, 90.0),
            any_number_up_to(5000.0, 90.0)
        )
            .prop_map(|(half_angle, knuckle_radius)| {
                HeadKind::Toriconical {
                    half_angle,
                    knuckle_radius,
                }
            }),
        (
            any_number_up_to(5000.0, 90.0),
            any_number_up_to(5000.0, 90.0)
        )
            .prop_map(|(half_angle, small_diameter)| HeadKind::Conical {
                half_angle,
                small_diameter
            }),
        any_number_up_to(5000.0, 90.0).prop_map(|knuckle_radius| HeadKind::Flat { knuckle_radius }),
    ]
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 2000, failure_persistence: None, ..ProptestConfig::default() })]

    #[test]
    fn heads_never_panic(d in any_number_up_to(5000.0, 90.0), sf in any_number_up_to(5000.0, 90.0), kind in head_kind()) {
        let head = Head { outside_diameter: d, straight_flange: sf, kind };
        check(head.patches())?;
        // Depth is finite whenever the head is valid.
        if let Ok(depth) = head.depth() {
            prop_assert!(depth.is_finite() && depth >= 0.0);
        }
    }

    #[test]
    fn shells_never_panic(d in any_number_up_to(5000.0, 90.0), l in any_number_up_to(5000.0, 90.0)) {
        check(Shell { outside_diameter: d, length: l }.patches())?;
    }

    #[test]
    fn reducers_never_panic(a in any_number_up_to(5000.0, 90.0), b in any_number_up_to(5000.0, 90.0), l in any_number_up_to(5000.0, 90.0), side in any_number_up_to(5000.0, 90.0), eccentric in any::<bool>()) {
        let alignment = if eccentric { ReducerAlignment::Eccentric { flat_side: side } } else { ReducerAlignment::Concentric };
        check(Reducer { large_diameter: a, small_diameter: b, length: l, alignment }.patches())?;
    }
}

#[test]
fn impossible_heads_name_the_rule() {
    let err = Head::new(
        2000.0,
        HeadKind::Torispherical {
            crown_radius: 100.0,
            knuckle_radius: 150.0,
        },
    )
    .validate()
    .unwrap_err();
    assert!(err.to_string().contains("knuckle_radius"), "{err}");
    assert!(err.to_string().contains("crown radius"), "{err}");
    let err = Head::new(
        2000.0,
        HeadKind::Conical {
            half_angle: 90.0,
            small_diameter: 0.0,
        },
    )
    .validate()
    .unwrap_err();
    assert!(err.to_string().contains("half_angle = 90"), "{err}");
    let err = Head::new(f64::NAN, HeadKind::Hemispherical)
        .validate()
        .unwrap_err();
    assert!(err.to_string().contains("outside_diameter = NaN"), "{err}");
    let err = Head::new(
        2000.0,
        HeadKind::Torispherical {
            crown_radius: 900.0,
            knuckle_radius: 100.0,
        },
    )
    .validate()
    .unwrap_err();
    assert!(err.to_string().contains("crown_radius = 900"), "{err}");
}
