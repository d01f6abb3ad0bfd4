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

/// Table 5.1a against ITSdesign's published question (itsdesign.blogspot.com,
/// 10 Dec 2012, "Annular Ring Thickness Calculations"): a 45 mm first course,
/// product stress 220 MPa, hydrotest stress 240 MPa, CA 1 mm. The fifth row
/// gives 16 mm at ≤ 220 MPa and 19 mm at ≤ 250 MPa; Note b takes the greater
/// stress (240 → the 250 column, 19 mm) and 5.5.3 adds the CA: 19 + 1 = 20 mm
/// ("you will always be using" the test column plus CA, their reply).
/// Width, hand calculation with H = 20 m, G = 1:
/// L = 215 · 20 / √20 = 4300 / 4.472 136 = 961.51 mm.
#[test]
fn annular_plate_thickness_reproduces_itsdesign_example() {
    use vesselcad::calc::annular::{FirstCourse, annular, table_thickness};
    assert_eq!(table_thickness(45.0, 220.0).unwrap(), 16.0);
    assert_eq!(table_thickness(45.0, 240.0).unwrap(), 19.0);
    // The same through 5.5.3: t_d = 45 with Sd = 220 gives (45 − 1)/(45 − 1)·220
    // = 220 MPa; t_t = 45 with St = 240 gives 240 MPa.
    let course = FirstCourse {
        thickness: 45.0,
        design: 45.0,
        test: 45.0,
        corrosion_allowance: 1.0,
        design_stress: 220.0,
        test_stress: 240.0,
        level: 20.0,
        gravity: 1.0,
    };
    let a = annular(&course, Some("IV")).unwrap();
    close(a.product_stress, 220.0, 1e-9);
    close(a.test_stress, 240.0, 1e-9);
    assert_eq!((a.table_thickness, a.thickness), (19.0, 20.0));
    close(a.width_formula, 961.51, 0.01);
    close(a.width, 961.51, 0.01);
    // 5.5.1: Group IV above 160 and 171 MPa needs annular plates.
    assert_eq!(a.required, Some(true), "{}", a.reason);
}

/// Table 5.1a Note b's stresses on JStephen's published example (eng-tips
/// thread 457258, 2019): t = 1.00 in, CA = 0.06 in, t_d = 0.95 in, t_t = 0.82 in:
/// product stress = (0.95 − 0.06)/0.94 · Sd = 0.946 809 · Sd; hydrostatic
/// stress = 0.82/1.00 · St. Dimensionless, so taken in mm with Sd = St = 100.
#[test]
fn first_course_stresses_follow_table_5_1a_note_b() {
    use vesselcad::calc::annular::{FirstCourse, course_stresses};
    let c = FirstCourse {
        thickness: 1.00,
        design: 0.95,
        test: 0.82,
        corrosion_allowance: 0.06,
        design_stress: 100.0,
        test_stress: 100.0,
        level: 10.0,
        gravity: 1.0,
    };
    let (p, t) = course_stresses(&c).unwrap();
    close(p, 94.680_85, 1e-4);
    close(t, 82.0, 1e-9);
}

/// 5.5.1's cases and the table's reach, hand figures: a 19 mm course at
/// exactly 190 MPa is row 1, column 1 (6 mm); 19.01 mm at 190.01 MPa row 2,
/// column 2 (7 mm); 600 mm governs when L is smaller.
#[test]
fn annular_plates_required_and_out_of_scope() {
    use vesselcad::calc::annular::{FirstCourse, annular, table_thickness};
    assert_eq!(table_thickness(19.0, 190.0).unwrap(), 6.0);
    assert_eq!(table_thickness(19.01, 190.01).unwrap(), 7.0);
    assert_eq!(table_thickness(33.0, 200.0).unwrap(), 11.0);
    let e = table_thickness(46.0, 200.0).unwrap_err().to_string();
    assert!(e.contains("5.5.3") && e.contains("46"), "{e}");
    let e = table_thickness(20.0, 251.0).unwrap_err().to_string();
    assert!(e.contains("251.0"), "{e}");
    // A 20 mm course, t_d = 18 (CA 2: (16/18)·173 = 153.78 MPa ≤ 160) and
    // t_t = 19 (19/20 · 195 = 185.25 MPa): lap-welded bottom permitted in Group IV.
    let c = FirstCourse {
        thickness: 20.0,
        design: 18.0,
        test: 19.0,
        corrosion_allowance: 2.0,
        design_stress: 173.0,
        test_stress: 195.0,
        level: 15.0,
        gravity: 0.9,
    };
    let a = annular(&c, Some("IV")).unwrap();
    close(a.product_stress, 153.777_78, 1e-4);
    close(a.test_stress, 185.25, 1e-9);
    assert_eq!(a.required, Some(false), "{}", a.reason);
    // Row 19 < t ≤ 25, column ≤ 190: 6 mm + CA 2 = 8 mm; L = 1720/3.674 235 =
    // 468.12 mm < 600 mm.
    assert_eq!(a.thickness, 8.0);
    close(a.width_formula, 468.12, 0.01);
    assert_eq!(a.width, 600.0);
    // t_d = 20 (product 173 MPa) too: both limits exceeded, required.
    let hot = FirstCourse { design: 20.0, ..c };
    assert_eq!(annular(&hot, Some("V")).unwrap().required, Some(true));
    assert_eq!(annular(&hot, Some("III")).unwrap().required, Some(false));
    assert_eq!(annular(&hot, None).unwrap().required, None);
    // H·G above 23 m is outside the table (5.5.3).
    let tall = FirstCourse {
        level: 24.0,
        gravity: 1.0,
        ..c
    };
    let e = annular(&tall, Some("IV")).unwrap_err().to_string();
    assert!(e.contains("5.5.3") && e.contains("24.00"), "{e}");
    let bad = FirstCourse {
        thickness: -1.0,
        ..c
    };
    let e = annular(&bad, Some("IV")).unwrap_err().to_string();
    assert!(e.contains("thickness") && e.contains("-1"), "{e}");
}

/// The example tank TK-301 (A283-C, Group I; first course 10 mm, CA 1.5,
/// t_d 3.986 23, t_t 2.211 78, Sd 137, St 154, H 9 m, G 1), hand calculation:
///   product stress = (3.986 23 − 1.5)/(10 − 1.5) · 137 = 40.072 MPa
///   test stress = 2.211 78/10 · 154 = 34.061 MPa
///   Table 5.1a row t ≤ 19, column ≤ 190: 6 mm; + CA: 7.5 mm
///   L = 215 · 7.5 / √9 = 537.5 mm → 600 mm; Group I: not required.
/// Live and pure agree (the tank test above compares whole calculations), and
/// the report shows the table.
#[test]
fn the_example_tank_reports_its_annular_plates() {
    use vesselcad::calc::html::{ReportVessel, html};
    assert_eq!(
        MaterialTable::builtin()
            .get("SA-516-70")
            .unwrap()
            .api650_group
            .as_ref()
            .map(|g| g.value.as_str()),
        Some("IV")
    );
    let d = example("storage-tank");
    let resolved = design::resolve(&d).unwrap();
    let c = calculate(&d.vessels[0], &resolved[0], &MaterialTable::builtin());
    let a = c.vessel.annular.as_ref().unwrap().as_ref().unwrap();
    close(a.product_stress, 40.0722, 1e-3);
    close(a.test_stress, 34.0614, 1e-3);
    assert_eq!((a.table_thickness, a.thickness), (6.0, 7.5));
    close(a.width_formula, 537.5, 1e-3);
    assert_eq!(a.width, 600.0);
    assert_eq!(a.required, Some(false), "{}", a.reason);
    assert!(a.reason.contains("Group I"), "{}", a.reason);
    let page = html(
        "storage-tank",
        &[ReportVessel {
            design: &d.vessels[0],
            calculation: &c,
            weights: Err("not needed".into()),
        }],
    );
    assert!(page.contains("Annular bottom plates (API 650 5.5)"));
    assert!(page.contains("215·t_b/(H·G)^0.5"));
    let json = serde_json::to_value(&c.vessel).unwrap();
    assert_eq!(json["annular"]["Ok"]["thickness"], 7.5);
    // A pressure vessel has no annular figures.
    let drum = example("horizontal-drum");
    let r = design::resolve(&drum).unwrap();
    let c = calculate(&drum.vessels[0], &r[0], &MaterialTable::builtin());
    assert!(c.vessel.annular.is_none());
}
