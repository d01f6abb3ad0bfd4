//! The design store on every backend (SQLite always, PostgreSQL when
//! `$VESSELCAD_TEST_PG` is set): revisions, replay from checkpoints, tags,
//! checkout as a new revision, content-addressed snapshots, optimistic
//! concurrency, diffs, migrations and refusals.

mod common;

use common::examples::example;
use common::stores::{sqlite_store, test_stores};
use vesselcad::design::{Design, PartDesign, Units};
use vesselcad::store::{CHECKPOINT, Change, SCHEMA_VERSION, Store, StoreError, diff};

fn change(message: &str) -> Change {
    Change {
        author: "tester".into(),
        message: message.into(),
    }
}

/// The drum with its first shell course `length` long.
fn with_shell_length(design: &Design, length: f64) -> Design {
    let mut d = design.clone();
    for part in &mut d.vessels[0].parts {
        if let PartDesign::Shell(s) = part {
            s.length = length;
            break;
        }
    }
    d
}

#[test]
fn revisions_replay_tag_and_checkout_on_every_backend() {
    for t in test_stores() {
        let mut store = Store::open(&t.location).unwrap();
        let drum = example("horizontal-drum");
        let r0 = store
            .import("drum", &drum, Units::Mm, &change("first"))
            .unwrap();
        assert_eq!((r0.rev, r0.parent), (0, None), "{}", t.label);
        // Past a checkpoint, so some revisions are replayed from a snapshot.
        let mut designs = vec![drum.clone()];
        for k in 1..=(CHECKPOINT + 5) {
            let next = with_shell_length(&drum, 7000.0 + k as f64);
            let prev = designs.last().unwrap().clone();
            let r = store
                .commit("drum", k - 1, &prev, &next, &change(&format!("edit {k}")))
                .unwrap();
            assert_eq!(r.rev, k);
            designs.push(next);
        }
        for rev in [0, 1, CHECKPOINT - 1, CHECKPOINT, CHECKPOINT + 5] {
            assert_eq!(
                store.design_at("drum", rev).unwrap(),
                designs[rev as usize],
                "{}: revision {rev}",
                t.label
            );
        }
        let log = store.log("drum").unwrap();
        assert_eq!(log.len() as i64, CHECKPOINT + 6);
        assert_eq!(log[3].message, "edit 3");
        assert_eq!(log[3].author, "tester");
        assert_eq!(log[3].parent, Some(2));
        // Snapshots: revision 0 and the checkpoint.
        assert_eq!(store.stats().unwrap().snapshots, 2, "{}", t.label);

        store.tag("drum", "A", 0).unwrap();
        store.tag("drum", "B", 3).unwrap();
        assert_eq!(store.resolve("drum", "A").unwrap(), 0);
        assert_eq!(store.resolve("drum", "B").unwrap(), 3);
        assert_eq!(store.resolve("drum", "head").unwrap(), CHECKPOINT + 5);
        assert_eq!(store.log("drum").unwrap()[3].tags, vec!["B".to_string()]);
        // Tagging a snapshot's revision keeps no second copy.
        assert_eq!(store.stats().unwrap().snapshots, 3, "{}", t.label);

        // Checkout: a new revision with revision 0's design and hash.
        let head = CHECKPOINT + 5;
        let r = store
            .commit(
                "drum",
                head,
                &designs[head as usize],
                &drum,
                &change("checkout A"),
            )
            .unwrap();
        assert_eq!(r.hash, r0.hash);
        assert_eq!(store.design_at("drum", r.rev).unwrap(), drum);
        assert_eq!(store.log("drum").unwrap().len() as i64, head + 2);

        // Importing the same design again changes nothing.
        let again = store
            .import("drum", &drum, Units::Mm, &change("again"))
            .unwrap();
        assert_eq!(again.rev, r.rev);
    }
}

#[test]
fn a_stale_parent_is_a_conflict_and_writes_nothing() {
    for t in test_stores() {
        let mut one = Store::open(&t.location).unwrap();
        let mut two = Store::open(&t.location).unwrap();
        let drum = example("horizontal-drum");
        one.import("drum", &drum, Units::Mm, &change("first"))
            .unwrap();
        let a = with_shell_length(&drum, 7100.0);
        let b = with_shell_length(&drum, 7300.0);
        one.commit("drum", 0, &drum, &a, &change("one")).unwrap();
        let refused = two.commit("drum", 0, &drum, &b, &change("two"));
        match refused {
            Err(StoreError::Conflict {
                parent, current, ..
            }) => assert_eq!((parent, current), (0, 1), "{}", t.label),
            other => panic!("{}: expected a conflict, got {other:?}", t.label),
        }
        assert_eq!(two.head("drum").unwrap(), Some(1));
        assert_eq!(two.design_at("drum", 1).unwrap(), a);
        // Based on the newest revision, the second writer goes through.
        two.commit("drum", 1, &a, &b, &change("two again")).unwrap();
        assert_eq!(one.design_at("drum", 2).unwrap(), b);
    }
}

#[test]
fn diff_names_parameters_by_tag_and_id() {
    let drum = example("horizontal-drum");
    let mut after = with_shell_length(&drum, 8000.0);
    after.vessels[0].design.pressure = Some(1200.0);
    after.vessels[0].nozzles[0].size = 10.0;
    let (patch, changes) = diff(&drum, &after);
    assert_eq!(patch.as_array().unwrap().len(), 3);
    let lines: Vec<String> = changes.iter().map(ToString::to_string).collect();
    let tag = &drum.vessels[0].tag;
    let mark = &drum.vessels[0].nozzles[0].mark;
    assert!(
        lines.contains(&format!("{tag} design pressure: 1000.0 → 1200.0")),
        "{lines:?}"
    );
    assert!(
        lines.contains(&format!("{tag} shell S1 length: 7200.0 → 8000.0")),
        "{lines:?}"
    );
    assert!(
        lines.contains(&format!("{tag} nozzle {mark} size: 8.0 → 10.0")),
        "{lines:?}"
    );
}

#[test]
fn unknown_names_and_revisions_are_refused_by_name() {
    for t in test_stores() {
        let mut store = Store::open(&t.location).unwrap();
        let drum = example("horizontal-drum");
        store
            .import("drum", &drum, Units::Mm, &change("first"))
            .unwrap();
        let e = store.design_at("column", 0).unwrap_err().to_string();
        assert!(e.contains("\"column\"") && e.contains("drum"), "{e}");
        let e = store.resolve("drum", "7").unwrap_err().to_string();
        assert!(e.contains("no revision \"7\""), "{e}");
        let e = store.tag("drum", "bad tag", 0).unwrap_err().to_string();
        assert!(e.contains("\"bad tag\""), "{e}");
        let e = store
            .import("12", &drum, Units::Mm, &change("x"))
            .unwrap_err();
        assert!(matches!(e, StoreError::BadName { .. }), "{e}");
    }
}

#[test]
fn the_schema_is_versioned_and_a_newer_one_is_refused() {
    let t = sqlite_store();
    drop(Store::open(&t.location).unwrap());
    let raw = rusqlite::Connection::open(&t.location).unwrap();
    let version: i64 = raw
        .query_row("SELECT version FROM schema_version", [], |r| r.get(0))
        .unwrap();
    assert_eq!(version, SCHEMA_VERSION);
    // Opening again migrates nothing and keeps the data.
    let mut store = Store::open(&t.location).unwrap();
    store
        .import("drum", &example("horizontal-drum"), Units::Mm, &change("x"))
        .unwrap();
    drop(store);
    raw.execute("UPDATE schema_version SET version = version + 1", [])
        .unwrap();
    match Store::open(&t.location) {
        Err(StoreError::NewerSchema { found, known, .. }) => {
            assert_eq!((found, known), (SCHEMA_VERSION + 1, SCHEMA_VERSION));
        }
        Err(e) => panic!("expected NewerSchema, got {e}"),
        Ok(_) => panic!("expected NewerSchema, the store opened"),
    }
}

#[test]
fn an_unreachable_database_is_a_clear_error_without_the_password() {
    let e = Store::open("postgres://someone:secret@127.0.0.1:1/nowhere")
        .err()
        .expect("nothing listens on port 1")
        .to_string();
    assert!(e.contains("cannot connect"), "{e}");
    assert!(e.contains("someone:***@127.0.0.1:1"), "{e}");
    assert!(!e.contains("secret"), "{e}");
}

/// `store export` of a tagged revision puts the tag and the revision's date in
/// every vessel's drawing revision block, so the sheet drawn from the exported
/// file shows the revision it is; an untagged revision is written as stored.
#[test]
fn an_exported_named_revision_carries_its_tag_into_the_drawings() {
    let dir = tempfile::tempdir().unwrap();
    let db = dir.path().join("store.db");
    let run = |args: &[&str]| {
        let out = std::process::Command::new(env!("CARGO_BIN_EXE_vesselcad"))
            .arg("store")
            .arg("--store")
            .arg(&db)
            .args(args)
            .output()
            .unwrap();
        assert!(
            out.status.success(),
            "{args:?}: {}",
            String::from_utf8_lossy(&out.stderr)
        );
        String::from_utf8_lossy(&out.stdout).into_owned()
    };
    let source = common::examples::example_path("horizontal-drum");
    run(&["import", source.to_str().unwrap(), "--name", "drum"]);
    run(&["tag", "drum", "B"]);
    // Revision 1, untagged: the same design again.
    run(&["checkout", "drum", "0"]);
    let tagged = dir.path().join("drum-B.json");
    run(&["export", "drum", "B", "-o", tagged.to_str().unwrap()]);
    let design = vesselcad::design::load(&tagged).unwrap();
    let today = run(&["log", "drum"]);
    for v in &design.vessels {
        assert_eq!(v.drawing.revision.as_deref(), Some("B"), "{}", v.tag);
        let date = v.drawing.date.as_deref().unwrap();
        assert_eq!(date.len(), 10);
        assert!(today.contains(date), "{date} not in the log:\n{today}");
    }
    // The sheet of the exported design shows revision B.
    let svg = dir.path().join("drum-B.svg");
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_vesselcad"))
        .arg("drawing")
        .arg(&tagged)
        .args(["--vessel", "V-101", "-o"])
        .arg(&svg)
        .output()
        .unwrap();
    assert!(out.status.success());
    let svg = std::fs::read_to_string(&svg).unwrap();
    let texts: Vec<&str> = svg
        .split("</text>")
        .filter_map(|t| t.rsplit('>').next())
        .map(str::trim)
        .collect();
    assert!(texts.contains(&"B"), "no revision B on the sheet");
    let date = design.vessels[0].drawing.date.as_deref().unwrap();
    assert!(texts.contains(&date), "no date {date} on the sheet");
    // Untagged: the revision block as stored (the example has none).
    let plain = dir.path().join("drum-1.json");
    run(&["export", "drum", "1", "-o", plain.to_str().unwrap()]);
    let stored = vesselcad::design::load(&plain).unwrap();
    assert_eq!(
        stored.vessels[0].drawing,
        example("horizontal-drum").vessels[0].drawing
    );
    // A tag too long for the block leaves it as stored, and says so.
    run(&["tag", "drum", "issued-for-construction", "1"]);
    let said = run(&["export", "drum", "1", "-o", plain.to_str().unwrap()]);
    assert!(said.contains("longer than a drawing's revision"), "{said}");
    let stored = vesselcad::design::load(&plain).unwrap();
    assert_eq!(
        stored.vessels[0].drawing,
        example("horizontal-drum").vessels[0].drawing
    );
}
