//! A live edit whose geometry cannot be built is never acknowledged (issue 30
//! §1): it passes every design rule, but the model cannot mesh it, so the
//! server answers 422 (kind `geometry`, not a rule) naming the part's JSON
//! path, the stage and patch that failed and the mesher's typed cause, and the design, revision and model stay as they were. The edit is
//! `common::unbuildable`'s: head H2 of the horizontal drum made hemispherical
//! under a vertex budget its crown then needs more than.

mod common;
mod server_support;

use common::unbuildable::{ENTITY, PATCH, PATH, buildable_json, edit, option_args, written};
use server_support::ServerProcess;

#[test]
fn an_edit_that_cannot_be_built_is_refused_and_changes_nothing() {
    let (_dir, copy) = written(&buildable_json());
    let args = option_args();
    let args: Vec<&str> = args.iter().map(String::as_str).collect();
    let server = ServerProcess::start(&copy, &args);
    let before = server.request("GET", "/design.json", &[], b"");
    let glb_before = server.request("GET", "/model.glb", &[], b"").body;
    // Head H2 hemispherical: its crown needs more vertices than the budget.
    let r = server.edit(&edit());
    assert_eq!(r.status, 422, "{}", r.text());
    let answer = r.json();
    // A build failure, not a broken rule: no `violations`.
    assert_eq!(answer["kind"], "geometry", "{answer}");
    assert!(answer.get("violations").is_none(), "{answer}");
    let v = &answer["failures"][0];
    assert_eq!(v["path"], PATH, "{answer}");
    assert_eq!(v["entity"], ENTITY, "{answer}");
    assert_eq!(v["stage"], "mesh", "{answer}");
    assert_eq!(v["patch"], PATCH, "{answer}");
    assert!(
        v["cause"].as_str().unwrap().contains("max_vertices"),
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
