//! `vesselcad scan simulate` and `scan fit` through the binary: the JSON report
//! goes where `--json` says, and no output may overwrite an input.

mod common;

use std::path::Path;
use std::process::Command;

use common::scan::DRUM;

fn vesselcad(args: &[&str], dir: &Path) -> std::process::Output {
    Command::new(env!("CARGO_BIN_EXE_vesselcad"))
        .args(args)
        .current_dir(dir)
        .output()
        .expect("vesselcad runs")
}

#[test]
fn the_json_report_goes_where_asked_and_never_over_an_input() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    std::fs::write(d.join("drum.json"), DRUM).unwrap();
    let sim = vesselcad(
        &[
            "scan",
            "simulate",
            "drum.json",
            "--vessel",
            "V-1",
            "--density",
            "30",
            "--seed",
            "2",
            "--plant-frame",
            "-o",
            "scan.ply",
        ],
        d,
    );
    assert!(
        sim.status.success(),
        "{}",
        String::from_utf8_lossy(&sim.stderr)
    );
    // `-o drum.html --json drum.json` used to write drum.json over the design
    // (the report's name with .json); now each output is named, and an output
    // naming an input is refused before anything is written.
    for (option, value, what) in [
        ("--json", "drum.json", "design file"),
        ("--json", "scan.ply", "scan"),
        ("--glb", "./drum.json", "design file"),
        ("--json", "drum.html", "HTML report"),
    ] {
        let out = vesselcad(
            &[
                "scan",
                "fit",
                "drum.json",
                "--vessel",
                "V-1",
                "scan.ply",
                "--keep-frame",
                "-o",
                "drum.html",
                option,
                value,
            ],
            d,
        );
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{option} {value}: {err}");
        assert!(err.contains(option) && err.contains(what), "{err}");
        assert_eq!(std::fs::read_to_string(d.join("drum.json")).unwrap(), DRUM);
        assert!(!d.join("drum.html").exists());
    }
    let out = vesselcad(
        &[
            "scan",
            "fit",
            "drum.json",
            "--vessel",
            "V-1",
            "scan.ply",
            "--keep-frame",
            "-o",
            "drum.html",
            "--json",
            "report.json",
        ],
        d,
    );
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let report: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(d.join("report.json")).unwrap()).unwrap();
    assert_eq!(report["vessel"], "V-1");
    assert_eq!(std::fs::read_to_string(d.join("drum.json")).unwrap(), DRUM);
    assert!(d.join("drum.html").exists());
}
