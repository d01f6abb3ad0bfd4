//! Supports and the boot answer bad numbers — negative, zero, NaN, infinite, huge,
//! out-of-range angles and counts, impossible combinations — with
//! `PartError::InvalidParameter` naming the field, and never panic.

mod common;

use common::numbers::any_number_up_to;
use common::supports::*;
use proptest::prelude::*;
use vesselcad::parts::heads::HeadKind;
use vesselcad::parts::{Boot, Legs, Lugs, MAX_LEGS, MAX_LUGS, PartError, Patch, Saddle, Skirt};

/// Values no dimension accepts.
const BAD: [f64; 7] = [
    -1.0,
    0.0,
    -0.0,
    f64::NAN,
    f64::INFINITY,
    f64::NEG_INFINITY,
    1e300,
];

/// Angles no plan angle accepts.
const BAD_PLAN_ANGLES: [f64; 6] = [
    f64::NAN,
    f64::INFINITY,
    f64::NEG_INFINITY,
    360.5,
    -400.0,
    1e300,
];

/// Asserts `result` is an `InvalidParameter` naming `field`.
fn assert_rejects(result: Result<Vec<Patch>, PartError>, field: &str, value: impl std::fmt::Debug) {
    match result {
        Err(PartError::InvalidParameter { field: f, rule, .. }) => {
            assert_eq!(f, field, "{field} = {value:?} was blamed on {f}: {rule}");
            assert!(!rule.is_empty());
        }
        other => panic!("{field} = {value:?}: expected InvalidParameter, got {other:?}"),
    }
}

/// For each field: a setter and the values it must reject (on top of [`BAD`] when
/// `dimension`).
type Case<T> = (&'static str, fn(&mut T, f64), bool, &'static [f64]);

fn assert_fields<T: Copy>(
    valid: T,
    build: fn(&T) -> Result<Vec<Patch>, PartError>,
    cases: &[Case<T>],
) {
    assert!(build(&valid).is_ok());
    for &(field, set, dimension, extra) in cases {
        let base: &[f64] = if dimension { &BAD } else { &[] };
        for &value in base.iter().chain(extra) {
            let mut part = valid;
            set(&mut part, value);
            assert_rejects(build(&part), field, value);
        }
    }
}

#[test]
fn skirt_rejects_bad_numbers() {
    let angles = &[
        -1.0,
        -1e-9,
        45.0001,
        90.0,
        f64::NAN,
        f64::INFINITY,
        f64::NEG_INFINITY,
    ];
    let ring = &[-1.0, f64::NAN, f64::INFINITY, f64::NEG_INFINITY, 1e300];
    assert_fields(
        skirt_with(15.0, 150.0),
        Skirt::patches,
        &[
            ("top_diameter", |s, v| s.top_diameter = v, true, &[]),
            ("height", |s, v| s.height = v, true, &[]),
            ("flare_angle", |s, v| s.flare_angle = v, false, angles),
            ("thickness", |s, v| s.thickness = v, true, &[1200.0, 5000.0]),
            ("base_ring_width", |s, v| s.base_ring_width = v, false, ring),
        ],
    );
}

#[test]
fn saddle_rejects_bad_numbers() {
    let angles = &[119.9, 150.1, 0.0, 180.0, -120.0, f64::NAN, f64::INFINITY];
    assert_fields(
        saddle(),
        Saddle::patches,
        &[
            ("shell_diameter", |s, v| s.shell_diameter = v, true, &[]),
            ("contact_angle", |s, v| s.contact_angle = v, false, angles),
            ("width", |s, v| s.width = v, true, &[]),
            ("height", |s, v| s.height = v, true, &[1200.0, 800.0]),
            (
                "web_thickness",
                |s, v| s.web_thickness = v,
                true,
                &[250.0, 300.0],
            ),
            ("base_length", |s, v| s.base_length = v, true, &[2000.0]),
            ("base_width", |s, v| s.base_width = v, true, &[]),
            (
                "base_thickness",
                |s, v| s.base_thickness = v,
                true,
                &[400.0],
            ),
        ],
    );
}

#[test]
fn legs_reject_bad_numbers() {
    assert_fields(
        legs(),
        Legs::patches,
        &[
            ("pipe_diameter", |s, v| s.pipe_diameter = v, true, &[]),
            ("length", |s, v| s.length = v, true, &[]),
            ("shell_diameter", |s, v| s.shell_diameter = v, true, &[]),
            (
                "first_angle",
                |s, v| s.first_angle = v,
                false,
                &BAD_PLAN_ANGLES,
            ),
        ],
    );
    // Too few, too many, or too many for the base plates to fit side by side.
    for count in [0, 1, 2, MAX_LEGS + 1, u32::MAX, 32] {
        assert_rejects(Legs { count, ..legs() }.patches(), "count", count);
    }
    let fat = Legs {
        pipe_diameter: 1500.0,
        ..legs()
    };
    assert_rejects(fat.patches(), "count", 1500.0);
}

#[test]
fn lugs_reject_bad_numbers() {
    let wide = OD * std::f64::consts::FRAC_1_SQRT_2;
    assert_fields(
        lugs(),
        Lugs::patches,
        &[
            ("shell_diameter", |s, v| s.shell_diameter = v, true, &[]),
            ("height", |s, v| s.height = v, true, &[]),
            ("projection", |s, v| s.projection = v, true, &[]),
            ("width", |s, v| s.width = v, true, &[3000.0]),
            (
                "first_angle",
                |s, v| s.first_angle = v,
                false,
                &BAD_PLAN_ANGLES,
            ),
        ],
    );
    // Neighbouring lugs would touch at width = D · sin(180° / count).
    assert_rejects(
        Lugs {
            width: wide,
            ..lugs()
        }
        .patches(),
        "width",
        wide,
    );
    assert!(
        Lugs {
            width: 0.999 * wide,
            ..lugs()
        }
        .patches()
        .is_ok()
    );
    for count in [0, 1, MAX_LUGS + 1, u32::MAX] {
        assert_rejects(Lugs { count, ..lugs() }.patches(), "count", count);
    }
}

#[test]
fn boot_rejects_bad_numbers() {
    assert_fields(
        Boot::new(600.0, 900.0, OD),
        Boot::patches,
        &[
            ("diameter", |s, v| s.diameter = v, true, &[OD, 3000.0]),
            ("length", |s, v| s.length = v, true, &[]),
            ("host_diameter", |s, v| s.host_diameter = v, true, &[]),
        ],
    );
    for ratio in [f64::NAN, -2.0, 0.0] {
        let boot = Boot::new(600.0, 900.0, OD).with_head(HeadKind::Ellipsoidal { ratio });
        assert_rejects(boot.patches(), "ratio", ratio);
    }
}

fn any_count() -> impl Strategy<Value = u32> {
    prop_oneof![0..40u32, any::<u32>()]
}

/// Finite geometry, or an `InvalidParameter` naming one of `fields`.
fn check(result: Result<Vec<Patch>, PartError>, fields: &[&str]) -> Result<(), TestCaseError> {
    match result {
        Ok(patches) => {
            prop_assert!(!patches.is_empty());
            for p in &patches {
                let points = p.surface.homogeneous_points();
                prop_assert!(points.iter().all(|q| q.is_finite() && q.w > 0.0));
            }
        }
        Err(PartError::InvalidParameter { field, rule, .. }) => {
            prop_assert!(fields.contains(&field), "unexpected field {field}: {rule}");
        }
        Err(other) => prop_assert!(false, "not a parameter error: {other}"),
    }
    Ok(())
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 1000, failure_persistence: None, ..ProptestConfig::default() })]

    #[test]
    fn skirts_never_panic(d in any_number_up_to(5000.0, 180.0), h in any_number_up_to(5000.0, 180.0), a in any_number_up_to(5000.0, 180.0), t in any_number_up_to(5000.0, 180.0), w in any_number_up_to(5000.0, 180.0)) {
        let s = Skirt { top_diameter: d, height: h, flare_angle: a, thickness: t, base_ring_width: w };
        check(s.patches(), &["top_diameter", "height", "flare_angle", "thickness", "base_ring_width"])?;
    }

    #[test]
    fn saddles_never_panic(v in proptest::collection::vec(any_number_up_to(5000.0, 180.0), 8)) {
        let s = Saddle {
            shell_diameter: v[0], contact_angle: v[1], width: v[2], height: v[3],
            web_thickness: v[4], base_length: v[5], base_width: v[6], base_thickness: v[7],
        };
        check(s.patches(), &["shell_diameter", "contact_angle", "width", "height", "web_thickness",
            "base_length", "base_width", "base_thickness"])?;
    }

    #[test]
    fn legs_never_panic(count in any_count(), p in any_number_up_to(5000.0, 180.0), l in any_number_up_to(5000.0, 180.0), d in any_number_up_to(5000.0, 180.0), a in any_number_up_to(5000.0, 180.0)) {
        let legs = Legs { count, pipe_diameter: p, length: l, shell_diameter: d, first_angle: a };
        check(legs.patches(), &["count", "pipe_diameter", "length", "shell_diameter", "first_angle"])?;
    }

    #[test]
    fn lugs_never_panic(count in any_count(), v in proptest::collection::vec(any_number_up_to(5000.0, 180.0), 5)) {
        let lugs = Lugs { count, shell_diameter: v[0], height: v[1], projection: v[2], width: v[3], first_angle: v[4] };
        check(lugs.patches(), &["count", "shell_diameter", "height", "projection", "width", "first_angle"])?;
    }

    #[test]
    fn boots_never_panic(d in any_number_up_to(5000.0, 180.0), l in any_number_up_to(5000.0, 180.0), host in any_number_up_to(5000.0, 180.0), ratio in any_number_up_to(5000.0, 180.0)) {
        let boot = Boot::new(d, l, host).with_head(HeadKind::Ellipsoidal { ratio });
        check(boot.patches(), &["diameter", "length", "host_diameter", "ratio", "outside_diameter", "depth"])?;
    }
}
