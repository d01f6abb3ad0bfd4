//! UCS-66 minimum design metal temperature (`vesselcad::calc::mdmt`): the curve
//! letters of the built-in materials, the flat segment of Fig. UCS-66 and
//! UCS-66(d), the refusal above 10 mm (Table UCS-66 is not shipped), and the
//! figures through a whole design.
//!
//! Hand calculation, °C = (°F − 32)/1.8 on the values of Fig. UCS-66 (ASME BPVC
//! VIII-1 2019) at 0.394 in and below: curve A 18 °F → −7.78 °C; curve B −20 °F
//! → −28.89 °C; curves C and D −55 °F → −48.33 °C; UCS-66(d), 0.10 in (2.5 mm)
//! and thinner, −55 °F → −48.33 °C whatever the curve.

mod common;

use vesselcad::calc::mdmt::{mdmt, vessel_mdmt};
use vesselcad::calc::{MaterialTable, calculate};
use vesselcad::design::PartDesign;

fn close(got: Option<f64>, want: f64) {
    let got = got.expect("a temperature");
    assert!((got - want).abs() < 0.005, "got {got}, want {want}");
}

#[test]
fn builtin_materials_carry_their_fig_ucs66_curve() {
    let t = MaterialTable::builtin();
    let curve = |n: &str| {
        t.get(n)
            .unwrap()
            .ucs66_curve
            .as_ref()
            .map(|c| c.value.clone())
    };
    assert_eq!(curve("SA-516-70").as_deref(), Some("B"));
    assert_eq!(curve("SA-516-60").as_deref(), Some("C"));
    assert_eq!(curve("SA-285-C").as_deref(), Some("A"));
    assert_eq!(curve("SA-106-B").as_deref(), Some("B"));
    assert_eq!(curve("SA-105").as_deref(), Some("B"));
    // Austenitic stainless is Part UHA, not UCS: no curve.
    assert_eq!(curve("SA-240-304"), None);
}

#[test]
fn flat_segment_and_thin_material() {
    close(mdmt("A", 10.0).temperature, -7.78);
    close(mdmt("B", 8.0).temperature, -28.89);
    close(mdmt("C", 6.0).temperature, -48.33);
    close(mdmt("D", 10.0).temperature, -48.33);
    // UCS-66(d) takes over at 2.5 mm even on curve A.
    let thin = mdmt("A", 2.5);
    close(thin.temperature, -48.33);
    assert!(thin.basis.contains("UCS-66(d)"), "{}", thin.basis);
}

#[test]
fn above_ten_mm_is_not_computed_and_says_why() {
    let m = mdmt("B", 12.0);
    assert_eq!(m.temperature, None);
    assert!(m.basis.contains("Table UCS-66"), "{}", m.basis);
    let bad = mdmt("E", 5.0);
    assert_eq!(bad.temperature, None);
    assert!(bad.basis.contains("\"E\""), "{}", bad.basis);
}

#[test]
fn the_vessel_mdmt_is_the_warmest_part() {
    let a = mdmt("A", 8.0);
    let b = mdmt("B", 8.0);
    let thick = mdmt("A", 20.0);
    let v = vessel_mdmt([("S1", &b), ("H1", &a), ("S2", &thick)]).unwrap();
    assert_eq!(v.0, "H1");
    close(Some(v.1), -7.78);
}

/// Through a design: an SA-516-70 drum (curve B) with 8 mm shells and heads has
/// every part at −28.89 °C; a 12 mm shell is reported as not computed.
#[test]
fn a_design_s_parts_get_their_mdmt() {
    let table = MaterialTable::builtin();
    let mut design = common::examples::example("horizontal-drum");
    let v = &mut design.vessels[0];
    v.design.pressure = Some(300.0);
    v.design.temperature = Some(100.0);
    v.design.material = Some("SA-516-70".into());
    let mut first_shell = true;
    for p in &mut v.parts {
        match p {
            PartDesign::Shell(s) if first_shell => {
                s.thickness = Some(12.0);
                first_shell = false;
            }
            PartDesign::Shell(s) => s.thickness = Some(8.0),
            PartDesign::Head(h) => h.thickness = Some(8.0),
            _ => {}
        }
    }
    let resolved = vesselcad::constraints::resolve_vessel(v, 0).unwrap();
    let c = calculate(v, &resolved, &table);
    let with: Vec<_> = c.parts.iter().filter_map(|p| p.mdmt.as_ref()).collect();
    assert_eq!(with.len(), c.parts.len(), "{:?}", c.parts);
    let mut computed = 0;
    for m in &with {
        assert_eq!(m.curve, "B");
        if m.governing_thickness == 8.0 {
            close(m.temperature, -28.89);
            computed += 1;
        } else {
            assert_eq!(m.temperature, None);
        }
    }
    assert!(computed >= 2, "{with:?}");
}
