//! ASME VIII-1 internal-pressure formulas (`vesselcad::calc`): closed-form checks
//! at four decimals in inch units (the printed precision of the code's examples),
//! unit consistency between inch and SI inputs, the round trip
//! MAWP(t_required(P)) = P for every shape, scope limits and bad inputs.
//!
//! The reference figures are the formulas evaluated independently (by hand, in
//! Python) for P = 356 psi, S = 20 000 psi, E = 1, CA = 0.125 in: the conditions of
//! ASME PTB-4's VIII-1 examples as commonly quoted. PTB-4's printed results could
//! not be found in the sources available, so these are not its published numbers.

use proptest::prelude::*;
use vesselcad::calc::vessel::{
    PartPressure, hydrotest_pressure, minimum_thickness, static_head, vessel_mawp,
};
use vesselcad::calc::{CalcError, Shape, Strength, mawp, required_thickness};

const P: f64 = 356.0;
const INCH: Strength = Strength {
    stress: 20_000.0,
    joint_efficiency: 1.0,
    corrosion_allowance: 0.125,
};

fn t_req(shape: Shape) -> f64 {
    required_thickness(&shape, P, &INCH).unwrap().value
}

fn assert_4dp(got: f64, printed: f64) {
    assert!(
        (got - printed).abs() <= 0.5e-4,
        "got {got:.6}, expected {printed:.4}"
    );
}

#[test]
fn cylinder_ug27_circumferential_governs() {
    let shape = Shape::Cylinder {
        inside_radius: 45.0,
    };
    let f = required_thickness(&shape, P, &INCH).unwrap();
    assert_eq!(f.paragraph, "UG-27(c)(1)");
    assert_eq!(f.formula, "t = P·R / (S·E − 0.6·P)");
    assert_4dp(f.value, 0.9369);
    // MAWP of a 1.0 in wall: circumferential 383.35 psi < longitudinal 781.69 psi.
    let m = mawp(&shape, 1.0, &INCH).unwrap();
    assert_eq!(m.paragraph, "UG-27(c)(1)");
    assert!((m.value - 383.35).abs() < 0.005, "{}", m.value);
}

#[test]
fn heads_and_cone_closed_form() {
    assert_4dp(
        t_req(Shape::Sphere {
            inside_radius: 45.0,
        }),
        0.5273,
    );
    let two_to_one = Shape::Ellipsoidal {
        inside_diameter: 90.0,
        inside_depth: 22.5,
    };
    let f = required_thickness(&two_to_one, P, &INCH).unwrap();
    assert_eq!(f.paragraph, "UG-32(d)");
    assert_4dp(f.value, 0.9297);
    let flat_ellipse = Shape::Ellipsoidal {
        inside_diameter: 90.0,
        inside_depth: 18.0,
    };
    let f = required_thickness(&flat_ellipse, P, &INCH).unwrap();
    assert_eq!(f.paragraph, "Appendix 1-4(c)");
    assert_4dp(f.value, 1.2314);
    assert_4dp(
        t_req(Shape::Torispherical {
            crown_radius: 72.0,
            knuckle_radius: 4.375,
        }),
        1.2509,
    );
    assert_4dp(
        t_req(Shape::Cone {
            inside_diameter: 90.0,
            half_apex_angle: 30.0,
        }),
        1.0629,
    );
    let f = required_thickness(
        &Shape::Flat {
            diameter: 24.0,
            attachment_factor: 0.33,
        },
        P,
        &INCH,
    )
    .unwrap();
    assert_eq!(f.paragraph, "UG-34(c)(2)");
    assert_4dp(f.value, 1.9836);
}

#[test]
fn torispherical_at_16_2_3_is_ug32e() {
    // UG-32(e): t = 0.885·P·L / (S·E − 0.1·P) for r = 6% of L = D; Appendix 1-4(d)
    // gives M = 1.7706 there, so the two agree to 0.1%.
    let no_ca = Strength {
        corrosion_allowance: 0.0,
        ..INCH
    };
    let l = 96.0;
    let shape = Shape::Torispherical {
        crown_radius: l,
        knuckle_radius: l * 0.06,
    };
    let t = required_thickness(&shape, P, &no_ca).unwrap().value;
    let ug32e = 0.885 * P * l / (20_000.0 - 0.1 * P);
    assert!((t / ug32e - 1.0).abs() < 1e-3, "{t} vs {ug32e}");
}

#[test]
fn si_and_inch_inputs_agree() {
    const MPA_PER_PSI: f64 = 0.006_894_757;
    let si = Strength {
        stress: INCH.stress * MPA_PER_PSI,
        joint_efficiency: 0.85,
        corrosion_allowance: 0.125 * 25.4,
    };
    let inch = Strength {
        joint_efficiency: 0.85,
        ..INCH
    };
    for (shape_in, shape_mm) in [
        (
            Shape::Cylinder {
                inside_radius: 45.0,
            },
            Shape::Cylinder {
                inside_radius: 45.0 * 25.4,
            },
        ),
        (
            Shape::Torispherical {
                crown_radius: 72.0,
                knuckle_radius: 4.375,
            },
            Shape::Torispherical {
                crown_radius: 72.0 * 25.4,
                knuckle_radius: 4.375 * 25.4,
            },
        ),
        (
            Shape::Cone {
                inside_diameter: 90.0,
                half_apex_angle: 20.0,
            },
            Shape::Cone {
                inside_diameter: 90.0 * 25.4,
                half_apex_angle: 20.0,
            },
        ),
    ] {
        let t_in = required_thickness(&shape_in, P, &inch).unwrap().value;
        let t_mm = required_thickness(&shape_mm, P * MPA_PER_PSI, &si)
            .unwrap()
            .value;
        assert!((t_mm / 25.4 - t_in).abs() < 1e-9, "{shape_in:?}");
        let p_in = mawp(&shape_in, 1.5, &inch).unwrap().value;
        let p_mm = mawp(&shape_mm, 1.5 * 25.4, &si).unwrap().value;
        assert!((p_mm / MPA_PER_PSI / p_in - 1.0).abs() < 1e-12);
    }
}

fn shapes() -> impl Strategy<Value = Shape> {
    prop_oneof![
        (200.0..3000.0f64).prop_map(|r| Shape::Cylinder { inside_radius: r }),
        (200.0..3000.0f64).prop_map(|r| Shape::Sphere { inside_radius: r }),
        (400.0..6000.0f64, 1.0..3.0f64).prop_map(|(d, ratio)| Shape::Ellipsoidal {
            inside_diameter: d,
            inside_depth: d / (2.0 * ratio),
        }),
        (400.0..6000.0f64, 1.0..16.0f64).prop_map(|(l, ratio)| Shape::Torispherical {
            crown_radius: l,
            knuckle_radius: l / ratio,
        }),
        (400.0..6000.0f64, 1.0..30.0f64).prop_map(|(d, a)| Shape::Cone {
            inside_diameter: d,
            half_apex_angle: a,
        }),
        (100.0..1500.0f64, 0.1..0.33f64).prop_map(|(d, c)| Shape::Flat {
            diameter: d,
            attachment_factor: c,
        }),
    ]
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 2000, ..ProptestConfig::default() })]
    /// MAWP(t_required(P)) = P: the thickness and pressure forms are inverses.
    #[test]
    fn mawp_of_required_thickness_is_the_pressure(
        shape in shapes(),
        p in 0.05..3.0f64,
        s in 100.0..160.0f64,
        e in 0.6..1.0f64,
        ca in 0.0..6.0f64,
    ) {
        let strength = Strength { stress: s, joint_efficiency: e, corrosion_allowance: ca };
        let t = required_thickness(&shape, p, &strength).unwrap();
        let back = mawp(&shape, t.value, &strength).unwrap();
        prop_assert!((back.value / p - 1.0).abs() < 1e-12, "{:?}: {} -> {} -> {}", shape, p, t.value, back.value);
        prop_assert_eq!(back.paragraph, t.paragraph);
    }
}

#[test]
fn outside_the_paragraphs_scope_is_an_error() {
    let steep = Shape::Cone {
        inside_diameter: 1000.0,
        half_apex_angle: 45.0,
    };
    let e = required_thickness(&steep, 1.0, &INCH).unwrap_err();
    assert!(
        matches!(
            e,
            CalcError::OutOfScope {
                paragraph: "UG-32(g)",
                ..
            }
        ),
        "{e}"
    );
    assert!(e.to_string().contains("Appendix 1-5(g)"), "{e}");
    // P > 0.385·S·E: thick-wall cylinder, Appendix 1-2.
    let cyl = Shape::Cylinder {
        inside_radius: 500.0,
    };
    let e = required_thickness(&cyl, 8000.0, &INCH).unwrap_err();
    assert!(e.to_string().contains("0.385"), "{e}");
    let deep = Shape::Torispherical {
        crown_radius: 1000.0,
        knuckle_radius: 20.0,
    };
    let e = mawp(&deep, 10.0, &INCH).unwrap_err();
    assert!(e.to_string().contains("outside 1 to 16⅔"), "{e}");
}

#[test]
fn bad_inputs_name_field_and_value() {
    let cyl = Shape::Cylinder {
        inside_radius: f64::NAN,
    };
    let e = required_thickness(&cyl, 1.0, &INCH).unwrap_err();
    assert!(
        matches!(&e, CalcError::Input { entity, field, .. } if entity == "cylinder" && field == "inside_radius"),
        "{e}"
    );
    let cyl = Shape::Cylinder {
        inside_radius: 500.0,
    };
    let over = Strength {
        joint_efficiency: 1.2,
        ..INCH
    };
    let e = required_thickness(&cyl, 1.0, &over).unwrap_err();
    assert!(e.to_string().contains("joint_efficiency = 1.2"), "{e}");
    let e = mawp(&cyl, 0.1, &INCH).unwrap_err();
    assert!(e.to_string().contains("corrosion allowance"), "{e}");
    let e = required_thickness(&cyl, -1.0, &INCH).unwrap_err();
    assert!(e.to_string().contains("pressure = -1"), "{e}");
}

#[test]
fn vessel_mawp_hydrotest_and_minimum() {
    // 1000 kg/m³ water over 10 m: 0.0980665 MPa.
    let head = static_head(1000.0, 10_000.0).unwrap();
    assert!((head - 0.098_066_5).abs() < 1e-12);
    let parts = [
        PartPressure {
            id: "V-1/top".into(),
            mawp: 1.20,
            static_head: 0.0,
        },
        PartPressure {
            id: "V-1/bottom".into(),
            mawp: 1.25,
            static_head: head,
        },
    ];
    let (m, governing) = vessel_mawp(&parts).unwrap();
    assert_eq!(governing, "V-1/bottom");
    assert!((m - (1.25 - head)).abs() < 1e-12);
    let test = hydrotest_pressure(1.0, &[(138.5, 138.5), (136.6, 120.0)]).unwrap();
    assert_eq!(test.paragraph, "UG-99(b)");
    assert!((test.value - 1.3).abs() < 1e-12, "lowest ratio is 1.0");
    let test = hydrotest_pressure(1.0, &[(138.5, 120.0)]).unwrap();
    assert!((test.value - 1.3 * 138.5 / 120.0).abs() < 1e-12);
    let min = minimum_thickness(3.0).unwrap();
    assert_eq!((min.value, min.paragraph), (4.5, "UG-16(b)"));
    assert!(vessel_mawp(&[]).is_err());
}
