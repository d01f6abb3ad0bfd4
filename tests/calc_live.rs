//! The code calculations live in the pipeline: the model's calculation components
//! equal the pure `calc::calculate` of its design after any edit, and an edit
//! recomputes only what it touches (work counters): a nozzle edit that nozzle and
//! its host, a pressure edit its vessel, a liquid level its vessel.

mod common;

use common::examples::example;
use vesselcad::calc::{Calculation, MaterialTable, calculate};
use vesselcad::design::{self, PartDesign};
use vesselcad::mesh::TessellationOptions;
use vesselcad::model::{Edit, Model};

fn model(name: &str) -> Model {
    Model::from_design(&example(name), TessellationOptions::chord(5.0)).unwrap()
}

/// The pure calculation of vessel `tag` of the model's current design.
fn fresh(m: &Model, tag: &str) -> Calculation {
    let d = m.design();
    let resolved = design::resolve(&d).unwrap();
    let i = d.vessels.iter().position(|v| v.tag == tag).unwrap();
    calculate(&d.vessels[i], &resolved[i], &MaterialTable::builtin())
}

fn assert_live(m: &Model, tag: &str) {
    assert_eq!(m.calculation(tag).unwrap(), fresh(m, tag), "{tag}");
}

#[test]
fn every_vessel_is_calculated_on_the_first_update() {
    let m = model("small-plant");
    for v in m.design().vessels {
        assert_live(&m, &v.tag);
    }
    let drum = m.calculation("V-101").unwrap();
    // SA-516-70 at 120 °C, 1000 kPa, CA 3, E 0.85 (default): every wall holds.
    assert!(
        drum.parts.iter().all(|p| p.deficiency.is_none()),
        "{drum:#?}"
    );
    // UG-45 t_b3 is the standard wall less 12.5 % plus the corrosion allowance,
    // which a standard-wall neck cannot meet with 3 mm of corrosion; the
    // example's manway neck is NPS 24 Sch 40: 0.875 · 17.48 = 15.295 mm
    // available against 0.875 · 9.53 + 3 = 11.34 mm required.
    let m1 = drum.nozzles.iter().find(|n| n.mark == "M1").unwrap();
    assert!((m1.t_b3 - 11.338_75).abs() < 1e-9 && (m1.available - 15.295).abs() < 1e-9);
    assert!(m1.deficiency.is_none(), "{m1:?}");
    assert!(drum.vessel.mawp.unwrap() > 1.0, "{:?}", drum.vessel.mawp);
    assert_eq!(
        drum.parts.len(),
        3,
        "two heads and a course: {:?}",
        drum.parts
    );
    assert_eq!(drum.nozzles.len(), 8);
    // A storage tank is API 650's: its course by the one-foot method, its bottom
    // and roof plates not calculated — said, not guessed.
    let tank = m
        .design()
        .vessels
        .iter()
        .find(|v| v.kind == vesselcad::design::VesselKind::Tank)
        .unwrap()
        .tag
        .clone();
    let t = m.calculation(&tank).unwrap();
    assert!(t.vessel.problems[0].contains("API 650"), "{:?}", t.vessel);
    assert_eq!(t.vessel.code, "API 650");
    assert!(
        t.parts
            .iter()
            .any(|p| p.required.paragraph.starts_with("API 650")),
        "{:?}",
        t.parts
    );
}

#[test]
fn a_nozzle_edit_recalculates_that_nozzle_and_its_host_only() {
    let mut m = model("small-plant");
    let mut n = m.design().vessels[0].nozzles[1].clone();
    n.projection += 100.0;
    let c = m
        .edit(Edit::SetNozzle {
            vessel: "V-101".into(),
            nozzle: n,
        })
        .unwrap();
    assert_eq!(
        (
            c.nozzles_calculated,
            c.parts_calculated,
            c.vessels_calculated
        ),
        (1, 1, 1),
        "{c:?}"
    );
    assert_live(&m, "V-101");
}

#[test]
fn a_pressure_edit_recalculates_its_vessel_only() {
    let mut m = model("small-plant");
    let mut v = m.design().vessels[0].clone();
    let parts = v.parts.len() as u64;
    let nozzles = v.nozzles.len() as u64;
    v.design.pressure = Some(1500.0);
    let c = m.edit(Edit::SetVessel(v)).unwrap();
    assert_eq!(
        (
            c.parts_calculated,
            c.nozzles_calculated,
            c.vessels_calculated
        ),
        (parts, nozzles, 1),
        "{c:?}"
    );
    assert_live(&m, "V-101");
    // Nothing touched, nothing recalculated.
    let c = m.update();
    assert_eq!(
        (
            c.parts_calculated,
            c.nozzles_calculated,
            c.vessels_calculated
        ),
        (0, 0, 0)
    );
}

#[test]
fn a_liquid_level_adds_static_head_to_the_parts_below_it() {
    let mut m = model("vertical-column");
    let before = m.calculation("C-201").unwrap();
    let c = m
        .edit(Edit::SetOperating {
            vessel: "C-201".into(),
            operating: Some(vesselcad::design::OperatingDesign {
                liquid_level: 10_000.0,
                liquid_density: Some(1000.0),
            }),
        })
        .unwrap();
    assert_eq!(c.vessels_calculated, 1, "{c:?}");
    assert_live(&m, "C-201");
    let after = m.calculation("C-201").unwrap();
    let part =
        |calc: &Calculation, id: &str| calc.parts.iter().find(|p| p.id == id).unwrap().clone();
    // The bottom head sits under 10 m of water: 1000 · 9.80665 · 10 m = 0.0981 MPa.
    let h1 = part(&after, "H1");
    assert!(
        (h1.static_head - 0.098_066_5).abs() < 2e-4,
        "{}",
        h1.static_head
    );
    assert!(part(&before, "H1").static_head == 0.0);
    // The top course S2 starts above 10 m of liquid: no head.
    assert_eq!(part(&after, "S2").static_head, 0.0);
    assert!(h1.required.value > part(&before, "H1").required.value);
}

#[test]
fn a_thin_wall_is_a_deficiency_and_thickening_clears_it() {
    let mut m = model("small-plant");
    let v = m.design().vessels[0].clone();
    let thin = |t: f64| {
        let mut s = v.parts.iter().find(|p| p.id() == "S1").unwrap().clone();
        if let PartDesign::Shell(s) = &mut s {
            s.thickness = Some(t);
        }
        Edit::SetPart {
            vessel: "V-101".into(),
            part: s,
        }
    };
    m.edit(thin(8.0)).unwrap();
    let calc = m.calculation("V-101").unwrap();
    let walls: Vec<&String> = calc
        .vessel
        .deficiencies
        .iter()
        .filter(|d| d.contains(": wall "))
        .collect();
    assert_eq!(walls.len(), 1, "{:?}", calc.vessel);
    let d = walls[0];
    assert!(
        d.starts_with("S1: wall 8 mm") && d.contains("UG-27(c)(1)"),
        "{d}"
    );
    assert_eq!(calc.vessel.governing.as_deref(), Some("S1"));
    assert_live(&m, "V-101");
    m.edit(thin(14.0)).unwrap();
    let calc = m.calculation("V-101").unwrap();
    assert!(
        calc.vessel
            .deficiencies
            .iter()
            .all(|d| !d.contains(": wall ")),
        "{:?}",
        calc.vessel.deficiencies
    );
    assert_live(&m, "V-101");
}
