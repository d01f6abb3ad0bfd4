//! A vessel's sheet costs what that vessel costs, not what the plant costs: the
//! model a sheet is drawn from holds that vessel only (work counted, not timed),
//! and its sheet is the one a model of the whole plant gives.

use std::process::Command;

use vesselcad::design::{Design, to_canonical_json};
use vesselcad::drawing::{SheetModelError, SheetOptions, sheet_model, sheet_svg};
use vesselcad::mesh::TessellationOptions;
use vesselcad::model::Model;
use vesselcad::plant::generate_plant;

fn options() -> TessellationOptions {
    TessellationOptions::chord(5.0)
}

#[test]
fn a_sheet_model_does_the_work_of_its_vessel_alone() {
    let plant = generate_plant(24, 11).unwrap();
    let vessel = plant.vessels[9].clone();
    let alone = Design {
        vessels: vec![vessel.clone()],
        ..plant.clone()
    };
    let (in_plant, work) = sheet_model(&plant, &vessel.tag, options()).unwrap();
    let (_, work_alone) = sheet_model(&alone, &vessel.tag, options()).unwrap();
    assert_eq!(work.vessels_resolved, 1);
    assert_eq!(work, work_alone, "the plant's other vessels cost something");
    assert!(work.triangles_meshed > 0);

    // The same sheet as from a model of the whole plant.
    let whole = Model::from_design(&plant, options()).unwrap();
    let options = SheetOptions::default();
    assert_eq!(
        sheet_svg(&in_plant, &vessel.tag, &options).unwrap(),
        sheet_svg(&whole, &vessel.tag, &options).unwrap()
    );
}

#[test]
fn an_unknown_tag_lists_the_tags() {
    let plant = generate_plant(3, 1).unwrap();
    let Err(e) = sheet_model(&plant, "NOPE", options()) else {
        panic!("built a vessel that does not exist");
    };
    assert!(matches!(e, SheetModelError::UnknownVessel { .. }));
    let text = e.to_string();
    for v in &plant.vessels {
        assert!(text.contains(&v.tag), "{text}");
    }
}

#[test]
fn the_drawing_command_builds_one_vessel_of_a_plant() {
    let dir = tempfile::tempdir().unwrap();
    let plant = generate_plant(24, 11).unwrap();
    let path = dir.path().join("plant.json");
    std::fs::write(&path, to_canonical_json(&plant)).unwrap();
    let svg = dir.path().join("sheet.svg");
    let output = Command::new(env!("CARGO_BIN_EXE_vesselcad"))
        .arg("drawing")
        .arg(&path)
        .args(["--vessel", &plant.vessels[9].tag, "--tolerance", "5", "-o"])
        .arg(&svg)
        .output()
        .unwrap();
    let stdout = String::from_utf8_lossy(&output.stdout);
    assert!(
        output.status.success(),
        "{stdout}{}",
        String::from_utf8_lossy(&output.stderr)
    );
    assert!(stdout.contains("built 1 vessel(s)"), "{stdout}");
    assert!(std::fs::read_to_string(&svg).unwrap().starts_with("<svg"));

    // An unknown tag lists the tags.
    let output = Command::new(env!("CARGO_BIN_EXE_vesselcad"))
        .arg("drawing")
        .arg(&path)
        .args(["--vessel", "NOPE", "-o"])
        .arg(&svg)
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert_eq!(output.status.code(), Some(1), "{stderr}");
    assert!(
        stderr.contains(&plant.vessels[0].tag) && stderr.contains("NOPE"),
        "{stderr}"
    );
}
