//! The materials table (`vesselcad::calc::materials`): the built-in table holds
//! every specification issue 33 asks for with sourced values, its allowable
//! stresses follow the II-D rule S = min(UTS/3.5, 2/3·Sy) at room temperature and
//! Mandatory Appendix 1 with the Table Y-1/U trends at temperature, meet the
//! published Table 1A rows, lookup by alias, interpolation and its range error
//! naming the limit, and a user's table from a path.

use std::io::Write;

use vesselcad::calc::{CalcError, MaterialTable};

const REQUIRED: [&str; 12] = [
    "SA-516-70",
    "SA-516-60",
    "SA-285-C",
    "SA-240-304",
    "SA-240-304L",
    "SA-240-316",
    "SA-240-316L",
    "SA-106-B",
    "SA-105",
    "SA-182-F316L",
    "SA-36",
    "SA-283-C",
];

#[test]
fn builtin_table_has_every_material_with_sources() {
    let table = MaterialTable::builtin();
    for name in REQUIRED {
        let m = table.get(name).unwrap();
        for source in [
            &m.tensile_strength.source,
            &m.yield_strength.source,
            &m.density.source,
            &m.modulus.source,
            &m.allowable_stress.source,
        ] {
            assert!(source.len() > 20, "{name}: source {source:?}");
        }
        // The derivation the source claims: S = min(UTS/3.5, 2/3·Sy), rounded down
        // to 0.1 MPa; or ASME II-D Table 1A's own values, which II-D derives by the
        // same rule from the customary (ksi) minimums, so within 1 % of it.
        let rule = (m.tensile_strength.value / 3.5).min(m.yield_strength.value * 2.0 / 3.0);
        let s = m.allowable_stress(20.0).unwrap();
        let source = &m.allowable_stress.source;
        if source.starts_with("ASME II-D Table 1A") {
            assert!(
                (s - rule).abs() / rule < 0.01,
                "{name}: S {s} vs rule {rule}"
            );
        } else {
            assert!(
                s <= rule && rule - s < 0.1 + 1e-9,
                "{name}: S {s} vs rule {rule}"
            );
            assert!(source.contains("min(UTS/3.5, 2/3 Sy)"));
        }
    }
    let sa516 = table.get("SA-516-70").unwrap();
    assert_eq!(sa516.tensile_strength.value, 485.0);
    assert_eq!(sa516.b16_5_group.as_ref().unwrap().value, "1.1");
    assert_eq!(table.get("SA-240-316L").unwrap().density.value, 8000.0);
}

#[test]
fn lookup_by_alias_and_unknown_names() {
    let table = MaterialTable::builtin();
    assert_eq!(table.get("a516-70").unwrap().name, "SA-516-70");
    assert_eq!(table.get("SA 516 70").unwrap().name, "SA-516-70");
    assert_eq!(table.get("A36").unwrap().name, "SA-36");
    let e = table.get("unobtainium").unwrap_err();
    assert!(matches!(e, CalcError::UnknownMaterial { .. }));
    assert!(e.to_string().contains("SA-516-70"), "{e}");
}

#[test]
fn stress_interpolates_and_refuses_to_extrapolate() {
    let json = r#"{"format": "vesselcad-materials/1", "materials": [{
        "name": "X-1",
        "tensile_strength": {"value": 485, "source": "test"},
        "yield_strength": {"value": 260, "source": "test"},
        "density": {"value": 7850, "source": "test"},
        "modulus": {"value": 200000, "source": "test"},
        "allowable_stress": {"points": [[20, 138], [100, 130], [300, 110]], "source": "test"}
    }]}"#;
    let mut file = tempfile::NamedTempFile::new().unwrap();
    file.write_all(json.as_bytes()).unwrap();
    let table = MaterialTable::from_path(file.path()).unwrap();
    let m = table.get("X-1").unwrap();
    assert_eq!(m.allowable_stress(20.0).unwrap(), 138.0);
    assert!((m.allowable_stress(60.0).unwrap() - 134.0).abs() < 1e-12);
    assert!((m.allowable_stress(200.0).unwrap() - 120.0).abs() < 1e-12);
    assert_eq!(m.allowable_stress(300.0).unwrap(), 110.0);
    let e = m.allowable_stress(301.0).unwrap_err();
    let text = e.to_string();
    assert!(
        text.contains("X-1") && text.contains("temperature = 301"),
        "{text}"
    );
    assert!(text.contains("20 to 300 °C"), "{text}");
    // The built-in tables stop at the material's Code limit or at the end of the
    // range their derivation is valid in, and say so.
    let table = MaterialTable::builtin();
    let e = table
        .get("SA-283-C")
        .unwrap()
        .allowable_stress(350.0)
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("-29 to 343.33 °C") && e.contains("Table 1A") && e.contains("650 F (343 C)"),
        "{e}"
    );
    let e = table
        .get("SA-240-316L")
        .unwrap()
        .allowable_stress(460.0)
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("-29 to 454.44 °C") && e.contains("850 F (454 C)") && e.contains("route (b)"),
        "{e}"
    );
    let e = table
        .get("SA-516-70")
        .unwrap()
        .allowable_stress(540.0)
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("-29 to 537.78 °C") && e.contains("1000 F"),
        "{e}"
    );
    // Below the table the message is the plain one.
    let e = table
        .get("SA-516-70")
        .unwrap()
        .allowable_stress(-30.0)
        .unwrap_err()
        .to_string();
    assert!(e.contains("give a licensed table"), "{e}");
}

/// ASME II-D Table 1A (customary, 3.5 margin) rows of the carbon steels as a
/// public C# stress-table importer on GitHub reproduces them, ksi at −20…100,
/// 150, 200, 300, 400, 500, 600, 650, 700, 750, 800, 850, 900, 950, 1000 °F.
/// Below the time-dependent range the shipped S is derived (route (b): II-D
/// Mandatory Appendix 1 with the public Table Y-1 trend ratios, from the metric
/// ASTM minimums, which differ from the customary ones by up to 0.8 %), so it
/// meets the printed value within 1 %, not to its 0.1 ksi; in the creep range
/// (from the first entry below the yield-based value) it is the printed entry
/// converted and rounded down to 0.1 MPa, so within 0.1 MPa of it and never above.
/// The old table held SA-516-70 at 138.5 MPa to 343 °C, 6.9 % above the 18.8 ksi
/// (129.6 MPa) printed for 650 °F.
#[test]
fn carbon_steels_at_temperature_meet_table_1a() {
    const F: [f64; 15] = [
        100.0, 150.0, 200.0, 300.0, 400.0, 500.0, 600.0, 650.0, 700.0, 750.0, 800.0, 850.0, 900.0,
        950.0, 1000.0,
    ];
    // (material, printed row, first creep-range column)
    let rows: [(&str, &[f64], f64); 6] = [
        (
            "SA-516-70",
            &[
                20.0, 20.0, 20.0, 20.0, 20.0, 20.0, 19.4, 18.8, 18.1, 14.8, 12.0, 9.3, 6.7, 4.0,
                2.5,
            ],
            750.0,
        ),
        (
            "SA-516-60",
            &[
                17.1, 17.1, 17.1, 17.1, 17.1, 17.1, 16.4, 15.8, 15.3, 13.0, 10.8, 8.7, 5.9, 4.0,
                2.5,
            ],
            750.0,
        ),
        (
            "SA-106-B",
            &[
                17.1, 17.1, 17.1, 17.1, 17.1, 17.1, 17.1, 17.1, 15.6, 13.0, 10.8, 8.7, 5.9, 4.0,
                2.5,
            ],
            700.0,
        ),
        (
            "SA-105",
            &[
                20.0, 20.0, 20.0, 20.0, 20.0, 19.6, 18.4, 17.8, 17.2, 14.8, 12.0, 9.3, 6.7, 4.0,
                2.5,
            ],
            750.0,
        ),
        (
            "SA-285-C",
            &[
                15.7, 15.7, 15.7, 15.7, 15.7, 15.7, 15.3, 14.8, 14.3, 13.0, 10.8, 8.7, 5.9,
            ],
            750.0,
        ),
        (
            "SA-283-C",
            &[15.7, 15.7, 15.7, 15.7, 15.7, 15.7, 15.3, 14.8],
            2000.0,
        ),
    ];
    let table = MaterialTable::builtin();
    let mut worst: f64 = 0.0;
    for (name, row, creep) in rows {
        let m = table.get(name).unwrap();
        for (&f, &ksi) in F.iter().zip(row) {
            // The tables give the Fahrenheit columns in °C to 0.01 °C.
            let t = ((f - 32.0) / 1.8 * 100.0).round() / 100.0;
            let s = m.allowable_stress(t).unwrap();
            let printed = ksi * 6.894_757;
            if f >= creep {
                assert!(
                    s <= printed + 1e-9 && printed - s < 0.1,
                    "{name} {f} F: {s} MPa vs printed {ksi} ksi = {printed} MPa"
                );
            } else {
                let d = (s - printed) / printed;
                worst = worst.max(d.abs());
                assert!(
                    d.abs() < 0.01,
                    "{name} {f} F: {s} MPa vs printed {ksi} ksi ({d:+.4})"
                );
            }
        }
    }
    eprintln!(
        "time-independent range: worst {:.2} % from Table 1A",
        worst * 100.0
    );
    // The allowable falls from 650 F on where Table 1A's does.
    let sa516 = table.get("SA-516-70").unwrap();
    assert!(sa516.allowable_stress(343.33).unwrap() < 130.0);
}

/// Route (b) recomputed here from the public Table Y-1 and U rows (metric, MPa at
/// 40, 100, 200, 300, 400, 450 °C) the built-in table cites: SA-240 316L yield
/// 172, 145, 121, 109, 101, 97.5 and tensile 483, 467, 429, 426, 421, 413; SA-106
/// B yield 241, 220, 207, 188 (tensile flat at 414 to 375 °C). S = min(UTS/3.5,
/// 1.1·UTS·Rt/3.5, 2/3·Sy, 2/3·Sy·Ry) with Ry = Y(T)/Y(40), Rt = U(T)/U(40),
/// rounded down to 0.1 MPa, is what the table ships at those temperatures.
/// The same rule with SA-240 304's rows (yield 207, 170, 144, 129, 118 MPa,
/// tensile 517, 485, 442, 437, 436) reproduces its published Table 1A lower row
/// (shipped) within 2 %, below it (the metric 205 MPa yield is 0.8 % under 30 ksi).
#[test]
fn derived_allowables_follow_appendix_1() {
    let table = MaterialTable::builtin();
    let rule = |uts: f64, sy: f64, y: f64, y40: f64, u: f64, u40: f64| {
        let s = (uts / 3.5)
            .min(1.1 * uts * u / u40 / 3.5)
            .min(2.0 / 3.0 * sy)
            .min(2.0 / 3.0 * sy * y / y40);
        (s * 10.0 + 1e-9).floor() / 10.0
    };
    let m = table.get("SA-240-316L").unwrap();
    for (t, y, u) in [
        (100.0, 145.0, 467.0),
        (200.0, 121.0, 429.0),
        (300.0, 109.0, 426.0),
        (400.0, 101.0, 421.0),
        (450.0, 97.5, 413.0),
    ] {
        let want = rule(485.0, 170.0, y, 172.0, u, 483.0);
        let got = m.allowable_stress(t).unwrap();
        assert!((got - want).abs() < 1e-9, "316L {t} °C: {got} vs {want}");
    }
    assert_eq!(
        table.get("SA-182-F316L").unwrap().allowable_stress.points,
        m.allowable_stress.points
    );
    let m = table.get("SA-106-B").unwrap();
    for (t, y) in [(100.0, 220.0), (200.0, 207.0), (300.0, 188.0)] {
        let want = rule(415.0, 240.0, y, 241.0, 414.0, 414.0);
        let got = m.allowable_stress(t).unwrap();
        assert!((got - want).abs() < 1e-9, "106 B {t} °C: {got} vs {want}");
    }
    let m = table.get("SA-240-304").unwrap();
    for (t, y, u) in [
        (100.0, 170.0, 485.0),
        (200.0, 144.0, 442.0),
        (300.0, 129.0, 437.0),
        (400.0, 118.0, 436.0),
    ] {
        let derived = rule(515.0, 205.0, y, 207.0, u, 517.0);
        let published = m.allowable_stress(t).unwrap();
        let d = (derived - published) / published;
        assert!(
            (-0.02..=0.0).contains(&d),
            "304 {t} °C: derived {derived}, Table 1A {published}"
        );
    }
}

/// ASME II-D Table 1A, SA-240 Type 304 plate, the lower (non-G5) column, as a
/// public pressure-vessel script on GitHub reproduces it (array
/// "SA-240g304plateNP", ksi at 100, 200, 300, … 1500 °F: 20.0, 16.7, 15.0, 13.8,
/// 12.9, 12.3, 12.0, 11.7, 11.5, 11.2, …, 1.4): S at 200 °F (93.33 °C) = 16.7 ksi
/// = 115.14 MPa, at 650 °F (343.33 °C) 12.0 ksi = 82.74 MPa, at 1500 °F (815.56 °C)
/// 1.4 ksi = 9.65 MPa, each shipped rounded down to 0.1 MPa. Between points the
/// stress is linear in temperature: at 121.11 °C (250 °F), halfway from 200 to
/// 300 °F, (115.1 + 103.4)/2 = 109.25 MPa. Above 1500 °F it is refused.
#[test]
fn sa240_304_stress_at_temperature_from_ii_d() {
    let m = MaterialTable::builtin().get("SA-240-304").unwrap().clone();
    let ksi = |t_f: f64| m.allowable_stress((t_f - 32.0) / 1.8).unwrap() / 6.894_757;
    for (t_f, want) in [
        (70.0, 20.0),
        (100.0, 20.0),
        (200.0, 16.7),
        (300.0, 15.0),
        (400.0, 13.8),
        (500.0, 12.9),
        (600.0, 12.3),
        (650.0, 12.0),
        (700.0, 11.7),
        (800.0, 11.2),
        (1000.0, 10.4),
        (1500.0, 1.4),
    ] {
        let got = ksi(t_f);
        assert!(
            got <= want && want - got < 0.1 / 6.894_757,
            "{t_f} F: {got} ksi, II-D {want}"
        );
    }
    assert!((m.allowable_stress(-29.0).unwrap() - 137.8).abs() < 1e-12);
    let mid = m.allowable_stress((250.0 - 32.0) / 1.8).unwrap();
    assert!((mid - 109.25).abs() < 1e-3, "{mid}");
    let e = m.allowable_stress(820.0).unwrap_err().to_string();
    assert!(
        e.contains("SA-240-304") && e.contains("temperature = 820") && e.contains("815.56"),
        "{e}"
    );
    assert!(m.allowable_stress.source.contains("Note G5"));
}

#[test]
fn bad_tables_name_path_and_rule() {
    let e = MaterialTable::from_path(std::path::Path::new("/nonexistent/m.json")).unwrap_err();
    assert!(e.to_string().contains("/nonexistent/m.json"), "{e}");
    let e =
        MaterialTable::from_json("m.json", r#"{"format": "other", "materials": []}"#).unwrap_err();
    assert!(e.to_string().contains("vesselcad-materials/1"), "{e}");
    let unsorted = r#"{"format": "vesselcad-materials/1", "materials": [{
        "name": "X-2",
        "tensile_strength": {"value": 485, "source": "t"},
        "yield_strength": {"value": 260, "source": "t"},
        "density": {"value": 7850, "source": "t"},
        "modulus": {"value": 200000, "source": "t"},
        "allowable_stress": {"points": [[100, 130], [20, 138]], "source": "t"}
    }]}"#;
    let e = MaterialTable::from_json("m.json", unsorted).unwrap_err();
    let text = e.to_string();
    assert!(
        text.contains("m.json") && text.contains("materials[0] (X-2)"),
        "{text}"
    );
    let typo = r#"{"format": "vesselcad-materials/1", "materials": [{"name": "X", "densty": 1}]}"#;
    let e = MaterialTable::from_json("m.json", typo).unwrap_err();
    assert!(e.to_string().contains("materials[0]"), "{e}");
}
