//! UG-28 / UG-33 external pressure in the elastic range (`vesselcad::calc::external`).
//!
//! Hand calculation (E = 200 000 MPa, Sy = 260 MPa, limit A·E ≤ 0.5·Sy = 130 MPa):
//! - Cylinder Do = 1000, t = 10, L = 3000 mm: t/Do = 0.01; long A = 1.1·0.01² =
//!   1.1e-4; short A = 1.30·0.01^1.5 / (3 − 0.45·0.1) = 0.0013/2.955 =
//!   4.39932e-4 (governs, the larger); A·E = 87.99 MPa ≤ 130; B = A·E/2 =
//!   43.993 MPa; Pa = 4B/(3·Do/t) = 4·43.993/300 = 0.58658 MPa.
//! - Long cylinder, L = 100 000 mm: short A = 0.0013/99.955 = 1.30e-5 < 1.1e-4,
//!   A = 1.1e-4, B = 11 MPa, Pa = 44/300 = 0.146667 MPa.
//!   Cross-check against the classical long-tube buckling pressure
//!   Pcr = 2E/(1−ν²)·(t/Do)³ = 2·200 000/0.91·1e-6 = 0.43956 MPa: Pa = Pcr/3
//!   within the 1.1 vs 2/0.91/2 = 1.0989 rounding of Fig. G (0.1 %).
//! - Torispherical head Ro = 2000, t = 5 mm: Ro/t = 400, A = 0.125/400 =
//!   3.125e-4, B = 31.25 MPa, Pa = B/(Ro/t) = 0.078125 MPa.
//! - 2:1 ellipsoidal head Do = 2000: Ro = 0.9·2000 = 1800 mm.

mod common;

use vesselcad::calc::external::{
    cylinder, ellipsoidal_ro, head, required_cylinder, required_head, required_long_cylinder,
};

const E: f64 = 200_000.0;
const SY: f64 = 260.0;

fn close(got: f64, want: f64, rel: f64) {
    assert!(((got - want) / want).abs() < rel, "got {got}, want {want}");
}

#[test]
fn ug28_short_cylinder_hand_calculation() {
    let r = cylinder(1000.0, 10.0, 3000.0, E, SY).unwrap();
    assert_eq!(r.paragraph, "UG-28(c)(1)");
    close(r.a, 4.39932e-4, 1e-5);
    close(r.b, 43.9932, 1e-5);
    close(r.allowable, 0.586576, 1e-5);
}

#[test]
fn ug28_long_cylinder_is_a_third_of_the_classical_buckling_pressure() {
    let r = cylinder(1000.0, 10.0, 100_000.0, E, SY).unwrap();
    close(r.a, 1.1e-4, 1e-12);
    close(r.allowable, 0.146_667, 1e-5);
    let pcr = 2.0 * E / (1.0 - 0.09) * 1e-6;
    close(r.allowable, pcr / 3.0, 2e-3);
}

#[test]
fn ug33_heads_hand_calculation() {
    let r = head(2000.0, 5.0, E, SY).unwrap();
    close(r.a, 3.125e-4, 1e-12);
    close(r.b, 31.25, 1e-12);
    close(r.allowable, 0.078125, 1e-12);
    close(ellipsoidal_ro(2000.0, 2.0).unwrap(), 1800.0, 1e-12);
    assert!(ellipsoidal_ro(2000.0, 2.5).unwrap_err().contains("2:1"));
}

#[test]
fn beyond_the_elastic_line_and_thick_walls_are_refused() {
    // Ro/t = 100: A = 1.25e-3, A·E = 250 MPa > 130 MPa.
    let e = head(1000.0, 10.0, E, SY).unwrap_err();
    assert!(e.contains("elastic line"), "{e}");
    // Do/t = 8 < 10.
    let e = cylinder(80.0, 10.0, 500.0, E, SY).unwrap_err();
    assert!(e.contains("UG-28(c)(2)"), "{e}");
    let e = cylinder(1000.0, 0.0, 500.0, E, SY).unwrap_err();
    assert!(e.contains("t = 0"), "{e}");
}

/// Through a design: a drum under full vacuum (101.3 kPa external) gets UG-28 on
/// its shells and UG-33 on its heads, computed on the corroded wall, and a part
/// whose allowable is below 0.1013 MPa is a deficiency; without the field no
/// part has an external figure.
#[test]
fn a_design_under_vacuum_gets_ug28_and_ug33() {
    use vesselcad::calc::{MaterialTable, calculate};
    let table = MaterialTable::builtin();
    let mut design = common::examples::example("horizontal-drum");
    let v = &mut design.vessels[0];
    v.design.pressure = Some(300.0);
    v.design.temperature = Some(100.0);
    let resolved = vesselcad::constraints::resolve_vessel(v, 0).unwrap();
    let none = calculate(v, &resolved, &table);
    assert!(none.parts.iter().all(|p| p.external.is_none()));
    v.design.external_pressure = Some(101.3);
    let c = calculate(v, &resolved, &table);
    let mut shells = 0;
    for p in &c.parts {
        let x = p.external.as_ref().expect("an external figure");
        let Ok(x) = x else { continue };
        if p.kind == "shell" {
            assert_eq!(x.paragraph, "UG-28(c)(1)");
            shells += 1;
        }
        let short = x.allowable < 0.1013;
        let flagged = c
            .vessel
            .deficiencies
            .iter()
            .any(|d| d.contains(&p.id) && d.contains("external"));
        assert_eq!(
            short, flagged,
            "{}: {x:?} {:?}",
            p.id, c.vessel.deficiencies
        );
    }
    assert!(shells > 0, "{:?}", c.parts);
}

/// A vessel designed for vacuum only (design pressure 0, external pressure full
/// vacuum) is calculated: its walls under UG-28 / UG-33, no internal thickness
/// but the UG-16(b) minimum, the UG-99(f) internal test 1.3 · 0.101325 =
/// 0.1317225 MPa, and the report's external-pressure table. With neither an
/// internal nor an external pressure the vessel is still not calculated.
#[test]
fn a_vacuum_only_vessel_is_calculated() {
    use vesselcad::calc::html::{ReportVessel, html};
    use vesselcad::calc::{MaterialTable, calculate};
    let table = MaterialTable::builtin();
    let mut design = common::examples::example("horizontal-drum");
    let v = &mut design.vessels[0];
    v.design.pressure = Some(0.0);
    v.design.temperature = Some(100.0);
    let resolved = vesselcad::constraints::resolve_vessel(v, 0).unwrap();
    let refused = calculate(v, &resolved, &table);
    assert!(refused.vessel.conditions.is_none());
    assert!(
        refused.vessel.problems[0].contains("design.external_pressure"),
        "{:?}",
        refused.vessel.problems
    );
    v.design.external_pressure = Some(101.325);
    let c = calculate(v, &resolved, &table);
    let conds = c.vessel.conditions.as_ref().expect("conditions");
    assert!(conds.vacuum_only());
    assert_eq!(c.parts.len(), 3, "{:?}", c.vessel.problems);
    for p in &c.parts {
        assert_eq!(p.required.paragraph, "UG-28");
        assert_eq!(p.required.value, 3.0, "t = CA");
        assert!(p.external.as_ref().is_some_and(|x| x.is_ok()), "{p:?}");
    }
    let test = c.vessel.hydrotest.as_ref().unwrap();
    assert_eq!(test.paragraph, "UG-99(f)");
    close(test.value, 0.131_722_5, 1e-12);
    // Nozzles: UG-45 still checked; no UG-37(c) without internal pressure, but
    // UG-37(d)(1) on every opening whose host has its external-pressure wall
    // (or the reason in the problems).
    assert_eq!(c.nozzles.len(), 8);
    let mut external = 0;
    for n in &c.nozzles {
        assert!(n.reinforcement.is_none(), "{}", n.mark);
        let host = c.parts.iter().find(|p| p.id == n.host).unwrap();
        match (&host.external_required, &n.reinforcement_external) {
            (Some(Ok(tr)), Some(r)) => {
                assert_eq!(r.paragraph, "UG-37(d)(1)");
                close(r.tr, *tr, 1e-12);
                close(r.a_required, 0.5 * r.d * tr, 1e-12);
                external += 1;
            }
            _ => assert!(
                c.vessel
                    .problems
                    .iter()
                    .any(|p| p.starts_with(&format!("{}:", n.mark)) && p.contains("UG-37(d)")),
                "{}: {:?} {:?}",
                n.mark,
                host.external_required,
                c.vessel.problems
            ),
        }
    }
    assert!(external > 0, "{:?}", c.vessel.problems);
    let page = html(
        "drum.json",
        &[ReportVessel {
            design: v,
            calculation: &c,
            weights: Err("not needed".into()),
        }],
    );
    assert!(
        page.contains("External pressure (UG-28 / UG-33"),
        "no table"
    );
    assert!(page.contains("UG-28(c)(1)") && page.contains("UG-33(d)/(e)"));
}

/// The walls UG-28 / UG-33 require, the hand calculations above inverted:
/// - Do = 1000, L = 3000 under 0.586 576 MPa → t = 10 mm (bisection);
/// - long: t = Do·(3P/(2.2E))^(1/3) = 1000·(0.44/440 000)^(1/3) = 10 mm at
///   P = 0.146 667 MPa (= 0.44/3);
/// - head Ro = 2000: t = 4·Ro·(P/E)^0.5 = 8000·(0.078 125/200 000)^0.5
///   = 8000 · 6.25e-4 = 5 mm.
///
/// And each found wall carries the pressure it was found for (property: the
/// allowable at the required wall is the design pressure).
#[test]
fn required_walls_under_external_pressure() {
    close(
        required_cylinder(1000.0, 3000.0, E, SY, 0.586_576).unwrap(),
        10.0,
        1e-5,
    );
    close(
        required_long_cylinder(1000.0, E, SY, 0.44 / 3.0).unwrap(),
        10.0,
        1e-12,
    );
    close(required_head(2000.0, E, SY, 0.078_125).unwrap(), 5.0, 1e-12);
    for (l, p) in [(500.0, 0.05), (3000.0, 0.1013), (20_000.0, 0.2)] {
        let t = required_cylinder(2000.0, l, E, SY, p).unwrap();
        close(cylinder(2000.0, t, l, E, SY).unwrap().allowable, p, 1e-6);
    }
    // Beyond the elastic line (A·E > 130 MPa) and past Do/10: refused, said why.
    let e = required_head(1000.0, E, SY, 5.0).unwrap_err();
    assert!(e.contains("elastic line"), "{e}");
    let e = required_cylinder(100.0, 1000.0, E, SY, 500.0).unwrap_err();
    assert!(e.contains("Do/10"), "{e}");
    let e = required_long_cylinder(0.0, E, SY, 0.1).unwrap_err();
    assert!(e.contains("Do = 0"), "{e}");
}

/// UG-37(d)(1), hand calculation on the opening of `calc_nozzles`'s UG-37(c)
/// hand calculation (NPS 8 Sch 40 neck OD 219.1 × 8.18, CA 3, wall 12 mm) with
/// tr = 7.5 mm and trn = 1.2 mm taken as the external-pressure walls:
///   tn = 5.18, d = 208.74, t = 9
///   A  = 0.5 · d · tr = 0.5 · 208.74 · 7.5 = 782.775 mm² (half UG-37(c)'s 1565.55)
///   A1 = 208.74 · (9 − 7.5) = 313.11 mm²
///   A2 = 5 · (5.18 − 1.2) · 5.18 = 103.082 mm²
///   A41 = 2 · 3.626² = 26.2958 mm²
///   available 442.4878 mm² < 782.775: deficient.
/// No published worked example of UG-37(d) with its numbers was found; the
/// method (tr from the external-pressure rules, not the internal ones; the neck
/// as a cylinder under UG-28) is the one a public answer spells out (onetb.com
/// forum, "Design of nozzles under external pressure").
#[test]
fn ug37d_hand_calculation() {
    use vesselcad::calc::{Opening, reinforcement, reinforcement_external};
    let o = Opening {
        pressure: 0.1013,
        stress: 138.0,
        corrosion_allowance: 3.0,
        neck_od: 219.1,
        neck_wall: 8.18,
        wall: 12.0,
        wall_required: 7.5,
        host_diameter: 2000.0,
        pad: None,
    };
    let r = reinforcement_external(&o, 1.2).unwrap();
    assert_eq!(r.paragraph, "UG-37(d)(1)");
    close(r.trn, 1.2, 1e-12);
    close(r.a_required, 782.775, 1e-9);
    close(r.a1, 313.11, 1e-9);
    close(r.a2, 103.082, 1e-9);
    close(r.a41, 26.2958, 1e-5);
    close(r.a_available, 442.4878, 1e-5);
    assert!(r.deficient());
    let internal = reinforcement(&Opening { pressure: 1.5, ..o }).unwrap();
    assert_eq!(internal.paragraph, "UG-37(c)");
    close(internal.a_required, 2.0 * r.a_required, 1e-12);
    let e = reinforcement_external(&o, -1.0).unwrap_err().to_string();
    assert!(e.contains("neck_required") && e.contains("-1"), "{e}");
}

/// A drum under internal pressure and full vacuum gets both UG-37(c) and
/// UG-37(d)(1) per opening; a thin wall under vacuum makes UG-37(d) deficient
/// and the deficiency names the paragraph.
#[test]
fn openings_under_internal_and_external_pressure_get_both_checks() {
    use vesselcad::calc::external::required_long_cylinder;
    use vesselcad::calc::{MaterialTable, calculate};
    let table = MaterialTable::builtin();
    let mut design = common::examples::example("horizontal-drum");
    let v = &mut design.vessels[0];
    v.design.pressure = Some(300.0);
    v.design.temperature = Some(100.0);
    v.design.external_pressure = Some(101.325);
    let resolved = vesselcad::constraints::resolve_vessel(v, 0).unwrap();
    let c = calculate(v, &resolved, &table);
    let both: Vec<_> = c
        .nozzles
        .iter()
        .filter(|n| n.reinforcement.is_some() && n.reinforcement_external.is_some())
        .collect();
    assert!(!both.is_empty(), "{:?}", c.vessel.problems);
    let conds = c.vessel.conditions.as_ref().unwrap();
    for n in both {
        let x = n.reinforcement_external.as_ref().unwrap();
        let trn = required_long_cylinder(n.neck_od, conds.modulus, conds.yield_strength, 0.101_325)
            .unwrap();
        close(x.trn, trn, 1e-12);
        let flagged = c
            .vessel
            .deficiencies
            .iter()
            .any(|d| d.starts_with(&format!("{}:", n.mark)) && d.contains("UG-37(d)(1)"));
        assert_eq!(x.deficient(), flagged, "{}: {x:?}", n.mark);
    }
}
