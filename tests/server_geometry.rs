//! A live edit whose geometry cannot be built is never acknowledged (issue 30
//! §1): it passes every design rule, but the model cannot mesh it, so the
//! server answers 422 (kind `geometry`, not a rule) naming the part's JSON
//! path, the stage and patch that failed and the mesher's typed cause, and the design, revision and model stay as they were.

mod server_support;

use serde_json::{Value, json};
use server_support::{ServerProcess, design_copy};

/// The fuzz plant of `tests/repros/` whose storage tank's conical roof could
/// not be meshed at 1 mm with nozzle N3 (`vessels[3].nozzles[1]`): the last
/// known design that passed every rule and could not be built. The roof now
/// builds, so the test is ignored until it gets another such edit (or an
/// injected mesher failure).
fn unbuildable() -> Value {
    let path = format!(
        "{}/tests/repros/fuzz-seed1-accepted-edit-roof-4M-vertices.json",
        env!("CARGO_MANIFEST_DIR")
    );
    serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap()
}

#[test]
#[ignore = "needs an edit that check accepts and the mesher cannot build: the fuzz plant's roof at 1 mm, the last one known, builds since the pole-row fix (issue 30)"]
fn an_edit_that_cannot_be_built_is_refused_and_changes_nothing() {
    let mut plant = unbuildable();
    let tank = &mut plant["vessels"][3];
    let n3 = tank["nozzles"].as_array_mut().unwrap().remove(1);
    assert_eq!(n3["mark"], "N3");
    if let Some(notes) = tank["notes"].as_array_mut() {
        notes.retain(|n| n["target"] != n3["mark"]);
    }
    let copy = design_copy("vertical-column.json", "geometry-refused");
    std::fs::write(&*copy, serde_json::to_string_pretty(&plant).unwrap()).unwrap();
    let server = ServerProcess::start(&copy, &["--tolerance", "1"]);
    let before = server.request("GET", "/design.json", &[], b"");
    let glb_before = server.request("GET", "/model.glb", &[], b"").body;
    // N3 back on the tank's roof.
    let r = server.edit(&json!([
        { "op": "add", "path": "/vessels/3/nozzles/1", "value": n3 }
    ]));
    assert_eq!(r.status, 422, "{}", r.text());
    let answer = r.json();
    // A build failure, not a broken rule: no `violations`.
    assert_eq!(answer["kind"], "geometry", "{answer}");
    assert!(answer.get("violations").is_none(), "{answer}");
    let v = &answer["failures"][0];
    assert_eq!(v["path"], "vessels[3].parts[2]", "{answer}");
    assert_eq!(v["entity"], "TK-301/ROOF", "{answer}");
    assert_eq!(v["stage"], "mesh", "{answer}");
    assert_eq!(v["patch"], "cone", "{answer}");
    assert!(
        v["cause"].as_str().unwrap().contains("refinement"),
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
