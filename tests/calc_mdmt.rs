//! UCS-66 minimum design metal temperature (`vesselcad::calc::mdmt`, on the
//! curves of `vesselcad::calc::ucs66`): Fig. UCS-66 against the tabular values of
//! Table UCS-66, Fig. UCS-66.1 and the whole rule set against published
//! calculations, the thick and thin rules, the refusals, and the figures through
//! a whole design.
//!
//! References (°C = (°F − 32)/1.8 throughout):
//! - Table UCS-66's tabular values as API RP 581 reproduces them (Tref, °F to
//!   0.1, 0.25 to 3.3125 in by 1/16 in; a public Python RBI code on GitHub, class
//!   `Table213`), transcribed in [`TABLE`].
//! - Published calculations with their printed inputs and results: Pressure
//!   Vessel Engineering Ltd., "Design Calculation, ASME Code Version 2015" (PV
//!   Elite 2017, firetube boiler 11110c-1, 2017) and "Heat Exchanger Sample"
//!   (PVE-4293, PV Elite 2012, 2012); Key Design Engineering, "Sample Filter
//!   KEY-026" (COMPRESS). PV Elite prints whole °F and reads Fig. UCS-66 rounded
//!   up to the next whole degree, so its figures are met within 1 °F.

mod common;

use vesselcad::calc::mdmt::{mdmt, vessel_mdmt};
use vesselcad::calc::ucs66::{CURVE_D_END_IN, celsius, curve_f, reduction_f};
use vesselcad::calc::{MaterialTable, calculate};
use vesselcad::design::PartDesign;

/// Governing thickness in, then curves A, B, C, D in °F.
const TABLE: [(f64, [f64; 4]); 49] = [
    (0.25, [18.0, -20.0, -55.0, -55.0]),
    (0.3125, [18.0, -20.0, -55.0, -55.0]),
    (0.375, [18.0, -20.0, -55.0, -55.0]),
    (0.4375, [24.2, -14.0, -40.5, -55.0]),
    (0.5, [31.6, -6.9, -32.2, -55.0]),
    (0.5625, [38.2, -0.6, -27.2, -51.0]),
    (0.625, [44.0, 5.2, -22.8, -47.5]),
    (0.6875, [49.2, 10.4, -18.7, -44.2]),
    (0.75, [53.9, 15.1, -15.0, -41.1]),
    (0.8125, [58.2, 19.5, -11.6, -38.1]),
    (0.875, [62.1, 23.5, -8.6, -35.3]),
    (0.9375, [65.6, 27.2, -5.7, -32.7]),
    (1.0, [68.9, 30.6, -3.1, -30.1]),
    (1.0625, [71.9, 33.8, -0.7, -27.8]),
    (1.125, [74.6, 36.7, 1.6, -25.5]),
    (1.1875, [77.2, 39.4, 3.7, -23.4]),
    (1.25, [79.6, 42.0, 5.8, -21.4]),
    (1.3125, [81.8, 44.4, 7.7, -19.5]),
    (1.375, [83.8, 46.6, 9.6, -17.6]),
    (1.4375, [85.8, 48.7, 11.4, -15.9]),
    (1.5, [87.6, 50.7, 13.1, -14.3]),
    (1.5625, [89.2, 52.5, 14.8, -12.7]),
    (1.625, [90.8, 54.3, 16.4, -11.2]),
    (1.6875, [92.3, 55.9, 17.9, -9.8]),
    (1.75, [93.7, 57.5, 19.4, -8.5]),
    (1.8125, [95.1, 58.9, 20.9, -7.2]),
    (1.875, [96.3, 60.3, 22.3, -5.9]),
    (1.9375, [97.5, 61.7, 23.7, -4.7]),
    (2.0, [98.6, 63.0, 25.0, -3.6]),
    (2.0625, [99.7, 64.2, 26.3, -2.5]),
    (2.125, [100.7, 65.3, 27.5, -1.4]),
    (2.1875, [101.7, 66.4, 28.7, -0.4]),
    (2.25, [102.6, 67.5, 29.9, 0.6]),
    (2.3125, [103.5, 68.5, 31.0, 1.6]),
    (2.375, [104.3, 69.5, 32.1, 2.5]),
    (2.4375, [105.1, 70.5, 33.2, 3.4]),
    (2.5, [105.8, 71.4, 34.3, 4.3]),
    (2.5625, [106.5, 72.3, 35.3, 5.2]),
    (2.625, [107.2, 73.2, 36.3, 6.0]),
    (2.6875, [107.9, 74.0, 37.2, 6.9]),
    (2.75, [108.5, 74.8, 38.2, 7.7]),
    (2.8125, [109.1, 75.6, 39.1, 8.5]),
    (2.875, [109.7, 76.4, 39.9, 9.3]),
    (2.9375, [110.2, 77.2, 40.8, 10.1]),
    (3.0, [110.8, 77.9, 41.7, 10.9]),
    (3.0625, [111.3, 78.7, 42.5, 11.7]),
    (3.125, [111.7, 79.4, 43.3, 12.4]),
    (3.1875, [112.2, 80.1, 44.0, 13.2]),
    (3.25, [112.6, 80.8, 44.8, 13.9]),
];

fn close(got: Option<f64>, want: f64, tol: f64) {
    let got = got.expect("a temperature");
    assert!((got - want).abs() <= tol, "got {got}, want {want} ± {tol}");
}

/// 1 °F as a temperature difference, K.
const ONE_F: f64 = 1.0 / 1.8;

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

/// Curves A, B and C (closed forms) meet every tabular value within its 0.05 °F
/// rounding; curve D (the table) equals it at its points and is linear between.
#[test]
fn fig_ucs66_matches_table_ucs66() {
    let mut worst = [0.0f64; 3];
    for (t, row) in TABLE {
        for (k, letter) in ["A", "B", "C"].into_iter().enumerate() {
            let d = (curve_f(letter, t).unwrap() - row[k]).abs();
            worst[k] = worst[k].max(d);
            assert!(d <= 0.05 + 1e-9, "curve {letter} at {t} in: {d} F off");
        }
        assert!((curve_f("D", t).unwrap() - row[3]).abs() < 1e-9, "D at {t}");
    }
    eprintln!("worst |curve - table|, F: A {worst:?}");
    // Curve D halfway between 1 and 1.0625 in: (-30.1 - 27.8)/2.
    assert!((curve_f("D", 1.03125).unwrap() + 28.95).abs() < 1e-9);
    // The curves end where the figure does: A reaches 120 F at 6 in.
    assert!((curve_f("A", 6.0).unwrap() - 119.78).abs() < 0.01);
    assert!(curve_f("A", 6.01).unwrap_err().contains("shipped to 6 in"));
    assert!(curve_f("D", CURVE_D_END_IN + 0.01).is_err());
    assert!(curve_f("E", 1.0).unwrap_err().contains("\"E\""));
}

/// Fig. UCS-66.1 against the reductions printed by the published calculations
/// (coincident ratio → °F): PV Elite 0.957 → 4, 0.941 → 6, 0.911 → 9, 0.910 → 9,
/// 0.699 → 30, 0.597 → 41, 0.379 → 118; COMPRESS 0.38091 → 116.1. The two
/// branches meet at Rts = 0.6 (40 °F); none at Rts ≥ 1; UCS-66(b)(3) at ≤ 0.35.
/// The one published point off by more than 1 °F, PV Elite's 2:1 head at Rts
/// 0.574 printing 45 °F, is only held to lie above this curve (41.7 °F: the
/// smaller reduction, the safe side).
#[test]
fn fig_ucs66_1_matches_published_reductions() {
    for (rts, published) in [
        (0.957, 4.0),
        (0.941, 6.0),
        (0.911, 9.0),
        (0.910, 9.0),
        (0.699, 30.0),
        (0.597, 41.0),
        (0.379, 118.0),
        (0.38091, 116.1),
    ] {
        let got = reduction_f(rts).unwrap();
        assert!(
            (got - published).abs() <= 1.0,
            "Rts {rts}: {got} F vs {published} F"
        );
    }
    let head = reduction_f(0.574).unwrap();
    assert!((41.0..45.0).contains(&head), "{head}");
    assert!((reduction_f(0.6).unwrap() - 40.0).abs() < 0.02);
    assert!((reduction_f(0.600_001).unwrap() - 40.0).abs() < 0.001);
    assert_eq!(reduction_f(1.0), Some(0.0));
    assert_eq!(reduction_f(1.3), Some(0.0));
    assert_eq!(reduction_f(0.35), None);
    assert_eq!(reduction_f(f64::NAN), None);
    // Monotone: a lower ratio never gives a smaller reduction.
    let r: Vec<f64> = (36..=100)
        .map(|i| reduction_f(i as f64 / 100.0).unwrap())
        .collect();
    assert!(r.windows(2).all(|w| w[0] >= w[1]), "{r:?}");
}

/// Whole parts of the published calculations (curve B, SA-516-70 and SA-106 B),
/// governing thickness in, coincident ratio → the MDMT printed, °F.
#[test]
fn published_part_mdmts() {
    let f = |tg_in: f64, rts: f64| mdmt("B", tg_in * 25.4, Some(rts));
    // Cover: tg 0.297 in, Rts 0.957: -20 - 4 = -24 F.
    close(f(0.297, 0.957).temperature, celsius(-24.0), ONE_F);
    // Head knuckle: tg 0.168 in, Rts 0.699: -20 - 30 = -50 F.
    close(f(0.168, 0.699).temperature, celsius(-50.0), ONE_F);
    // Head straight flange: tg 0.188 in, Rts 0.597: -20 - 41 stops at -55 F.
    close(f(0.188, 0.597).temperature, celsius(-55.0), 1e-9);
    // Nozzle junction: tg 0.756 in, Rts 0.379: 118 F off the curve, -55 F floor.
    close(f(0.756, 0.379).temperature, celsius(-55.0), 1e-9);
    // Firetube SA-106 B: tg 0.328 in, Rts 0.190 <= 0.35: -155 F (UCS-66(b)(3)).
    let low = f(0.328, 0.190);
    close(low.temperature, celsius(-155.0), 1e-9);
    assert!(low.basis.contains("UCS-66(b)(3)"), "{}", low.basis);
    // Shell course: tg 0.750 in, tr 0.647 in, c 0.0625 in, E* 1:
    // Rts = 0.647/(0.750 - 0.0625) = 0.941; 16 - 6 = +10 F.
    let rts: f64 = 0.647 / (0.750 - 0.0625);
    assert!((rts - 0.941).abs() < 5e-4);
    close(f(0.750, rts).temperature, celsius(10.0), ONE_F);
    // Nozzle pad: tg 0.625 in, Rts 0.910: 6 - 9 = -3 F.
    close(f(0.625, 0.910).temperature, celsius(-3.0), ONE_F);
    // Where PV Elite differs from the Code's words: its nozzle neck at tg 0.5 in,
    // Rts 0.201 prints -6 - 140 = -146 F; UCS-66(b)(3) allows -155 F at Rts <= 0.35.
    close(f(0.5, 0.201).temperature, celsius(-155.0), 1e-9);
}

#[test]
fn flat_segment_and_thin_material() {
    close(mdmt("A", 10.0, None).temperature, -7.78, 0.005);
    close(mdmt("B", 8.0, None).temperature, -28.89, 0.005);
    close(mdmt("C", 6.0, None).temperature, -48.33, 0.005);
    close(mdmt("D", 12.0, None).temperature, -48.33, 0.005);
    // UCS-66(d) takes over at 2.5 mm even on curve A.
    let thin = mdmt("A", 2.5, None);
    close(thin.temperature, -48.33, 0.005);
    assert!(thin.basis.contains("UCS-66(d)"), "{}", thin.basis);
    // A ratio of 1 or more changes nothing.
    assert_eq!(
        mdmt("B", 8.0, Some(1.2)).temperature,
        mdmt("B", 8.0, None).temperature
    );
}

/// Above 10 mm the curves rise: curve B at 1 in (25.4 mm) is 30.6 F in the table.
/// A welded part over 4 in needs impact testing below 120 F. Curve D above
/// 3.3125 in and letters other than A–D are refused, saying why.
#[test]
fn thick_parts_and_refusals() {
    let b = mdmt("B", 25.4, None);
    close(b.temperature, celsius(30.6), 0.05 / 1.8 + 1e-9);
    close(b.curve_temperature, celsius(30.6), 0.05 / 1.8 + 1e-9);
    assert_eq!(b.reduction, None);
    let thick = mdmt("C", 110.0, Some(0.2));
    close(thick.temperature, celsius(120.0), 1e-9);
    assert!(thick.basis.contains("4 in"), "{}", thick.basis);
    let d = mdmt("D", 90.0, None);
    assert_eq!(d.temperature, None);
    assert!(
        d.basis.contains("curve D is shipped to 3.3125 in"),
        "{}",
        d.basis
    );
    let bad = mdmt("E", 5.0, None);
    assert_eq!(bad.temperature, None);
    assert!(bad.basis.contains("\"E\""), "{}", bad.basis);
}

#[test]
fn exemption_outcome() {
    // Curve B, 1 in, Rts 0.8: 30.6 - 20 = 10.6 F (-11.9 C).
    let m = mdmt("B", 25.4, Some(0.8));
    close(m.reduction, 20.0 / 1.8, 1e-9);
    assert_eq!(m.exempt_at(-10.0), Some(true));
    assert_eq!(m.exempt_at(-29.0), Some(false));
    assert_eq!(mdmt("D", 90.0, None).exempt_at(0.0), None);
}

#[test]
fn the_vessel_mdmt_is_the_warmest_part() {
    let a = mdmt("A", 8.0, None);
    let b = mdmt("B", 8.0, None);
    let thick = mdmt("A", 20.0, None);
    let v = vessel_mdmt([("S1", &b), ("H1", &a), ("S2", &thick)]).unwrap();
    assert_eq!(v.0, "S2");
    close(Some(v.1), celsius(curve_f("A", 20.0 / 25.4).unwrap()), 1e-9);
}

/// Through a design: an SA-516-70 drum (curve B) with one 12 mm shell and 8 mm
/// other parts. Every part gets a figure; each part's coincident ratio is its
/// corroded required thickness over its corroded wall (E* = max(E, 0.8)), and its
/// MDMT is Fig. UCS-66 lowered by Fig. UCS-66.1 at that ratio.
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
    let ca = v.design.corrosion_allowance.unwrap_or(0.0);
    let e = v
        .design
        .joint_efficiency
        .unwrap_or(vesselcad::calc::DEFAULT_JOINT_EFFICIENCY)
        .max(0.8);
    let resolved = vesselcad::constraints::resolve_vessel(v, 0).unwrap();
    let c = calculate(v, &resolved, &table);
    let mut thick = 0;
    for p in &c.parts {
        let m = p.mdmt.as_ref().expect("every part has a UCS-66 figure");
        assert_eq!(m.curve, "B");
        let t = p.thickness.unwrap();
        let rts = (p.required.value - ca) * e / (t - ca);
        assert!((m.ratio.unwrap() - rts).abs() < 1e-12, "{}: {m:?}", p.id);
        assert!(rts > 0.0 && rts < 1.0, "{}: Rts {rts}", p.id);
        let want = mdmt("B", t, Some(rts));
        assert_eq!(m.temperature, want.temperature, "{}", p.id);
        assert!(
            m.temperature.unwrap() < m.curve_temperature.unwrap(),
            "{m:?}"
        );
        if t == 12.0 {
            thick += 1;
            close(
                m.curve_temperature,
                celsius(curve_f("B", 12.0 / 25.4).unwrap()),
                1e-9,
            );
        }
    }
    assert_eq!(thick, 1);
}
