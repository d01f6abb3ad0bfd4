//! The viewer page in a real browser: two headless Chromium pages (Debian's
//! `/usr/bin/chromium`, driven by npm `playwright-core` from tests/support) open
//! the page served by the real `vesselcad serve`; an edit made through page A's
//! parameter panel changes the geometry page B shows, and a bad value shows the
//! server's error in page A and changes nothing in page B; undo, adding a nozzle
//! and the typed editors go through the same pages; page B draws the edit from a
//! meshopt-compressed delta. The History panel lists a
//! store's revisions and its Undo button adds one; the view draws no frame while
//! idle.

mod server_support;

use std::path::Path;
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

use serde_json::Value;
use server_support::{ServerProcess, design_copy};

const MISSING: &str = "Chromium or playwright-core is missing: install Debian's chromium and run \
                       npm ci --prefix tests/support";

/// Runs tests/support/viewer-test.js; `None` when the browser or driver is not
/// installed (a failure under CI).
fn drive(server: &ServerProcess, args: &[&str]) -> Option<Value> {
    run_script("viewer-test.js", server, args)
}

/// Runs the script `name` of tests/support against `server`.
fn run_script(name: &str, server: &ServerProcess, args: &[&str]) -> Option<Value> {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let driver = root.join("tests/support/node_modules/playwright-core/package.json");
    if !driver.is_file() || !Path::new("/usr/bin/chromium").exists() {
        assert!(std::env::var_os("CI").is_none(), "{MISSING}");
        eprintln!("{MISSING}");
        return None;
    }
    let mut child = Command::new("node")
        .arg(root.join("tests/support").join(name))
        .arg(server.url())
        .args(args)
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("cannot run node");
    // The script stops itself after 90 s; this is the backstop.
    let start = Instant::now();
    while child.try_wait().unwrap().is_none() {
        if start.elapsed() > Duration::from_secs(120) {
            let _ = child.kill();
            panic!("{name} did not finish");
        }
        std::thread::sleep(Duration::from_millis(100));
    }
    let output = child.wait_with_output().unwrap();
    let stdout = String::from_utf8_lossy(&output.stdout);
    assert!(
        output.status.success(),
        "{name} failed: {stdout}\n{}",
        String::from_utf8_lossy(&output.stderr)
    );
    Some(serde_json::from_str(&stdout).unwrap_or_else(|e| panic!("not JSON ({e}): {stdout}")))
}

fn floats(v: &Value) -> Vec<f64> {
    v.as_array()
        .unwrap()
        .iter()
        .map(|x| x.as_f64().unwrap())
        .collect()
}

/// Sizes of a `[min xyz, max xyz]` box, largest first.
fn sizes(b: &[f64]) -> Vec<f64> {
    let mut s: Vec<f64> = (0..3).map(|k| b[k + 3] - b[k]).collect();
    s.sort_by(|a, b| b.total_cmp(a));
    s
}

#[test]
fn an_edit_in_one_page_changes_the_geometry_in_another() {
    let design = design_copy("horizontal-drum.json", "browser");
    let server = ServerProcess::start(&design, &[]);
    // Lengthen shell S1 from 7200 to 7600 mm through page A's panel (8000 would
    // bring nozzle N2 onto saddle SD2's wear plate); then try -5.
    let Some(report) = drive(&server, &["V-101/S1", "length", "7600", "-5"]) else {
        return;
    };
    assert_eq!(report["shown"], "7200", "the panel shows the design value");
    assert_eq!(report["revision0"], 0);
    assert_eq!(report["revision1"], 1);
    let before = sizes(&floats(&report["before"]));
    let after = sizes(&floats(&report["after"]));
    // glTF metres: the course is 0.4 m longer in page B, its diameter unchanged.
    assert!((before[0] - 7.2).abs() < 1e-3, "{before:?}");
    assert!((after[0] - 7.6).abs() < 1e-3, "{after:?}");
    assert!((after[1] - before[1]).abs() < 1e-6 && (after[2] - before[2]).abs() < 1e-6);
    // Page B drew that edit from a meshopt-compressed delta.
    let delta = &report["delta"];
    assert_eq!(delta["revision"], 1, "{report}");
    assert!(
        delta["extensions"]
            .as_array()
            .is_some_and(|e| e.iter().any(|x| x == "EXT_meshopt_compression")),
        "{delta}"
    );
    println!("page B's delta: {} bytes", delta["bytes"]);
    // Success is not shown as an error.
    assert_eq!(report["statusA"], "accepted as revision 1");
    assert_eq!(report["statusAError"], "");
    // The bad value: error shown in page A, nothing changed in page B.
    let error = report["errorText"].as_str().unwrap();
    assert!(
        error.starts_with("422:") && error.contains("length = -5"),
        "{error}"
    );
    assert_eq!(report["revision2"], 1);
    assert_eq!(report["afterBad"], report["after"]);
    assert_eq!(report["gaps"], 0, "page B missed a revision");
    assert!(
        report["drawingSrc"]
            .as_str()
            .unwrap()
            .starts_with("/drawing.svg?vessel=V-101"),
        "{report}"
    );
    // Ctrl+Z: the server's undo, or its error shown in red (no /undo route).
    let undo = &report["undo"];
    assert!(
        undo["revision"].as_u64() > Some(1)
            || undo["error"].as_str().is_some_and(|e| e.contains("404")),
        "{undo}"
    );
    // A nozzle added through page A's button reaches page B.
    let added = report["added"].as_array().unwrap();
    assert_eq!(added.len(), 1, "{report}");
    assert!(
        added[0].as_str().unwrap().starts_with("V-101/N"),
        "{report}"
    );
    assert_eq!(report["addError"], "");
    // The vessel's editors: its kind a drop-down, its liquid level in mm.
    assert_eq!(report["kindEditor"], 1);
    assert!(
        report["levelLabel"].as_str().unwrap().contains("(mm)"),
        "{report}"
    );
    if report["webgl"] == true {
        assert_eq!(
            report["pixelsChangedByEdit"], true,
            "the edit changed no pixel"
        );
        assert_eq!(
            report["pixelsChangedByAdd"], true,
            "the added nozzle changed no pixel"
        );
        let picked = report["picked"].as_str().unwrap();
        assert!(
            picked.starts_with("V-101/"),
            "clicking the view picked {picked:?}"
        );
    }
    let page_errors: Vec<&str> = report["consoleErrors"]
        .as_array()
        .unwrap()
        .iter()
        .filter_map(Value::as_str)
        // The refused edit answers 422; the undo without a route 404.
        .filter(|e| !e.contains("status of 422") && !e.contains("status of 404"))
        .collect();
    assert!(
        page_errors.is_empty(),
        "errors in the page: {page_errors:?}"
    );
}

#[test]
fn the_history_panel_lists_the_revisions_and_undo_adds_one() {
    let design = design_copy("horizontal-drum.json", "browser-history");
    let store = tempfile::tempdir().unwrap();
    let location = store.path().join("vesselcad.db").display().to_string();
    let server = ServerProcess::start(&design, &["--store", location.as_str()]);
    for k in 1..=2 {
        let patch = serde_json::json!([{ "op": "replace",
            "path": "/vessels/0/nozzles/0/projection", "value": 1500 + 10 * k }]);
        assert_eq!(server.edit(&patch).status, 200);
    }
    let Some(report) = run_script("history-test.js", &server, &[]) else {
        return;
    };
    assert_eq!(report["revision"], 2, "{report}");
    assert_eq!(report["undoError"], "", "{report}");
    assert_eq!(report["revisionAfter"], 3, "{report}");
    let revs = |rows: &Value| -> Vec<u64> {
        rows.as_array()
            .unwrap()
            .iter()
            .map(|r| r[0].as_u64().unwrap())
            .collect()
    };
    assert_eq!(revs(&report["before"]), [2, 1, 0], "{report}");
    assert_eq!(revs(&report["after"]), [3, 2, 1, 0], "{report}");
    let newest = report["after"][0][1].as_str().unwrap();
    assert!(
        newest.starts_with("undo ·") && newest.ends_with("JSON"),
        "{newest}"
    );
    assert!(
        report["after"][3][1]
            .as_str()
            .unwrap()
            .starts_with("import ")
    );
    assert_eq!(report["current"], "3", "{report}");
    assert_eq!(report["consoleErrors"], serde_json::json!([]), "{report}");
    // The view draws on demand: frames were drawn, none over 1.5 s of idle.
    if report["webgl"] == true {
        assert!(report["framesBefore"].as_u64() > Some(0), "{report}");
        assert_eq!(report["framesIdle"], 0, "{report}");
    }
}

#[test]
fn without_a_store_the_history_panel_says_so() {
    let design = design_copy("horizontal-drum.json", "browser-no-history");
    let server = ServerProcess::start(&design, &[]);
    let Some(report) = run_script("history-test.js", &server, &[]) else {
        return;
    };
    assert_eq!(report["before"], serde_json::json!([]), "{report}");
    assert!(
        report["note"].as_str().unwrap().contains("--store"),
        "{report}"
    );
}
