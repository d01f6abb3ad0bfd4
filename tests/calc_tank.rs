//! API 650 storage tanks (`vesselcad::calc::api650`): the allowable stresses by
//! 5.6.2.1/5.6.2.2 reproduce Table 5-2a, the one-foot method (5.6.3.2) against a
//! hand calculation written out below, the 5.6.1.1 minimum by diameter, the
//! method's scope, and the example tank calculated live in the model (a course
//! edit recalculates the tank and a thin course is a deficiency).

mod common;

use common::examples::example;
use vesselcad::calc::api650::{allowable_stresses, minimum_nominal, one_foot};
use vesselcad::calc::{MaterialTable, calculate};
use vesselcad::design::{self, PartDesign};
use vesselcad::mesh::TessellationOptions;
use vesselcad::model::{Edit, Model};

fn close(got: f64, want: f64, tol: f64) {
    assert!(
        (got - want).abs() <= tol,
        "got {got}, expected {want} ± {tol}"
    );
}

/// API 650 Table 5-2a (SI) lists, for plates of these specified minimums:
/// A283M C (Sy 205, Su 380) Sd 137, St 154; A36M (250, 400) Sd 160, St 171;
/// A516M Gr 485 (260, 485) Sd 173, St 195 — the 5.6.2 rule rounded to 1 MPa.
#[test]
fn allowable_stresses_reproduce_table_5_2a() {
    assert_eq!(allowable_stresses(205.0, 380.0), (137.0, 154.0));
    assert_eq!(allowable_stresses(250.0, 400.0), (160.0, 171.0));
    assert_eq!(allowable_stresses(260.0, 485.0), (173.0, 195.0));
}

#[test]
fn minimum_nominal_thickness_by_diameter() {
    assert_eq!(minimum_nominal(14.99), 5.0);
    assert_eq!(minimum_nominal(15.0), 6.0);
    assert_eq!(minimum_nominal(35.99), 6.0);
    assert_eq!(minimum_nominal(36.0), 8.0);
    assert_eq!(minimum_nominal(60.0), 8.0);
    assert_eq!(minimum_nominal(60.01), 10.0);
}

/// Hand calculation, 5.6.3.2 in SI: D = 30 m, H = 14.4 m (the bottom course of
/// a 14.4 m shell), G = 0.85, A36 (Sd 160, St 171), CA = 1.5 mm:
///   t_d = 4.9 · 30 · (14.4 − 0.3) · 0.85 / 160 + 1.5 = 2072.7 · 0.85 / 160 + 1.5
///       = 1761.795 / 160 + 1.5 = 11.011 22 + 1.5 = 12.511 22 mm
///   t_t = 4.9 · 30 · 14.1 / 171 = 2072.7 / 171 = 12.121 05 mm
///   5.6.1.1 minimum for 15 ≤ D < 36 m: 6 mm → t_d governs, 12.51 mm.
/// Second course (H = 12 m): 4.9·30·11.7 = 1719.9; t_d = 1719.9·0.85/160 + 1.5
///   = 1461.915/160 + 1.5 = 10.636 97, t_t = 1719.9/171 = 10.057 89.
/// Top course (H = 2.4 m): 4.9·30·2.1 = 308.7; t_d = 262.395/160 + 1.5 = 3.139 97,
///   t_t = 308.7/171 = 1.805 26; the minimum 6 mm governs.
#[test]
fn one_foot_method_hand_calculation() {
    let c = one_foot(30.0, 14.4, 0.85, 160.0, 171.0, 1.5).unwrap();
    close(c.design, 12.511_22, 1e-5);
    close(c.test, 12.121_05, 1e-5);
    assert_eq!(c.minimum, 6.0);
    close(c.required, 12.511_22, 1e-5);
    let c2 = one_foot(30.0, 12.0, 0.85, 160.0, 171.0, 1.5).unwrap();
    close(c2.design, 10.636_97, 1e-5);
    close(c2.test, 10.057_89, 1e-5);
    let top = one_foot(30.0, 2.4, 0.85, 160.0, 171.0, 1.5).unwrap();
    close(top.design, 3.139_97, 1e-5);
    close(top.test, 1.805_26, 1e-5);
    assert_eq!(top.required, 6.0);
    // Water in the test governs a light product: G = 0.5.
    let light = one_foot(30.0, 14.4, 0.5, 160.0, 171.0, 0.0).unwrap();
    assert_eq!(light.required, light.test);
}

#[test]
fn one_foot_method_scope_and_bad_inputs() {
    let e = one_foot(62.0, 10.0, 1.0, 160.0, 171.0, 0.0)
        .unwrap_err()
        .to_string();
    assert!(e.contains("5.6.3.1") && e.contains("61"), "{e}");
    let e = one_foot(30.0, 10.0, -1.0, 160.0, 171.0, 0.0)
        .unwrap_err()
        .to_string();
    assert!(e.contains("specific_gravity") && e.contains("-1"), "{e}");
}

/// The example tank TK-301: one 9 m course, OD 8 m, 10 mm, A283-C, CA 1.5 mm, no
/// operating data (water): D = 7.99 m, H = 9 m, G = 1:
///   t_d = 4.9 · 7.99 · 8.7 / 137 + 1.5 = 340.6137 / 137 + 1.5 = 3.986 23 mm
///   t_t = 340.6137 / 154 = 2.211 78 mm; minimum (D < 15 m) 5 mm governs.
#[test]
fn the_example_tank_is_calculated_live() {
    let mut m =
        Model::from_design(&example("storage-tank"), TessellationOptions::chord(5.0)).unwrap();
    let tag = m.design().vessels[0].tag.clone();
    let live = m.calculation(&tag).unwrap();
    let d = m.design();
    let pure = calculate(
        &d.vessels[0],
        &design::resolve(&d).unwrap()[0],
        &MaterialTable::builtin(),
    );
    assert_eq!(live, pure);
    let course = live.parts.iter().find(|p| p.id == "S1").unwrap();
    let input = |n: &str| course.inputs.iter().find(|i| i.name == n).unwrap().value;
    close(input("D"), 7.99, 1e-12);
    close(input("H"), 9.0, 1e-9);
    close(input("Sd"), 137.0, 0.0);
    close(input("t_d"), 3.986_23, 1e-5);
    close(input("t_t"), 2.211_78, 1e-5);
    close(course.required.value, 5.0, 0.0);
    assert_eq!(course.required.paragraph, "API 650 5.6.1.1");
    assert!(course.deficiency.is_none());
    assert!(live.vessel.deficiencies.is_empty(), "{:?}", live.vessel);

    // A 4 mm course is thinner than the 5 mm minimum: a deficiency, live.
    let mut thin = d.vessels[0].parts[1].clone();
    let PartDesign::Shell(s) = &mut thin else {
        panic!("S1 is a shell: {thin:?}")
    };
    s.thickness = Some(4.0);
    m.edit(Edit::SetPart {
        vessel: tag.clone(),
        part: thin,
    })
    .unwrap();
    let after = m.calculation(&tag).unwrap();
    let d2 = m.design();
    assert_eq!(
        after,
        calculate(
            &d2.vessels[0],
            &design::resolve(&d2).unwrap()[0],
            &MaterialTable::builtin()
        )
    );
    assert!(
        after
            .vessel
            .deficiencies
            .iter()
            .any(|d| d.contains("S1") && d.contains("API 650")),
        "{:?}",
        after.vessel.deficiencies
    );
}

/// Bottom and roof plates. Hand calculation: a self-supporting cone roof on an
/// 8 m tank at θ = 10° needs D/(4.8·sin θ) = 8/(4.8 · 0.173648) = 9.598 mm
/// (5.10.5.1, T = 2.2 kPa); at θ = 37°, 8/(4.8 · 0.601815) = 2.769 → the 5 mm
/// minimum; a 40 m tank at 9.5°: 40/(4.8 · 0.165048) = 50.49 → the 13 mm most.
/// A dome of rr = D = 8 m: 8/2.4 = 3.33 → 5 mm; of rr = 9.6 m on a 8 m tank
/// (1.2·D): 9.6/2.4 = 4 → 5 mm; on a 30 m tank rr = 30: 12.5 mm.
#[test]
fn bottom_and_roof_plates() {
    use vesselcad::calc::api650::{plate, self_supporting_cone, self_supporting_dome};
    use vesselcad::parts::heads::HeadKind;
    close(self_supporting_cone(8.0, 10.0).unwrap(), 9.598, 1e-3);
    close(self_supporting_cone(8.0, 37.0).unwrap(), 5.0, 1e-12);
    close(self_supporting_cone(40.0, 9.5).unwrap(), 13.0, 1e-12);
    assert!(self_supporting_cone(8.0, 5.0).is_err());
    close(self_supporting_dome(8.0, 8.0).unwrap(), 5.0, 1e-12);
    close(self_supporting_dome(30.0, 30.0).unwrap(), 12.5, 1e-12);
    assert!(self_supporting_dome(8.0, 10.0).is_err());
    // 5.4.1: bottom 6 mm + CA; a cone roof taken as supported: 5 mm, with the
    // self-supporting figure beside it.
    let flat = HeadKind::Flat {
        knuckle_radius: 0.0,
    };
    let b = plate(flat, 8000.0, true, 1.5).unwrap();
    assert_eq!((b.required, b.paragraph), (7.5, "API 650 5.4.1"));
    let cone = HeadKind::Conical {
        half_angle: 80.0,
        small_diameter: 0.0,
    };
    let r = plate(cone, 8000.0, false, 1.5).unwrap();
    assert_eq!((r.required, r.paragraph), (5.0, "API 650 5.10.2.2"));
    close(r.self_supporting.unwrap(), 9.598, 1e-3);

    // The example tank: bottom 8 ≥ 7.5 mm, roof 6 ≥ 5 mm; its roof nozzles are
    // said to be roof nozzles (not shell nozzles).
    let d = example("storage-tank");
    let resolved = design::resolve(&d).unwrap();
    let c = calculate(&d.vessels[0], &resolved[0], &MaterialTable::builtin());
    let part = |id: &str| c.parts.iter().find(|p| p.id == id).unwrap();
    assert_eq!(part("BTM").shape, "tank bottom plate");
    assert_eq!(part("ROOF").shape, "supported cone roof");
    assert!(
        c.vessel.deficiencies.is_empty(),
        "{:?}",
        c.vessel.deficiencies
    );
    for mark in ["N3", "M2"] {
        let line = c
            .vessel
            .problems
            .iter()
            .find(|p| p.starts_with(&format!("{mark}:")))
            .unwrap();
        assert!(line.contains("roof nozzles"), "{line}");
    }
    let n1 = c
        .vessel
        .problems
        .iter()
        .find(|p| p.starts_with("N1:"))
        .unwrap();
    assert!(n1.contains("shell nozzles"), "{n1}");
    // A 7 mm bottom is deficient by 5.4.1.
    let mut thin = d.clone();
    if let PartDesign::Head(h) = &mut thin.vessels[0].parts[0] {
        h.thickness = Some(7.0);
    }
    let resolved = design::resolve(&thin).unwrap();
    let c = calculate(&thin.vessels[0], &resolved[0], &MaterialTable::builtin());
    assert!(
        c.vessel
            .deficiencies
            .iter()
            .any(|s| s.starts_with("BTM: tank bottom plate 7 mm") && s.contains("5.4.1")),
        "{:?}",
        c.vessel.deficiencies
    );
}
