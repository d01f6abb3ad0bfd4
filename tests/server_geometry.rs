//! A live edit whose geometry cannot be built is never acknowledged (issue 30
//! §1): it passes every design rule, but the model cannot cut it, so the
//! server answers 422 naming the nozzle's JSON path, the stage that failed and
//! why, and the design, revision and model stay as they were.

mod server_support;

use serde_json::json;
use server_support::{ServerProcess, design_copy};
use vesselcad::design::load;
use vesselcad::parts::tables::{Nps, pipe};

#[test]
fn an_edit_that_cannot_be_built_is_refused_and_changes_nothing() {
    let example = format!(
        "{}/examples/designs/vertical-column.json",
        env!("CARGO_MANIFEST_DIR")
    );
    let design = load(&example).unwrap();
    let resolved = vesselcad::design::resolve(&design).unwrap();
    let head = resolved[0].parts.iter().find(|p| p.id == "H2").unwrap();
    let patches = head.geometry.patches().unwrap();
    let crown = patches.iter().find(|p| p.name == "crown").unwrap();
    let seam = crown
        .surface
        .boundary(vesselcad::nurbs::Side::VMin)
        .control_points()[0]
        .truncate()
        .length();
    let k = design.vessels[0]
        .nozzles
        .iter()
        .position(|n| n.mark == "N3")
        .unwrap();
    let offset = seam - 0.25 * pipe(Nps::try_new(3.0).unwrap()).outside_diameter;

    let copy = design_copy("vertical-column.json", "geometry-refused");
    let server = ServerProcess::start(&copy, &[]);
    let before = server.request("GET", "/design.json", &[], b"");
    let glb_before = server.request("GET", "/model.glb", &[], b"").body;
    // N3 astride the knuckle–crown seam of H2 with a reinforcing pad.
    let n = format!("/vessels/0/nozzles/{k}");
    let r = server.edit(&json!([
        { "op": "replace", "path": format!("{n}/size"), "value": 3 },
        { "op": "replace", "path": format!("{n}/orientation"), "value": 30 },
        { "op": "add", "path": format!("{n}/offset"), "value": offset },
        { "op": "add", "path": format!("{n}/pad"), "value": { "od": 120, "thickness": 10 } }
    ]));
    assert_eq!(r.status, 422, "{}", r.text());
    let answer = r.json();
    assert_eq!(answer["kind"], "refused", "{answer}");
    let v = &answer["violations"][0];
    assert_eq!(v["path"], format!("vessels[0].nozzles[{k}]"), "{answer}");
    assert_eq!(v["entity"], "C-201/N3", "{answer}");
    assert_eq!(v["field"], "opening", "{answer}");
    assert!(
        v["rule"].as_str().unwrap().contains("reinforcing pad"),
        "{answer}"
    );
    let after = server.request("GET", "/design.json", &[], b"");
    assert_eq!(after.json(), before.json());
    assert_eq!(
        after.header("x-vesselcad-revision"),
        before.header("x-vesselcad-revision")
    );
    assert_eq!(
        server.request("GET", "/model.glb", &[], b"").body,
        glb_before
    );
}
