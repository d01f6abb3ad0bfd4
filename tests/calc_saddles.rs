//! Zick's saddle stresses: the factors against Zick's published table, one saddle
//! against a hand calculation written out below, and the example drum's saddles
//! from the weight model in the operating and hydrotest cases, live in the model.

mod common;

use common::examples::example;
use vesselcad::calc::saddles::compressive_b;
use vesselcad::calc::zick::{Saddle, factors, stresses};
use vesselcad::calc::{MaterialTable, calculate};
use vesselcad::design::{self, PartDesign};
use vesselcad::mesh::TessellationOptions;
use vesselcad::model::{Edit, Model};
use vesselcad::weights::weights;

fn close(got: f64, want: f64, tol: f64, what: &str) {
    assert!(
        (got - want).abs() <= tol,
        "{what}: got {got}, want {want} ± {tol}"
    );
}

#[test]
fn factors_match_zicks_table() {
    // Zick (1951, revised 1971), factor table for θ = 120° as reprinted in
    // Megyesy, Pressure Vessel Handbook ("Values of constant K", θ = 120°):
    // K1 = 0.335 (Megyesy's K1 multiplies R²·ts, i.e. π × Moss's 0.107),
    // K2 = 1.171, K3 = 0.880, K4 = 0.401, K5 = 0.760, K6 = 0.053; and θ = 150°:
    // K2 = 0.799, K3 = 0.485, K5 = 0.673, K6 = 0.032. Printed to 3 decimals.
    let f = factors(120.0);
    close(std::f64::consts::PI * f.k1, 0.335, 5e-4, "π·K1 at 120°");
    close(f.k1, 0.107, 5e-4, "K1 at 120°");
    close(f.k1_bottom, 0.192, 5e-4, "K1* at 120° (Moss)");
    close(f.k2, 1.171, 5e-4, "K2 at 120°");
    close(f.k3, 0.880, 5e-4, "K3 at 120°");
    close(f.k4, 0.401, 5e-4, "K4 at 120°");
    close(f.k5, 0.760, 5e-4, "K5 at 120°");
    close(f.k6, 0.053, 5e-4, "K6 at 120°");
    let f = factors(150.0);
    close(f.k2, 0.799, 5e-4, "K2 at 150°");
    close(f.k3, 0.485, 5e-4, "K3 at 150°");
    close(f.k5, 0.673, 5e-4, "K5 at 150°");
    close(f.k6, 0.032, 5e-4, "K6 at 150°");
}

/// One saddle, worked by hand (N, mm, MPa):
///
/// Q = 300 000 N, R = 1225, ts = th = 12, L = 12 000, H = 612.5, A = 1000,
/// b = 300, θ = 120°. A = 1000 > R/2 = 612.5: the shell is not stiffened by the
/// head, K1 = 0.10661, K1* = 0.19235, K2 = 1.17069, K5 = 0.76026, K6 = 0.052852.
///
/// - 1 + 4H/(3L) = 1 + 2450/36000 = 1.068056.
/// - Saddle: 1 − A/L + (R² − H²)/(2AL) = 1 − 0.083333 + (1 500 625 − 375 156.25)
///   / 24 000 000 = 0.963561; / 1.068056 = 0.902164; bracket 0.097836;
///   M1 = Q·A·0.097836 = 29 350 821 N·mm (hogging).
/// - π·R²·ts = π · 1 500 625 · 12 = 56 572 230 mm³.
/// - S1 top = 29 350 821 / (0.10661 · 56 572 230) = 4.866 MPa (tension);
///   bottom = 29 350 821 / (0.19235 · 56 572 230) = 2.697 MPa (compression).
/// - Midspan: (1 + 2·1 125 468.75 / 144 000 000) / 1.068056 − 4000/12000
///   = 1.015631 / 1.068056 − 0.333333 = 0.617584; M2 = Q·L/4 · 0.617584
///   = 555 824 732 N·mm; S1 = 9.825 MPa.
/// - S2 = K2·Q/(R·ts) · (L − 2A)/(L + 4H/3) = 1.17069 · 300 000 / 14 700
///   · 10 000 / 12 816.67 = 18.641 MPa.
/// - A/R = 0.81633: K6 · (0.25 + 0.75 · 0.31633 / 0.5) = 0.052852 · 0.72449
///   = 0.038291. L = 12 000 ≥ 8R = 9800: S3 = −Q/(4·ts·(b + 1.56√(R·ts)))
///   − 3·K6·Q/(2·ts²); b + 1.56·√14 700 = 489.140; −300 000 / (48 · 489.140)
///   − 1.5 · 0.038291 · 300 000 / 144 = −12.778 − 119.658 = −132.435 MPa.
/// - S4 = −K5·Q/(ts · 489.140) = −0.76026 · 300 000 / 5869.68 = −38.857 MPa.
/// - With a 10 mm wear plate (t = 22 in S3 and S4): S3 = −300 000 / (88 · 489.140)
///   − 1.5 · 0.038291 · 300 000 / 484 = −6.970 − 35.601 = −42.570 MPa;
///   S4 = −0.76026 · 300 000 / (22 · 489.140) = −21.195 MPa.
#[test]
fn one_saddle_matches_the_hand_calculation() {
    let input = Saddle {
        load: 300_000.0,
        a: 1000.0,
        l: 12_000.0,
        r: 1225.0,
        ts: 12.0,
        th: 12.0,
        h: 612.5,
        b: 300.0,
        theta: 120.0,
        wear_plate: 0.0,
    };
    let s = stresses(&input).unwrap();
    assert!(!s.stiffened);
    close(-s.m_saddle, 29_350_821.0, 5.0, "M1");
    close(s.s1_saddle_top, 4.866, 1e-3, "S1 top at the saddle");
    close(s.s1_saddle_bottom, -2.697, 1e-3, "S1 bottom at the saddle");
    close(s.m_midspan, 555_824_732.0, 50.0, "M2");
    close(s.s1_midspan, 9.825, 1e-3, "S1 midspan");
    close(s.s2_shell, 18.641, 1e-3, "S2");
    assert!(s.s2_head.is_none() && s.head_additional.is_none());
    close(s.k6_used, 0.038_291, 1e-6, "K6 reduced for A/R");
    close(s.s3_horn, -132.435, 1e-3, "S3");
    close(s.s4_bottom, -38.857, 1e-3, "S4");
    let w = stresses(&Saddle {
        wear_plate: 10.0,
        ..input
    })
    .unwrap();
    close(w.s3_horn, -42.570, 1e-3, "S3 with wear plate");
    close(w.s4_bottom, -21.195, 1e-3, "S4 with wear plate");
    // The wear plate changes the circumferential stresses only.
    assert_eq!(w.s1_saddle_top, s.s1_saddle_top);
    assert_eq!(w.s2_shell, s.s2_shell);
}

/// Near the head (A ≤ R/2) the head stiffens the shell: K1 = K1* = 1, shear by
/// K3 in shell and head, the head's additional stress by K4, K6 a quarter.
#[test]
fn a_saddle_near_the_head_is_stiffened_by_it() {
    let s = stresses(&Saddle {
        load: 300_000.0,
        a: 500.0,
        l: 6000.0,
        r: 1225.0,
        ts: 12.0,
        th: 10.0,
        h: 612.5,
        b: 300.0,
        theta: 120.0,
        wear_plate: 0.0,
    })
    .unwrap();
    assert!(s.stiffened);
    // K3·Q/(R·ts) = 0.87993 · 300 000 / 14 700 = 17.958; in the head / (R·th):
    // 0.87993 · 300 000 / 12 250 = 21.549; K4·Q/(R·th) = 0.40106 · 24.490 = 9.822.
    close(s.s2_shell, 17.958, 1e-3, "S2 shell");
    close(s.s2_head.unwrap(), 21.549, 1e-3, "S2 head");
    close(s.head_additional.unwrap(), 9.822, 1e-3, "head additional");
    close(s.k6_used, 0.052_852 / 4.0, 1e-6, "K6 / 4");
    // S1 at the saddle over the full section (K1 = 1): tension = compression.
    close(s.s1_saddle_top, -s.s1_saddle_bottom, 1e-12, "K1 = K1*");
    // L = 6000 < 8R: S3 = −Q/(4·ts·band) − 12·K6·Q·R/(L·ts²)
    // = −12.778 − 12 · 0.013213 · 300 000 · 1225 / (6000 · 144) = −12.778 − 67.440.
    close(s.s3_horn, -80.218, 2e-3, "S3 short vessel");
    // A saddle at or beyond midspan is outside the method.
    let beyond = Saddle {
        load: 300_000.0,
        a: 3000.0,
        l: 6000.0,
        r: 1225.0,
        ts: 12.0,
        th: 10.0,
        h: 612.5,
        b: 300.0,
        theta: 120.0,
        wear_plate: 0.0,
    };
    assert!(stresses(&beyond).unwrap_err().contains("midspan"));
}

#[test]
fn ug23_b_is_the_elastic_line_capped_at_a_quarter_of_yield() {
    // A = 0.125 · 11 / 1194.5 = 0.0011511; A·E/2 = 115.1 MPa > Sy/4 = 65 MPa.
    close(
        compressive_b(11.0, 1194.5, 200_000.0, 260.0),
        65.0,
        1e-12,
        "capped",
    );
    // Thin: A = 0.125 · 2 / 2000 = 1.25e-4; A·E/2 = 12.5 MPa.
    close(
        compressive_b(2.0, 2000.0, 200_000.0, 260.0),
        12.5,
        1e-9,
        "elastic",
    );
}

#[test]
fn the_drum_saddles_carry_its_weights_in_both_cases() {
    let d = example("horizontal-drum");
    let resolved = design::resolve(&d).unwrap();
    let table = MaterialTable::builtin();
    let calc = calculate(&d.vessels[0], &resolved[0], &table);
    let w = weights(&d.vessels[0], &resolved[0]).unwrap();
    let cases = &calc.vessel.saddles;
    assert_eq!(cases.len(), 4, "{:?}", calc.vessel.problems);
    for (case, mass) in [("operating", w.operating), ("hydrotest", w.test)] {
        let loads: Vec<f64> = cases
            .iter()
            .filter(|c| c.case == case)
            .map(|c| c.input.load)
            .collect();
        // Statics: the two reactions carry the whole weight.
        close(loads.iter().sum::<f64>(), mass * 9.806_65, 1e-6, case);
        assert!(loads.iter().all(|&q| q > 0.0), "{loads:?}");
    }
    let op = cases.iter().find(|c| c.case == "operating").unwrap();
    let test = cases.iter().find(|c| c.case == "hydrotest").unwrap();
    // Operating: corroded wall (14 − 3), mean radius (2400 − 11)/2; the
    // hydrotest is new (14) at the UG-99(b) pressure, full of water.
    close(op.input.ts, 11.0, 1e-12, "corroded ts");
    close(op.input.r, 1194.5, 1e-12, "mean radius");
    close(test.input.ts, 14.0, 1e-12, "new ts");
    close(
        test.pressure,
        calc.vessel.hydrotest.as_ref().unwrap().value,
        1e-12,
        "test P",
    );
    assert!(test.input.load > op.input.load);
    // Default saddles at 0.2 L from the tangent lines: L = 7200 + 2 · 50 of
    // straight flange = 7300, A = 1460 mm > R/2.
    close(op.input.l, 7300.0, 1e-9, "L");
    close(op.input.a, 1460.0, 1e-9, "A");
    assert!(!op.stresses.stiffened);
    // The drum holds on its saddles in both cases.
    let failing: Vec<String> = cases.iter().flat_map(|c| c.deficiencies()).collect();
    assert!(failing.is_empty(), "{failing:#?}");
}

/// A saddle too narrow for its load: the horn stress is a deficiency, reported
/// with the saddle, case, check and figures; a wear plate clears it.
#[test]
fn an_overloaded_horn_is_a_deficiency_that_a_wear_plate_clears() {
    let mut d = example("horizontal-drum");
    let set = |d: &mut design::Design, width: f64, wear: Option<f64>| {
        for p in &mut d.vessels[0].parts {
            if let PartDesign::Saddle(s) = p {
                s.width = width;
                s.wear_plate = wear;
            }
        }
    };
    // Thin the course so the horn governs.
    for p in &mut d.vessels[0].parts {
        if let PartDesign::Shell(s) = p {
            s.thickness = Some(10.0);
        }
    }
    set(&mut d, 100.0, None);
    let resolved = design::resolve(&d).unwrap();
    let calc = calculate(&d.vessels[0], &resolved[0], &MaterialTable::builtin());
    let horn: Vec<&String> = calc
        .vessel
        .deficiencies
        .iter()
        .filter(|s| s.contains("S3 at the horn"))
        .collect();
    assert!(!horn.is_empty(), "{:#?}", calc.vessel);
    assert!(
        horn.iter().any(|h| h.starts_with("SD")
            && h.contains("): Zick S3 at the horn = ")
            && h.contains("exceeds 1.5·S = 207.8 MPa")),
        "{horn:#?}"
    );
    set(&mut d, 100.0, Some(12.0));
    let resolved = design::resolve(&d).unwrap();
    let calc = calculate(&d.vessels[0], &resolved[0], &MaterialTable::builtin());
    assert!(
        calc.vessel.deficiencies.iter().all(|s| !s.contains("Zick")),
        "{:#?}",
        calc.vessel.deficiencies
    );
}

/// Live: any edit of a vessel on saddles recalculates its supports (its weight
/// changed), and the model's figures equal the pure calculation.
#[test]
fn saddle_checks_are_live() {
    let mut m =
        Model::from_design(&example("horizontal-drum"), TessellationOptions::chord(5.0)).unwrap();
    let fresh = |m: &Model| {
        let d = m.design();
        let r = design::resolve(&d).unwrap();
        calculate(&d.vessels[0], &r[0], &MaterialTable::builtin())
    };
    assert_eq!(m.calculation("V-101").unwrap(), fresh(&m));
    let before = m.calculation("V-101").unwrap().vessel.saddles;
    let mut n = m.design().vessels[0].nozzles[0].clone();
    n.projection += 300.0;
    let c = m
        .edit(Edit::SetNozzle {
            vessel: "V-101".into(),
            nozzle: n,
        })
        .unwrap();
    assert_eq!(c.supports_calculated, 1, "{c:?}");
    let after = m.calculation("V-101").unwrap();
    assert_eq!(after, fresh(&m));
    // A longer nozzle weighs more: the saddles carry more.
    let load = |cases: &[vesselcad::calc::saddles::SaddleCase]| -> f64 {
        cases
            .iter()
            .filter(|c| c.case == "operating")
            .map(|c| c.input.load)
            .sum()
    };
    assert!(load(&after.vessel.saddles) > load(&before));
    assert_eq!(m.update().supports_calculated, 0);
}
