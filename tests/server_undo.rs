//! Undo and redo of a live session, which keep the patch that takes each edit
//! back rather than a copy of the design: over edits confined to one vessel and
//! edits of the whole document (a vessel removed, a vessel renamed) they walk
//! back and forth through exactly the designs the edits made, a new edit ends
//! the redo chain, the journal replays the undos, and a store's history holds
//! every revision's design.

mod common;

use std::path::{Path, PathBuf};

use common::stores::test_stores;
use serde_json::{Value, json};
use vesselcad::mesh::TessellationOptions;
use vesselcad::server::ApiError;
use vesselcad::server::session::Session;

/// The example plant copied into a temporary folder.
fn plant_copy(dir: &Path) -> PathBuf {
    let path = dir.join("plant.json");
    let source = Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/designs/small-plant.json");
    std::fs::copy(source, &path).unwrap();
    path
}

/// Edits confined to a vessel (a value, a nozzle removed) and of the whole
/// document (a vessel removed, one renamed).
fn edits() -> Vec<Value> {
    vec![
        json!([{ "op": "replace", "path": "/vessels/0/nozzles/0/projection", "value": 1620 }]),
        json!([{ "op": "remove", "path": "/vessels/2/nozzles/9" }]),
        json!([{ "op": "remove", "path": "/vessels/3" }]),
        json!([{ "op": "replace", "path": "/vessels/1/tag", "value": "V-102A" }]),
        json!([{ "op": "replace", "path": "/vessels/1/nozzles/1/orientation", "value": 200 }]),
    ]
}

/// The session's design text, checked against its model's.
fn text(session: &Session) -> String {
    let text = session.design_text();
    assert_eq!(
        text,
        vesselcad::design::to_canonical_json(&session.model().design())
    );
    text
}

/// Applies every edit, then walks back to the start and forward again;
/// returns the design texts after each edit (the first is the start).
fn walk(session: &mut Session) -> Vec<String> {
    let mut texts = vec![text(session)];
    for (k, edit) in edits().iter().enumerate() {
        let body = serde_json::to_vec(edit).unwrap();
        session
            .apply_patch(&body)
            .unwrap_or_else(|e| panic!("edit {k}: {e}"));
        texts.push(text(session));
    }
    for k in (0..edits().len()).rev() {
        let undone = session.undo().unwrap();
        undone.wait_durable().unwrap();
        assert_eq!(text(session), texts[k], "undo back to {k}");
        assert!(!undone.changed.is_empty() || !undone.removed.is_empty());
    }
    assert!(matches!(session.undo(), Err(ApiError::NothingTo("undo"))));
    for (k, expected) in texts.iter().enumerate().skip(1) {
        session.redo().unwrap().wait_durable().unwrap();
        assert_eq!(&text(session), expected, "redo to {k}");
    }
    assert!(matches!(session.redo(), Err(ApiError::NothingTo("redo"))));
    texts
}

#[test]
fn undo_and_redo_walk_back_and_forth_through_vessel_and_whole_edits() {
    let dir = tempfile::tempdir().unwrap();
    let path = plant_copy(dir.path());
    let mut session = Session::open(&path, TessellationOptions::DEFAULT).unwrap();
    let texts = walk(&mut session);
    let edits = edits().len() as u64;
    assert_eq!(session.revision(), 3 * edits);

    // Two undos, then a new edit: it ends the redo chain; undo takes it back.
    session.undo().unwrap().wait_durable().unwrap();
    session.undo().unwrap().wait_durable().unwrap();
    let before = text(&session);
    assert_eq!(before, texts[texts.len() - 3]);
    let edit =
        json!([{ "op": "replace", "path": "/vessels/0/nozzles/1/projection", "value": 1700 }]);
    session
        .apply_patch(&serde_json::to_vec(&edit).unwrap())
        .unwrap();
    let after = text(&session);
    assert!(matches!(session.redo(), Err(ApiError::NothingTo("redo"))));
    session.undo().unwrap().wait_durable().unwrap();
    assert_eq!(text(&session), before);
    session.redo().unwrap().wait_durable().unwrap();
    assert_eq!(text(&session), after);

    // The journal holds the undos and redos as patches: a restart replays
    // them to the same design.
    let revision = session.revision();
    drop(session);
    let session = Session::open(&path, TessellationOptions::DEFAULT).unwrap();
    assert_eq!(session.revision(), revision);
    assert_eq!(text(&session), after);
}

#[test]
fn a_store_keeps_every_design_undo_and_redo_went_through() {
    for store in test_stores() {
        let dir = tempfile::tempdir().unwrap();
        let path = plant_copy(dir.path());
        let options = TessellationOptions::DEFAULT;
        let mut session = Session::open_with(&path, options, Some(&store.location)).unwrap();
        let texts = walk(&mut session);
        let n = texts.len() - 1;
        // Revisions: the import, the edits, the undos back, the redos forward.
        let mut expected: Vec<&String> = texts.iter().collect();
        expected.extend(texts.iter().rev().skip(1));
        expected.extend(texts.iter().skip(1));
        let log = session.revisions().unwrap();
        assert_eq!(log.len(), 3 * n + 1, "{}", store.label);
        let messages: Vec<&str> = log.iter().map(|r| r.message.as_str()).collect();
        assert_eq!(&messages[1..=n], vec!["edit"; n]);
        assert_eq!(&messages[n + 1..=2 * n], vec!["undo"; n]);
        assert_eq!(&messages[2 * n + 1..], vec!["redo"; n]);
        for (revision, text) in expected.iter().enumerate() {
            assert_eq!(
                &&session.design_text_at(revision as u64).unwrap(),
                text,
                "{}: revision {revision}",
                store.label
            );
        }
    }
}
