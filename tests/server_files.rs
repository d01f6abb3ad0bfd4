//! `vesselcad serve` and the user's file: never written without edits and a
//! save, written back in its own units (inches as given), the previous file kept
//! as `.bak`, written through a symbolic link to its target, and a failed save
//! said as such.

mod server_support;

use serde_json::json;
use server_support::{ServerProcess, design_copy};
use vesselcad::design::units::to_inches;
use vesselcad::design::{load, to_canonical_json};

fn rotate(server: &ServerProcess, degrees: f64) {
    let r = server.edit(
        &json!([{ "op": "replace", "path": "/vessels/0/placement/rotation", "value": degrees }]),
    );
    assert_eq!(r.status, 200, "{}", r.text());
}

#[test]
fn the_file_is_written_only_by_a_save_with_edits() {
    let design = design_copy("horizontal-drum.json", "files-untouched");
    let file = std::fs::read(&*design).unwrap();
    let mut server = ServerProcess::start(&design, &[]);
    // A save with nothing to save writes nothing.
    let r = server.request("POST", "/save", &[], b"");
    assert_eq!(r.status, 200, "{}", r.text());
    assert_eq!(r.json()["written"], false);
    assert!(server.terminate());
    assert_eq!(std::fs::read(&*design).unwrap(), file);
    // Even a clean shutdown asked to save writes nothing without edits.
    let mut server = ServerProcess::start(&design, &["--save-on-exit"]);
    assert!(server.terminate());
    assert_eq!(std::fs::read(&*design).unwrap(), file);
    assert!(!design.with_file_name("design.json.bak").exists());
}

#[test]
fn an_inch_file_is_saved_in_inches_as_written_with_a_backup() {
    let design = design_copy("horizontal-drum.json", "files-inches");
    let mut inches = load(&design).unwrap();
    to_inches(&mut inches);
    let text = to_canonical_json(&inches);
    assert!(text.contains("\"units\": \"in\""));
    std::fs::write(&design, &text).unwrap();
    let server = ServerProcess::start(&design, &[]);
    rotate(&server, 30.0);
    let r = server.request("POST", "/save", &[], b"");
    assert_eq!(r.status, 200, "{}", r.text());
    assert_eq!(r.json()["written"], true);
    let saved = std::fs::read_to_string(&*design).unwrap();
    // Only the rotation changed: every length reads as it was written.
    let mut expected: serde_json::Value = serde_json::from_str(&text).unwrap();
    expected["vessels"][0]["placement"]["rotation"] = json!(30.0);
    let saved_value: serde_json::Value = serde_json::from_str(&saved).unwrap();
    assert_eq!(saved_value, expected, "{saved}");
    assert_eq!(
        std::fs::read_to_string(design.with_file_name("design.json.bak")).unwrap(),
        text
    );
}

#[cfg(unix)]
#[test]
fn a_save_through_a_link_writes_its_target() {
    let design = design_copy("storage-tank.json", "files-link");
    let link = design.with_file_name("link.json");
    std::os::unix::fs::symlink(&*design, &link).unwrap();
    let server = ServerProcess::start(&link, &[]);
    rotate(&server, 15.0);
    let r = server.request("POST", "/save", &[], b"");
    assert_eq!(r.status, 200, "{}", r.text());
    assert!(
        std::fs::symlink_metadata(&link)
            .unwrap()
            .file_type()
            .is_symlink()
    );
    assert_eq!(load(&*design).unwrap().vessels[0].placement.rotation, 15.0);
}

#[test]
fn a_failed_save_says_so_and_changes_nothing() {
    let design = design_copy("storage-tank.json", "files-failed");
    let file = std::fs::read(&*design).unwrap();
    let server = ServerProcess::start(&design, &[]);
    rotate(&server, 20.0);
    // The temp file's name is taken by a folder: the write fails.
    std::fs::create_dir(design.with_file_name("design.json.tmp")).unwrap();
    let r = server.request("POST", "/save", &[], b"");
    assert_eq!(r.status, 500, "{}", r.text());
    let body = r.json();
    assert_eq!(body["kind"], "save_failed");
    let message = body["error"].as_str().unwrap();
    assert!(
        message.contains("design not saved") && !message.contains("edit not saved"),
        "{message}"
    );
    assert_eq!(std::fs::read(&*design).unwrap(), file);
    // The edit is still there, and a save works once the way is clear.
    std::fs::remove_dir(design.with_file_name("design.json.tmp")).unwrap();
    let r = server.request("POST", "/save", &[], b"");
    assert_eq!(r.status, 200, "{}", r.text());
    assert_eq!(load(&*design).unwrap().vessels[0].placement.rotation, 20.0);
    assert!(!design.with_file_name("design.json.tmp").exists());
}

/// A design file deleted while serving is written again by a save, and the
/// answer says so (it failed reading the file to back it up).
#[test]
fn a_save_recreates_a_deleted_file_and_says_so() {
    let design = design_copy("horizontal-drum.json", "files-deleted");
    let server = ServerProcess::start(&design, &[]);
    rotate(&server, 25.0);
    std::fs::remove_file(&*design).unwrap();
    let r = server.request("POST", "/save", &[], b"");
    assert_eq!(r.status, 200, "{}", r.text());
    let body = r.json();
    assert_eq!(body["written"], true, "{body}");
    assert_eq!(body["recreated"], true, "{body}");
    assert!(
        body["message"].as_str().unwrap().contains("deleted"),
        "{body}"
    );
    assert_eq!(load(&*design).unwrap().vessels[0].placement.rotation, 25.0);
    // Deleted again with nothing left to save: a save still writes it.
    std::fs::remove_file(&*design).unwrap();
    let r = server.request("POST", "/save", &[], b"");
    assert_eq!(r.status, 200, "{}", r.text());
    assert_eq!(r.json()["recreated"], true);
    assert_eq!(load(&*design).unwrap().vessels[0].placement.rotation, 25.0);
    // An ordinary save says nothing was recreated.
    rotate(&server, 35.0);
    let r = server.request("POST", "/save", &[], b"");
    assert_eq!(r.json()["recreated"], false, "{}", r.text());
}
