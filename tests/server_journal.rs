//! Nothing acknowledged is lost: `vesselcad serve` killed with SIGKILL after N
//! acknowledged edits comes back, on restart, with all N (the journal is flushed
//! before each answer); `POST /save` (and a clean shutdown with
//! `--save-on-exit`) write the design file and start a fresh journal; a clean
//! shutdown without it leaves the file alone.

mod server_support;

use serde_json::json;
use server_support::{ServerProcess, design_copy};
use vesselcad::design::load;

/// Edits acknowledged before the kill.
const EDITS: usize = 12;

/// The `k`-th edit: each nozzle's projection gets its own value.
fn edit(k: usize) -> serde_json::Value {
    json!([{ "op": "replace", "path": format!("/vessels/0/nozzles/{}/projection", k % 7), "value": 1450 + 10 * k }])
}

/// Expected projection of nozzle `n` after edits `0..count`.
fn expected(n: usize, count: usize, original: f64) -> f64 {
    (0..count)
        .rfind(|k| k % 7 == n)
        .map_or(original, |k| (1450 + 10 * k) as f64)
}

#[test]
fn every_acknowledged_edit_survives_kill_9() {
    let design = design_copy("horizontal-drum.json", "journal-kill");
    let original = load(&design).unwrap();
    let projections: Vec<f64> = original.vessels[0]
        .nozzles
        .iter()
        .map(|n| n.projection)
        .collect();

    let mut server = ServerProcess::start(&design, &[]);
    for k in 0..EDITS {
        let r = server.edit(&edit(k));
        assert_eq!(r.status, 200, "edit {k}: {}", r.text());
        assert_eq!(r.json()["revision"], k + 1);
    }
    server.kill9();
    // The design file itself was never written.
    assert_eq!(load(&design).unwrap(), original);

    let mut server = ServerProcess::start(&design, &[]);
    let r = server.request("GET", "/design.json", &[], b"");
    assert_eq!(r.header("x-vesselcad-revision"), Some(&*EDITS.to_string()));
    let served = r.json();
    for n in 0..7 {
        assert_eq!(
            served["vessels"][0]["nozzles"][n]["projection"].as_f64(),
            Some(expected(n, EDITS, projections[n])),
            "nozzle {n}"
        );
    }
    // Revisions go on from where they were.
    let r = server.edit(&edit(EDITS));
    assert_eq!(r.json()["revision"], EDITS + 1);

    // A save writes the design and empties the journal; a kill then loses nothing.
    let r = server.request("POST", "/save", &[], b"");
    assert_eq!(r.status, 200, "{}", r.text());
    let journal = design.with_file_name("design.json.journal");
    assert_eq!(
        std::fs::read_to_string(&journal).unwrap().lines().count(),
        1
    );
    let saved = load(&design).unwrap();
    assert_eq!(
        saved.vessels[0].nozzles[EDITS % 7].projection,
        expected(EDITS % 7, EDITS + 1, 0.0)
    );
    server.kill9();
    let mut server = ServerProcess::start(&design, &[]);
    let r = server.request("GET", "/design.json", &[], b"");
    assert_eq!(
        r.header("x-vesselcad-revision"),
        Some(&*(EDITS + 1).to_string())
    );
    assert_eq!(r.json(), serde_json::to_value(&saved).unwrap());

    // A clean shutdown (SIGTERM) leaves the file as the last save wrote it: the
    // edit stays in the journal and comes back on restart.
    let r = server
        .edit(&json!([{ "op": "replace", "path": "/vessels/0/placement/rotation", "value": 45 }]));
    assert_eq!(r.status, 200);
    let file = std::fs::read(&*design).unwrap();
    assert!(server.terminate(), "clean shutdown failed");
    assert_eq!(
        std::fs::read(&*design).unwrap(),
        file,
        "the file was rewritten"
    );
    assert_eq!(
        std::fs::read_to_string(&journal).unwrap().lines().count(),
        2
    );
    // With --save-on-exit, a clean shutdown saves it.
    let mut server = ServerProcess::start(&design, &["--save-on-exit"]);
    let r = server.request("GET", "/design.json", &[], b"");
    assert_eq!(r.json()["vessels"][0]["placement"]["rotation"], 45.0);
    assert!(server.terminate(), "clean shutdown failed");
    assert_eq!(load(&design).unwrap().vessels[0].placement.rotation, 45.0);
    assert_eq!(
        std::fs::read_to_string(&journal).unwrap().lines().count(),
        1
    );
}

#[test]
fn a_design_changed_behind_the_journal_is_refused_at_start() {
    let design = design_copy("storage-tank.json", "journal-changed");
    let mut server = ServerProcess::start(&design, &[]);
    let r = server
        .edit(&json!([{ "op": "replace", "path": "/vessels/0/placement/rotation", "value": 30 }]));
    assert_eq!(r.status, 200);
    server.kill9();
    // Someone edits the file by hand while the journal holds an edit.
    let text = std::fs::read_to_string(&design).unwrap();
    std::fs::write(&design, format!("{text}\n")).unwrap();
    let output = std::process::Command::new(env!("CARGO_BIN_EXE_vesselcad"))
        .args(["serve", design.to_str().unwrap(), "--port", "0"])
        .output()
        .unwrap();
    assert_eq!(output.status.code(), Some(1));
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(stderr.contains("changed outside the server"), "{stderr}");
}

/// A restart with a journal of N edits replays them on the design and builds
/// the model once, not once per edit (issue 30 §4: 400 edits took 12 s).
#[test]
fn a_restart_builds_the_model_once_whatever_the_journal_holds() {
    let design = design_copy("horizontal-drum.json", "journal-once");
    let original = load(&design).unwrap();
    let mut server = ServerProcess::start(&design, &[]);
    for k in 0..EDITS {
        let r = server.edit(&edit(k));
        assert_eq!(r.status, 200, "edit {k}: {}", r.text());
    }
    server.kill9();
    let session = vesselcad::server::session::Session::open(
        &design,
        vesselcad::mesh::TessellationOptions::DEFAULT,
    )
    .unwrap();
    assert_eq!(session.revision(), EDITS as u64);
    assert_eq!(session.model().runs(), 1, "one build for {EDITS} edits");
    let nozzles = &session.model().design().vessels[0].nozzles;
    for (n, nozzle) in nozzles.iter().enumerate().take(7) {
        assert_eq!(
            nozzle.projection,
            expected(n, EDITS, original.vessels[0].nozzles[n].projection),
            "nozzle {n}"
        );
    }
}
