//! `vesselcad serve --store` on every backend (SQLite always, PostgreSQL when
//! `$VESSELCAD_TEST_PG` is set): every acknowledged edit survives `kill -9`,
//! undo and redo are new revisions, history is served, an old journal is
//! migrated, two servers on one store refuse a stale edit with 409, and on
//! PostgreSQL a viewer of one server sees the other server's edits, and a lost
//! database connection refuses the edit at hand, then reconnects.

mod common;
mod server_support;

use common::stores::{postgres_store, postgres_url, test_stores};
use futures_util::StreamExt;
use serde_json::{Value, json};
use server_support::{ServerProcess, TIMEOUT, design_copy};
use tokio_tungstenite::tungstenite::Message;
use vesselcad::design::load;

/// The content type every POST declares.
const JSON: &[(&str, &str)] = &[("content-type", "application/json")];

fn projection(k: usize) -> Value {
    json!([{ "op": "replace", "path": "/vessels/0/nozzles/0/projection", "value": 1500 + 10 * k }])
}

#[test]
fn acknowledged_edits_survive_kill_9_and_history_is_served() {
    for t in test_stores() {
        let design = design_copy("horizontal-drum.json", "store-kill");
        let original = std::fs::read(&*design).unwrap();
        let args = ["--store", t.location.as_str()];
        let mut server = ServerProcess::start(&design, &args);
        for k in 1..=5 {
            let r = server.edit(&projection(k));
            assert_eq!(r.status, 200, "{}: {}", t.label, r.text());
            assert_eq!(r.json()["revision"], k);
        }
        server.kill9();
        assert_eq!(
            std::fs::read(&*design).unwrap(),
            original,
            "the file was written"
        );
        assert!(!design.with_file_name("design.json.journal").exists());

        let server = ServerProcess::start(&design, &args);
        let r = server.request("GET", "/design.json", &[], b"");
        assert_eq!(r.header("x-vesselcad-revision"), Some("5"), "{}", t.label);
        assert_eq!(r.json()["vessels"][0]["nozzles"][0]["projection"], 1550.0);
        let revisions = server.get_json("/revisions");
        let list = revisions["revisions"].as_array().unwrap();
        assert_eq!(list.len(), 6, "{}", t.label);
        assert_eq!(list[3]["message"], "edit");
        assert_eq!(
            list[3]["patch"][0]["path"],
            "/vessels/0/nozzles/0/projection"
        );
        let r = server.request("GET", "/design.json?rev=0", &[], b"");
        assert_eq!(r.header("x-vesselcad-revision"), Some("0"));
        let first = serde_json::to_value(load(&*design).unwrap()).unwrap();
        assert_eq!(r.json(), first);
        let r = server.request("GET", "/design.json?rev=9", &[], b"");
        assert_eq!(r.status, 400, "{}", r.text());
    }
}

#[test]
fn undo_and_redo_are_new_revisions() {
    for t in test_stores() {
        let design = design_copy("horizontal-drum.json", "store-undo");
        let server = ServerProcess::start(&design, &["--store", t.location.as_str()]);
        let at = |s: &ServerProcess| {
            s.get_json("/design.json")["vessels"][0]["nozzles"][0]["projection"].clone()
        };
        let before = at(&server);
        assert_eq!(server.request("POST", "/undo", JSON, b"").status, 409);
        assert_eq!(server.edit(&projection(1)).status, 200);
        assert_eq!(server.edit(&projection(2)).status, 200);
        let r = server.request("POST", "/undo", JSON, b"");
        assert_eq!(r.status, 200, "{}", r.text());
        assert_eq!(r.json()["revision"], 3);
        assert_eq!(at(&server), 1510.0);
        let r = server.request("POST", "/undo", JSON, b"");
        assert_eq!(r.json()["revision"], 4);
        assert_eq!(at(&server), before);
        let r = server.request("POST", "/redo", JSON, b"");
        assert_eq!(r.json()["revision"], 5, "{}", r.text());
        assert_eq!(at(&server), 1510.0);
        // A new edit ends the redo chain.
        assert_eq!(server.edit(&projection(7)).status, 200);
        assert_eq!(server.request("POST", "/redo", JSON, b"").status, 409);
        let log = server.get_json("/revisions");
        let messages: Vec<&str> = log["revisions"]
            .as_array()
            .unwrap()
            .iter()
            .map(|r| r["message"].as_str().unwrap())
            .collect();
        assert_eq!(
            &messages[1..],
            ["edit", "edit", "undo", "undo", "redo", "edit"],
            "{}",
            t.label
        );
    }
}

#[test]
fn without_a_store_there_is_no_history_but_undo_works() {
    let design = design_copy("horizontal-drum.json", "store-none");
    let server = ServerProcess::start(&design, &[]);
    assert_eq!(server.request("GET", "/revisions", &[], b"").status, 404);
    assert_eq!(server.edit(&projection(1)).status, 200);
    let r = server.request("POST", "/undo", JSON, b"");
    assert_eq!(r.status, 200, "{}", r.text());
    assert_eq!(r.json()["revision"], 2);
}

#[test]
fn an_old_journal_is_migrated_on_first_start() {
    for t in test_stores() {
        let design = design_copy("horizontal-drum.json", "store-migrate");
        let mut server = ServerProcess::start(&design, &[]);
        assert_eq!(server.edit(&projection(1)).status, 200);
        assert_eq!(server.edit(&projection(2)).status, 200);
        server.kill9();
        let journal = design.with_file_name("design.json.journal");
        assert!(journal.exists());
        let server = ServerProcess::start(&design, &["--store", t.location.as_str()]);
        let r = server.request("GET", "/design.json", &[], b"");
        assert_eq!(r.header("x-vesselcad-revision"), Some("2"), "{}", t.label);
        assert_eq!(r.json()["vessels"][0]["nozzles"][0]["projection"], 1520.0);
        assert!(!journal.exists());
        assert!(
            design
                .with_file_name("design.json.journal.migrated")
                .exists()
        );
        // One revision per journaled edit, each with its own design.
        let log = server.get_json("/revisions");
        let revisions = log["revisions"].as_array().unwrap();
        assert_eq!(revisions.len(), 3, "{log}");
        for (k, revision) in revisions.iter().enumerate().skip(1) {
            assert_eq!(
                revision["message"],
                format!("edit migrated from the journal (its revision {k})")
            );
            let at = server.get_json(&format!("/design.json?rev={k}"));
            assert_eq!(
                at["vessels"][0]["nozzles"][0]["projection"],
                1500.0 + 10.0 * k as f64,
                "{}",
                t.label
            );
        }
    }
}

#[test]
fn a_stale_server_gets_409_with_the_current_revision_then_catches_up() {
    // On SQLite nothing tells the second server, so its session is stale.
    let t = &test_stores()[0];
    let a = design_copy("horizontal-drum.json", "store-team-a");
    let b = design_copy("horizontal-drum.json", "store-team-b");
    let args = ["--store", t.location.as_str()];
    let one = ServerProcess::start(&a, &args);
    let two = ServerProcess::start(&b, &args);
    assert_eq!(one.edit(&projection(1)).status, 200);
    let r = two.edit(&projection(2));
    assert_eq!(r.status, 409, "{}", r.text());
    assert_eq!(r.json()["kind"], "conflict");
    assert_eq!(r.json()["revision"], 1);
    // The refused server took the winner's revision; an edit now goes on it.
    assert_eq!(
        two.get_json("/design.json")["vessels"][0]["nozzles"][0]["projection"],
        1510.0
    );
    let r = two.edit(&projection(3));
    assert_eq!(r.status, 200, "{}", r.text());
    assert_eq!(r.json()["revision"], 2);
}

#[test]
fn two_servers_on_postgres_stream_each_others_edits() {
    let Some(url) = postgres_url() else {
        eprintln!("VESSELCAD_TEST_PG is not set: skipped");
        return;
    };
    let t = postgres_store(&url);
    let a = design_copy("horizontal-drum.json", "store-pg-a");
    let b = design_copy("horizontal-drum.json", "store-pg-b");
    let args = ["--store", t.location.as_str()];
    let one = ServerProcess::start(&a, &args);
    let two = ServerProcess::start(&b, &args);
    let runtime = tokio::runtime::Builder::new_current_thread()
        .enable_all()
        .build()
        .unwrap();
    runtime.block_on(async {
        let url = format!("ws://{}/ws", two.address);
        let mut viewer = tokio_tungstenite::connect_async(url).await.unwrap().0;
        let hello = next_header(&mut viewer).await;
        assert_eq!(hello["revision"], 0);
        let address = one.address;
        let r = tokio::task::spawn_blocking(move || {
            server_support::request(
                address,
                "POST",
                "/edit",
                &[("content-type", "application/json")],
                projection(4).to_string().as_bytes(),
            )
        })
        .await
        .unwrap();
        assert_eq!(r.status, 200, "{}", r.text());
        // The viewer of the other server gets the edit as a delta.
        let delta = next_header(&mut viewer).await;
        assert_eq!(delta["revision"], 1, "{delta}");
        assert!(!delta["changed"].as_array().unwrap().is_empty(), "{delta}");
    });
    assert_eq!(
        two.get_json("/design.json")["vessels"][0]["nozzles"][0]["projection"],
        1540.0
    );
    let r = two.edit(&projection(5));
    assert_eq!(r.status, 200, "{}", r.text());
    assert_eq!(r.json()["revision"], 2);
}

#[test]
fn a_lost_database_connection_refuses_the_edit_then_reconnects() {
    let Some(url) = postgres_url() else {
        eprintln!("VESSELCAD_TEST_PG is not set: skipped");
        return;
    };
    let t = postgres_store(&url);
    let app = format!("vesselcad_lost_{}", std::process::id());
    let location = format!("{}&application_name={app}", t.location);
    let design = design_copy("horizontal-drum.json", "store-pg-lost");
    let server = ServerProcess::start(&design, &["--store", location.as_str()]);
    assert_eq!(server.edit(&projection(1)).status, 200);
    // The database ends the session's connection, as a restart or a failover
    // does (the follower's LISTEN connection is left alone: it reconnects by
    // itself, and would otherwise race the session to find the loss).
    let mut admin = postgres::Client::connect(&url, postgres::NoTls).unwrap();
    // The follower connects on its own thread: wait until it is listening, or
    // its connection (not yet showing `LISTEN`) would be ended with the session's.
    let listening = || {
        let rows = admin_count(
            &url,
            "SELECT count(*) FROM pg_stat_activity \
             WHERE application_name = $1 AND query LIKE 'LISTEN%'",
            &app,
        );
        rows == 1
    };
    let start = std::time::Instant::now();
    while !listening() {
        assert!(
            start.elapsed() < std::time::Duration::from_secs(20),
            "the follower never listened"
        );
        std::thread::sleep(std::time::Duration::from_millis(50));
    }
    let ended = admin
        .query(
            "SELECT pg_terminate_backend(pid) FROM pg_stat_activity \
             WHERE application_name = $1 AND query NOT LIKE 'LISTEN%'",
            &[&app],
        )
        .unwrap();
    assert_eq!(ended.len(), 1, "one session connection");
    let r = server.edit(&projection(2));
    assert_eq!(r.status, 503, "{}", r.text());
    assert_eq!(r.json()["kind"], "store_unavailable", "{}", r.text());
    assert_eq!(r.header("retry-after"), Some("1"));
    // Nothing was acknowledged: the session is still at revision 1.
    let now = server.request("GET", "/design.json", &[], b"");
    assert_eq!(now.header("x-vesselcad-revision"), Some("1"));
    assert_eq!(now.json()["vessels"][0]["nozzles"][0]["projection"], 1510.0);
    // The next edit reconnects and is stored as revision 2.
    let r = server.edit(&projection(3));
    assert_eq!(r.status, 200, "{}", r.text());
    assert_eq!(r.json()["revision"], 2);
    let log = server.get_json("/revisions");
    let revisions = log["revisions"].as_array().unwrap();
    assert_eq!(revisions.len(), 3, "{log}");
    let mut store = vesselcad::store::Store::open(&t.location).unwrap();
    let stored = store.design_at("design", 2).unwrap();
    assert_eq!(stored.vessels[0].nozzles[0].projection, 1530.0);
}

/// Runs a `count(*)` query with one text parameter on a fresh connection.
fn admin_count(url: &str, sql: &str, param: &str) -> i64 {
    let mut c = postgres::Client::connect(url, postgres::NoTls).unwrap();
    c.query_one(sql, &[&param]).unwrap().get(0)
}

#[test]
fn an_unreachable_store_stops_the_server_with_a_clear_error() {
    let design = design_copy("horizontal-drum.json", "store-down");
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_vesselcad"))
        .args([
            "serve",
            "--port",
            "0",
            "--store",
            "postgres://u:pw@127.0.0.1:1/db",
        ])
        .arg(&*design)
        .output()
        .unwrap();
    assert!(!out.status.success());
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.contains("cannot connect") && err.contains("u:***@127.0.0.1:1"),
        "{err}"
    );
    assert!(!err.contains("pw@"), "{err}");
}

/// The next text message (a hello or delta header) of a viewer socket.
async fn next_header<S>(ws: &mut S) -> Value
where
    S: futures_util::Stream<Item = Result<Message, tokio_tungstenite::tungstenite::Error>> + Unpin,
{
    loop {
        let message = tokio::time::timeout(TIMEOUT, ws.next())
            .await
            .expect("no message within the timeout")
            .expect("socket closed")
            .expect("socket error");
        if let Message::Text(text) = message {
            return serde_json::from_str(&text).unwrap();
        }
    }
}
