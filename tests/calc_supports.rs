//! Supports of vertical vessels under wind and earthquake: the ASCE 7 pieces
//! against published figures, the skirt, legs and lugs on the example column,
//! and the checks kept live (a wind edit recalculates the supports only).
//!
//! Sources of the reference numbers (each test says which it uses):
//! - Kz: ASCE 7-16 Table 26.10-1 (Exposures B, C, D at 15–500 ft, two
//!   decimals), as reproduced in a public Python wind module found by the
//!   search tool (a table of 22 heights 4.6–152.4 m; the search tool did not name
//!   its repository). The same values are in ASCE 7-10 Table 27.3-1.
//! - Cs: a public worked example of ASCE 7-05 §12.8 (scribd document 329403343,
//!   "ASCE 7-05 Equivalent Lateral Force Procedure"): SDS 2.84, SD1 1.21, R 3,
//!   I 1.25, T 0.137 s → Cs = 1.18, 12.8-3's cap 3.68.
//! - Vertical distribution: an ENERCALC "ASCE 7-16 Seismic Base Shear" printout
//!   in the City of Santa Ana's public building records (publicdocs.santa-ana.org
//!   BuildingWeblink doc 548648, page 109): W 62.30 k, V 9.58 k, levels 20.90 k at
//!   17 ft and 41.40 k at 8 ft, k = 1 → Fx 4.96 k and 4.62 k, base moment
//!   121.3 k-ft.
//! - Anchor bolts: a PV Elite base-ring report published on scribd ("Base PLate
//!   Calculation Separator", document 602774370): P = −0.6·7 839.42/12 +
//!   4·1 369/(12·1.546) = −96.81 kgf.
//! - AISC ASD columns: Cc = 126.1 (Fy 36 ksi) and 107.0 (Fy 50 ksi), Fa beyond Cc
//!   ≈ 150 000/(KL/r)² ksi (Hicks, *Civil Engineering Formulas*, Table 9.1 and
//!   Eq. 9.6, from the AISC ASD specification).
//!
//! No published worked example of a whole skirt (stress, ring, bolts) was found;
//! the skirt test below is a hand calculation written out in the test.

mod common;

use common::examples::example;
use vesselcad::calc::legs::allowable_axial;
use vesselcad::calc::seismic::{Mass, coefficient, forces, shear_and_moment};
use vesselcad::calc::skirt::bolt_load;
use vesselcad::calc::wind::kz;
use vesselcad::calc::{MaterialTable, calculate};
use vesselcad::design::{self, Design, Exposure, PartDesign, SeismicDesign, WindDesign};
use vesselcad::mesh::TessellationOptions;
use vesselcad::model::{Edit, Model};

fn close(got: f64, want: f64, tol: f64, what: &str) {
    assert!(
        (got - want).abs() <= tol,
        "{what}: got {got}, want {want} ± {tol}"
    );
}

#[test]
fn kz_matches_asce7_table_26_10_1() {
    let feet = [
        15.0, 20.0, 25.0, 30.0, 40.0, 50.0, 60.0, 70.0, 80.0, 90.0, 100.0, 120.0, 140.0, 160.0,
        180.0, 200.0, 250.0, 300.0, 350.0, 400.0, 450.0, 500.0,
    ];
    let table = [
        (
            Exposure::B,
            [
                0.57, 0.62, 0.66, 0.70, 0.76, 0.81, 0.85, 0.89, 0.93, 0.96, 0.99, 1.04, 1.09, 1.13,
                1.17, 1.20, 1.28, 1.35, 1.41, 1.47, 1.52, 1.56,
            ],
        ),
        (
            Exposure::C,
            [
                0.85, 0.90, 0.94, 0.98, 1.04, 1.09, 1.13, 1.17, 1.21, 1.24, 1.26, 1.31, 1.36, 1.39,
                1.43, 1.46, 1.53, 1.59, 1.64, 1.69, 1.73, 1.77,
            ],
        ),
        (
            Exposure::D,
            [
                1.03, 1.08, 1.12, 1.16, 1.22, 1.27, 1.31, 1.34, 1.38, 1.40, 1.43, 1.48, 1.52, 1.55,
                1.58, 1.61, 1.68, 1.73, 1.78, 1.82, 1.86, 1.89,
            ],
        ),
    ];
    for (exposure, values) in table {
        for (ft, want) in feet.iter().zip(values) {
            // Printed to two decimals, some rounded and some cut (C at 60 ft:
            // 2.01·(60/900)^(2/9.5) = 1.1366, printed 1.13): the formula lies
            // within [printed − 0.005, printed + 0.01).
            let got = kz(exposure, ft * 304.8);
            assert!(
                want - 0.005 <= got && got < want + 0.01,
                "Kz {exposure:?} at {ft} ft: {got} against the table's {want}"
            );
        }
        // Below 15 ft, Kz of 15 ft (Table 26.10-1, note 1).
        assert_eq!(kz(exposure, 1000.0), kz(exposure, 15.0 * 304.8));
    }
}

#[test]
fn seismic_coefficient_matches_a_published_example() {
    let s = SeismicDesign {
        sds: 2.84,
        sd1: 1.21,
        response_modification: 3.0,
        importance: Some(1.25),
        period: Some(0.137),
    };
    let c = coefficient(&s);
    close(c.cs, 1.18, 0.005, "Cs");
    assert_eq!(c.equation, "12.8-2");
    close(1.21 / (0.137 * 3.0 / 1.25), 3.68, 0.005, "12.8-3 cap");
    assert_eq!(c.k, 1.0, "T ≤ 0.5 s");
    // Without the period: the plateau and k = 2.
    let c = coefficient(&SeismicDesign { period: None, ..s });
    close(c.cs, 2.84 / (3.0 / 1.25), 1e-12, "plateau");
    assert_eq!(c.k, 2.0);
    // A long period: 12.8-3 governs; a tiny SDS: 15.4-1's floor 0.03.
    let c = coefficient(&SeismicDesign {
        period: Some(3.0),
        ..s
    });
    assert_eq!((c.equation, c.k), ("12.8-3", 2.0));
    let c = coefficient(&SeismicDesign {
        sds: 0.1,
        sd1: 0.05,
        response_modification: 8.0,
        importance: None,
        period: None,
    });
    assert_eq!((c.cs, c.equation), (0.03, "15.4-1"));
}

#[test]
fn vertical_distribution_matches_a_published_printout() {
    // Heights in ft, weights in kips: Fx depends on ratios only.
    let masses = [
        Mass::Point {
            h: 17.0,
            mass: 20.90,
        },
        Mass::Point {
            h: 8.0,
            mass: 41.40,
        },
    ];
    let v = 9.58;
    let f = forces(v, 1.0, &masses);
    close(f[0], 4.96, 0.005, "F2");
    close(f[1], 4.62, 0.005, "F1");
    let (shear, moment) = shear_and_moment(v, 1.0, &masses, 0.0);
    close(shear, 9.58, 1e-12, "base shear");
    close(moment, 121.3, 0.05, "base moment, k-ft");
    // A uniform mass of a cantilever: k = 1 puts the resultant at 2/3 of the
    // height, k = 2 at 3/4.
    let bar = [Mass::Uniform {
        h0: 0.0,
        h1: 30.0,
        mass: 5.0,
    }];
    close(
        shear_and_moment(1.0, 1.0, &bar, 0.0).1,
        20.0,
        1e-12,
        "k = 1",
    );
    close(
        shear_and_moment(1.0, 2.0, &bar, 0.0).1,
        22.5,
        1e-12,
        "k = 2",
    );
    // Above half height: shear (1 − 0.5²) of V for k = 1.
    close(
        shear_and_moment(1.0, 1.0, &bar, 15.0).0,
        0.75,
        1e-12,
        "shear at mid",
    );
}

#[test]
fn anchor_bolt_load_matches_a_published_report() {
    // PV Elite: wind operating, corroded: W 7 839.42 kg, M 1 369 kgf·m, 12
    // bolts on a 1.546 m circle, 0.6·W.
    // (M is printed to 1 kgf·m: ± 0.015 kgf on P.)
    let p = bolt_load(12, 1.546, 1369.0, 0.6 * 7839.42);
    close(p, -96.81, 0.015, "P per bolt, kgf");
}

#[test]
fn aisc_column_allowable_stress() {
    // Cc = √(2π²E/Fy) with E = 29 000 ksi: 126.1 at Fy 36, 107.0 at Fy 50; at Cc
    // both ASD formulas give 6/23·Fy; beyond it Fa ≈ 150 000/(KL/r)².
    for (fy, cc) in [(36.0, 126.1), (50.0, 107.0)] {
        let below = allowable_axial(cc - 0.05, fy, 29_000.0);
        let above = allowable_axial(cc + 0.05, fy, 29_000.0);
        close(below, 6.0 / 23.0 * fy, 0.02, "E2-1 at Cc");
        close(above, 6.0 / 23.0 * fy, 0.02, "E2-2 at Cc");
    }
    close(
        allowable_axial(150.0, 36.0, 29_000.0),
        150_000.0 / 150.0f64.powi(2),
        0.04,
        "E2-2",
    );
    // E2-1 at KL/r = 0: Fy / (5/3).
    close(allowable_axial(0.0, 36.0, 29_000.0), 21.6, 1e-9, "Fa at 0");
}

fn column(wind: Option<WindDesign>, seismic: Option<SeismicDesign>, bolts: Option<u32>) -> Design {
    let mut d = example("vertical-column");
    let v = &mut d.vessels[0];
    v.design.wind = wind.map(Box::new);
    v.design.seismic = seismic.map(Box::new);
    for p in &mut v.parts {
        if let PartDesign::Skirt(s) = p {
            s.anchor_bolts = bolts;
        }
    }
    d
}

fn wind45() -> WindDesign {
    WindDesign {
        speed: 45.0,
        exposure: Exposure::C,
        importance: None,
        topographic_factor: None,
        directionality_factor: None,
        gust_factor: None,
        force_coefficient: None,
        area_factor: Some(1.2),
        base_elevation: Some(2000.0),
    }
}

/// The column's skirt under wind: the wind moment at the base against a hand
/// integration, and the skirt's stresses against the formulas written out.
#[test]
fn skirt_under_wind_and_earthquake() {
    let d = column(
        Some(wind45()),
        Some(SeismicDesign {
            sds: 0.5,
            sd1: 0.2,
            response_modification: 2.0,
            importance: None,
            period: None,
        }),
        Some(12),
    );
    let r = design::resolve(&d).unwrap();
    let c = calculate(&d.vessels[0], &r[0], &MaterialTable::builtin());
    let v = &c.vessel;
    let lat = v.lateral.as_ref().expect("lateral figures");
    let (shear, moment, _) = lat.wind.unwrap();
    // Hand integration: 1 mm slices of every band, qz·G·Cf·1.2·OD.
    let mut hand = (0.0, 0.0);
    let f = vesselcad::calc::wind::WindFactors::of(&wind45());
    let base = lat.base_elevation;
    assert_eq!(base, 2000.0);
    for p in &r[0].parts {
        use vesselcad::constraints::PartGeometry as G;
        let od = match &p.geometry {
            G::Shell(s) => s.outside_diameter,
            G::Head(h) => h.outside_diameter,
            G::Reducer(x) => x.large_diameter,
            G::Skirt(s) => s.top_diameter,
            _ => continue,
        };
        // Heights above grade: the skirt's base stands 2 m above it.
        let (lo, hi) = (p.span.0.min(p.span.1), p.span.0.max(p.span.1));
        let (z0, z1) = (lo - r[0].extent.0 + 2000.0, hi - r[0].extent.0 + 2000.0);
        let n = ((z1 - z0) as usize).max(1);
        let dz = (z1 - z0) / n as f64;
        for i in 0..n {
            let z = z0 + (i as f64 + 0.5) * dz;
            let force = f.pressure(z) * 1.2 * od * dz * 1e-6;
            hand.0 += force;
            hand.1 += force * (z - base);
        }
    }
    close(shear, hand.0, 1e-6 * hand.0, "wind shear");
    close(moment, hand.1, 1e-6 * hand.1, "wind moment");
    let (cs, eq, k, vs, _) = lat.seismic.unwrap();
    assert_eq!((cs, eq, k), (0.25, "12.8-2", 2.0));
    let w = vesselcad::weights::weights(&d.vessels[0], &r[0]).unwrap();
    close(vs, 0.25 * w.operating * vesselcad::calc::GRAVITY, 1e-6, "V");
    // The skirt at its base in D + 0.6W: σ = 4M/(π·D²·t) ± W/(π·D·t).
    let s = &v.skirts[0];
    let case = s
        .cases
        .iter()
        .find(|c| c.plane == "base" && c.load.name == "D + 0.6W (operating)")
        .unwrap();
    let (dm, t) = (s.base_diameter, s.thickness);
    let pi = std::f64::consts::PI;
    let m = 0.6 * moment;
    let weight = w.operating * vesselcad::calc::GRAVITY;
    close(case.load.moment, m, 1e-6 * m, "0.6·M");
    close(
        case.checks[1].stress,
        4.0 * m / (pi * dm * dm * t) + weight / (pi * dm * t),
        1e-9,
        "compression",
    );
    close(
        case.checks[0].stress,
        4.0 * m / (pi * dm * dm * t) - weight / (pi * dm * t),
        1e-9,
        "tension",
    );
    // Anchor bolts: the largest of the combinations at the base.
    let worst = s
        .cases
        .iter()
        .filter(|c| c.plane == "base")
        .map(|c| bolt_load(12, s.bolt_circle, c.load.moment, c.load.weight))
        .fold(f64::NEG_INFINITY, f64::max);
    close(s.bolt_load, worst, 1e-9, "bolt load");
    assert!(s.ring_required.unwrap() > 0.0);
}

/// No wind or earthquake: the skirt still carries the operating and hydrotest
/// weights, with no lateral combination.
#[test]
fn skirt_under_weight_only() {
    let d = column(None, None, None);
    let r = design::resolve(&d).unwrap();
    let c = calculate(&d.vessels[0], &r[0], &MaterialTable::builtin());
    let s = &c.vessel.skirts[0];
    assert!(s.cases.iter().all(|c| !c.load.lateral));
    assert!(s.bolt_load < 0.0, "nothing lifts under weight alone");
    assert!(c.vessel.lateral.as_ref().unwrap().wind.is_none());
}

/// Legs and lugs under wind: reactions from statics, the leg's interaction.
#[test]
fn legs_and_lugs_under_wind() {
    let mut d: Design = serde_json::from_str(
        r#"{"format": "vesselcad/1", "vessels": [{"tag": "V-1", "kind": "vertical",
            "design": {"pressure": 500, "temperature": 100, "material": "SA-516-70",
                       "corrosion_allowance": 1.5,
                       "wind": {"speed": 40, "exposure": "C"}},
            "parts": [
              {"legs": {"id": "L", "count": 4, "size": 4, "length": 1200}},
              {"head": {"id": "H1", "shape": "ellipsoidal", "thickness": 8}},
              {"shell": {"id": "S1", "od": 1200, "length": 3000, "thickness": 8}},
              {"head": {"id": "H2", "shape": "ellipsoidal", "thickness": 8}}
            ]}]}"#,
    )
    .unwrap();
    design::validate(&d).unwrap();
    let r = design::resolve(&d).unwrap();
    let c = calculate(&d.vessels[0], &r[0], &MaterialTable::builtin());
    let legs = &c.vessel.legs[0];
    let case = legs
        .cases
        .iter()
        .find(|c| c.load.name == "D + 0.6W (operating)")
        .unwrap();
    let n = 4.0;
    close(
        case.reaction,
        case.load.weight / n + 4.0 * case.load.moment / (n * legs.circle),
        1e-9,
        "leg reaction",
    );
    close(
        legs.circle,
        1200.0 + 114.3,
        1e-9,
        "leg circle: shell OD + NPS 4 OD",
    );
    assert!(
        case.check.stress > 0.0 && case.check.stress < 1.0,
        "{case:?}"
    );
    // Lugs on the same vessel instead of legs.
    d.vessels[0].parts[0] = serde_json::from_str(
        r#"{"lugs": {"id": "LG", "count": 4, "elevation": 2000, "height": 300,
                     "projection": 200, "width": 150}}"#,
    )
    .unwrap();
    let r = design::resolve(&d).unwrap();
    let c = calculate(&d.vessels[0], &r[0], &MaterialTable::builtin());
    let lugs = &c.vessel.lugs[0];
    assert!(lugs.reaction > 0.0);
    assert_eq!(lugs.checks.len(), 2);
}

/// Live: a wind edit recalculates the vessel's figures and supports, no part
/// or nozzle, and the model equals the pure calculation.
#[test]
fn a_wind_edit_recalculates_the_supports_only() {
    let mut m = Model::from_design(
        &column(Some(wind45()), None, Some(12)),
        TessellationOptions::chord(5.0),
    )
    .unwrap();
    let fresh = |m: &Model| {
        let d = m.design();
        let r = design::resolve(&d).unwrap();
        calculate(&d.vessels[0], &r[0], &MaterialTable::builtin())
    };
    let tag = m.design().vessels[0].tag.clone();
    let before = m.calculation(&tag).unwrap();
    assert_eq!(before, fresh(&m));
    let mut v = m.design().vessels[0].clone();
    v.design.wind = Some(Box::new(WindDesign {
        speed: 60.0,
        ..wind45()
    }));
    let counters = m.edit(Edit::SetVessel(v)).unwrap();
    assert_eq!(counters.parts_calculated, 0, "{counters:?}");
    assert_eq!(counters.nozzles_calculated, 0, "{counters:?}");
    assert_eq!(counters.vessels_calculated, 1, "{counters:?}");
    assert_eq!(counters.supports_calculated, 1, "{counters:?}");
    let after = m.calculation(&tag).unwrap();
    assert_eq!(after, fresh(&m));
    let moment =
        |c: &vesselcad::calc::Calculation| c.vessel.lateral.as_ref().unwrap().wind.unwrap().1;
    let ratio = moment(&after) / moment(&before);
    close(ratio, (60.0f64 / 45.0).powi(2), 1e-9, "M ∝ V²");
    // A pressure edit still recalculates the parts.
    let mut v = m.design().vessels[0].clone();
    v.design.pressure = v.design.pressure.map(|p| p * 0.9);
    let counters = m.edit(Edit::SetVessel(v)).unwrap();
    assert!(counters.parts_calculated > 0, "{counters:?}");
    assert_eq!(m.calculation(&tag).unwrap(), fresh(&m));
}

/// The base ring has its own thickness (`base_ring_thickness`, default the
/// skirt's): the column's 12 mm skirt with a 12 mm ring 150 mm wide is short of
/// the t = l·√(3·fc/S) its bearing needs (17.0 mm), a 25 mm ring holds, and the
/// ring's extra 13 mm is in the weight: π·(1150² − 1000²)·13 mm³ of steel.
#[test]
fn the_base_ring_has_its_own_thickness() {
    let mut thin = column(None, None, None);
    let mut thick = thin.clone();
    for (d, t) in [(&mut thin, None), (&mut thick, Some(25.0))] {
        for p in &mut d.vessels[0].parts {
            if let PartDesign::Skirt(s) = p {
                s.base_ring_thickness = t;
            }
        }
    }
    let table = MaterialTable::builtin();
    let calc = |d: &Design| {
        let r = design::resolve(d).unwrap();
        let c = calculate(&d.vessels[0], &r[0], &table);
        let w = vesselcad::weights::weights(&d.vessels[0], &r[0]).unwrap();
        (c, w)
    };
    let (c12, w12) = calc(&thin);
    let (c25, w25) = calc(&thick);
    let (s12, s25) = (&c12.vessel.skirts[0], &c25.vessel.skirts[0]);
    assert_eq!((s12.ring_thickness, s25.ring_thickness), (12.0, 25.0));
    let need = s12.ring_required.unwrap();
    assert!(need > 12.0 && need < 25.0, "required ring {need} mm");
    // The thicker ring weighs on its own bearing: a little more is needed.
    let need25 = s25.ring_required.unwrap();
    assert!(need25 > need && need25 < 25.0, "{need} -> {need25} mm");
    let ring = |c: &vesselcad::calc::Calculation| {
        c.vessel
            .deficiencies
            .iter()
            .filter(|d| d.contains("SK: base ring needs"))
            .count()
    };
    assert_eq!(ring(&c12), 1, "{:?}", c12.vessel.deficiencies);
    assert_eq!(ring(&c25), 0, "{:?}", c25.vessel.deficiencies);
    let pi = std::f64::consts::PI;
    let extra = pi * (1150.0f64.powi(2) - 1000.0f64.powi(2)) * 13.0 * 1e-9 * w12.metal_density;
    close(w25.empty - w12.empty, extra, 1e-6 * extra, "ring mass");
}

/// A ring thickness without a ring, or not a positive length, is refused with
/// its path.
#[test]
fn a_base_ring_thickness_needs_a_ring() {
    for (width, t) in [(0.0, 20.0), (150.0, 0.0), (150.0, f64::NAN)] {
        let mut d = column(None, None, None);
        for p in &mut d.vessels[0].parts {
            if let PartDesign::Skirt(s) = p {
                s.base_ring_width = width;
                s.base_ring_thickness = Some(t);
            }
        }
        let e = design::resolve(&d).unwrap_err().to_string();
        assert!(
            e.contains("vessels[0].parts[0].skirt.base_ring_thickness")
                && e.contains("base_ring_width > 0"),
            "{width} {t}: {e}"
        );
    }
}
