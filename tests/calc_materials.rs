//! The materials table (`vesselcad::calc::materials`): the built-in table holds
//! every specification issue 33 asks for with sourced values, its allowable
//! stresses follow the II-D rule S = min(UTS/3.5, 2/3·Sy) they claim, lookup by
//! alias, interpolation and its range error, and a user's table from a path.

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
    // The built-in table stops at the II-D room-temperature column (SA-516-60)
    // or at 343 °C, where II-D's SA-516-70 values start to fall.
    let table = MaterialTable::builtin();
    let e = table
        .get("SA-516-60")
        .unwrap()
        .allowable_stress(150.0)
        .unwrap_err();
    assert!(e.to_string().contains("-29 to 38 °C"), "{e}");
    let sa516 = table.get("SA-516-70").unwrap();
    let e = sa516.allowable_stress(350.0).unwrap_err();
    assert!(e.to_string().contains("-29 to 343 °C"), "{e}");
}

/// ASME II-D Table 1A: SA-516-70 at 20.0 ksi (137.9 MPa) from −20 °F to 650 °F
/// (source quoted in `data/materials.json`); the shipped 138.5 MPa is the
/// rule's min(485/3.5, 2/3·260) at room temperature, within 0.5 % of it.
#[test]
fn sa516_70_holds_its_stress_to_650_f() {
    let sa516 = MaterialTable::builtin().get("SA-516-70").unwrap().clone();
    for t in [-29.0, 20.0, 120.0, 180.0, 343.0] {
        let s = sa516.allowable_stress(t).unwrap();
        assert_eq!(s, 138.5, "{t} °C");
        assert!((s - 20.0 * 6.894_757).abs() / s < 0.005);
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
