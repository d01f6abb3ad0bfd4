//! Calculation results in the live viewer: `GET /calc.json` names each
//! deficiency's part or nozzle by stable id, and in a real browser (headless
//! Chromium through tests/support/calc-viewer-test.js) a deficient nozzle is
//! drawn red with its figures listed, and turns back when an edit clears it.
//! The design is the example drum with its manway on a standard-wall neck,
//! which UG-45 refuses with 3 mm of corrosion allowance.

mod server_support;

use std::path::Path;
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

use serde_json::{Value, json};
use server_support::{DesignCopy, ServerProcess, design_copy};

const MISSING: &str = "Chromium or playwright-core is missing: install Debian's chromium and run \
                       npm ci --prefix tests/support";

/// The drum with manway M1 (nozzle 7) on a standard-wall neck.
fn deficient_drum() -> DesignCopy {
    let copy = design_copy("horizontal-drum.json", "calc-viewer");
    let text = std::fs::read_to_string(&*copy).unwrap();
    let std_manway = text.replace(
        r#""flange": "blind", "schedule": "40","#,
        r#""flange": "blind","#,
    );
    assert_ne!(text, std_manway, "the example's manway schedule moved");
    std::fs::write(&*copy, std_manway).unwrap();
    copy
}

/// The patch that gives M1 its Sch 40 neck back.
fn sound_patch() -> Value {
    json!([{ "op": "add", "path": "/vessels/0/nozzles/7/schedule", "value": "40" }])
}

/// `id`'s deficiency texts in a /calc.json answer.
fn texts<'a>(calc: &'a Value, id: &str) -> Vec<&'a str> {
    calc["deficiencies"]
        .as_array()
        .unwrap()
        .iter()
        .filter(|d| d["id"] == id)
        .map(|d| d["text"].as_str().unwrap())
        .collect()
}

#[test]
fn calc_json_names_the_deficient_nozzle_and_follows_edits() {
    let design = deficient_drum();
    let server = ServerProcess::start(&design, &[]);
    let calc = server.get_json("/calc.json");
    assert_eq!(calc["revision"], 0);
    let m1 = texts(&calc, "V-101/M1");
    assert_eq!(m1.len(), 1, "{calc}");
    assert!(
        m1[0].starts_with("M1: neck wall 9.53 mm less 12.5 % = 8.34 mm")
            && m1[0].contains("UG-45's 11.34 mm"),
        "{}",
        m1[0]
    );
    assert_eq!(calc["deficiencies"].as_array().unwrap().len(), 1, "{calc}");
    let r = server.edit(&sound_patch());
    assert_eq!(r.status, 200, "{}", r.text());
    let calc = server.get_json("/calc.json");
    assert_eq!(calc["revision"], 1);
    assert_eq!(calc["deficiencies"], json!([]), "{calc}");
}

#[test]
fn a_deficient_nozzle_is_red_in_the_viewer_with_its_figures() {
    let design = deficient_drum();
    let server = ServerProcess::start(&design, &[]);
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let driver = root.join("tests/support/node_modules/playwright-core/package.json");
    if !driver.is_file() || !Path::new("/usr/bin/chromium").exists() {
        assert!(std::env::var_os("CI").is_none(), "{MISSING}");
        eprintln!("{MISSING}");
        return;
    }
    let mut child = Command::new("node")
        .arg(root.join("tests/support/calc-viewer-test.js"))
        .arg(server.url())
        .args(["V-101/M1", "V-101/S1", &sound_patch().to_string()])
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("cannot run node");
    // The script stops itself after 90 s; this is the backstop.
    let start = Instant::now();
    while child.try_wait().unwrap().is_none() {
        if start.elapsed() > Duration::from_secs(120) {
            let _ = child.kill();
            panic!("calc-viewer-test.js did not finish");
        }
        std::thread::sleep(Duration::from_millis(100));
    }
    let output = child.wait_with_output().unwrap();
    let stdout = String::from_utf8_lossy(&output.stdout);
    assert!(
        output.status.success(),
        "calc-viewer-test.js failed: {stdout}\n{}",
        String::from_utf8_lossy(&output.stderr)
    );
    let report: Value =
        serde_json::from_str(&stdout).unwrap_or_else(|e| panic!("not JSON ({e}): {stdout}"));
    let before = &report["before"];
    assert_eq!(before["colour"], "d01010", "{report}");
    assert_ne!(before["sound"], "d01010", "{report}");
    let list = before["deficiencies"].as_array().unwrap();
    assert_eq!(list.len(), 1, "{report}");
    assert_eq!(list[0][0], "V-101/M1");
    let line = list[0][1].as_str().unwrap();
    assert!(
        line.starts_with("V-101/M1: neck wall 9.53 mm") && line.contains("UG-45's 11.34 mm"),
        "{line}"
    );
    assert_eq!(report["picked"], "V-101/M1", "a click on the line picks it");
    assert_eq!(report["status"], 200);
    let after = &report["after"];
    assert_eq!(after["deficiencies"], json!([]), "{report}");
    assert!(
        after["colour"].is_string() && after["colour"] != "d01010",
        "{report}"
    );
    assert!(
        after["note"].as_str().unwrap().starts_with("No deficiency"),
        "{report}"
    );
    assert_eq!(report["consoleErrors"], json!([]), "{report}");
}
