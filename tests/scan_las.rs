//! LAS and LAZ scans: written and read back through the `las` crate in chunks,
//! `scan simulate -o x.las|x.laz` writes them, and `scan fit` reports on them
//! exactly what it reports on a PLY of the same points. A truncated or foreign
//! file is an error naming the file, never a panic.

mod common;

use std::path::Path;
use std::process::Command;

use common::scan::DRUM;
use glam::DVec3;
use vesselcad::scan::ScanError;
use vesselcad::scan::points::{CHUNK, PointFormat, load_points, read_points, write_points};

fn vesselcad(args: &[&str], dir: &Path) -> std::process::Output {
    Command::new(env!("CARGO_BIN_EXE_vesselcad"))
        .args(args)
        .current_dir(dir)
        .output()
        .expect("vesselcad runs")
}

fn ok(out: &std::process::Output) {
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
}

#[test]
fn las_and_laz_round_trip_in_chunks() {
    let dir = tempfile::tempdir().unwrap();
    // More than one chunk, site-like coordinates (hundreds of metres in mm).
    let n = CHUNK + 4321;
    let points: Vec<DVec3> = (0..n)
        .map(|i| {
            let t = i as f64;
            DVec3::new(
                4.5e5 + (t * 0.37).sin() * 3000.0,
                -2.2e5 + t * 0.01,
                120.0 + (t * 0.011).cos() * 9000.0,
            )
        })
        .collect();
    for name in ["a.las", "b.LAZ"] {
        let path = dir.path().join(name);
        let format = PointFormat::of_path(&path, false);
        assert_eq!(
            format,
            if name.ends_with("las") {
                PointFormat::Las
            } else {
                PointFormat::Laz
            }
        );
        write_points(&path, format, &points).unwrap();
        let mut chunks = Vec::new();
        let count = read_points(&path, |c| chunks.push(c.len())).unwrap();
        assert_eq!(count, n as u64, "{name}");
        assert_eq!(chunks, vec![CHUNK, 4321], "{name}");
        let back = load_points(&path).unwrap();
        for (a, b) in back.iter().zip(&points) {
            // 0.001 mm steps: half a step either way.
            assert!((*a - *b).abs().max_element() <= 0.0005 + 1e-9, "{name}");
        }
    }
    let las = std::fs::metadata(dir.path().join("a.las")).unwrap().len();
    let laz = std::fs::metadata(dir.path().join("b.LAZ")).unwrap().len();
    assert!(laz < las / 2, "LAZ {laz} bytes vs LAS {las}");
}

#[test]
fn a_truncated_or_foreign_las_is_an_error_naming_the_file() {
    let dir = tempfile::tempdir().unwrap();
    let points: Vec<DVec3> = (0..500).map(|i| DVec3::splat(i as f64)).collect();
    for name in ["t.las", "t.laz"] {
        let path = dir.path().join(name);
        write_points(&path, PointFormat::of_path(&path, false), &points).unwrap();
        let bytes = std::fs::read(&path).unwrap();
        for keep in [40, bytes.len() - 700] {
            std::fs::write(&path, &bytes[..keep]).unwrap();
            match load_points(&path) {
                Err(ScanError::Points { path: p, .. }) | Err(ScanError::Io { path: p, .. }) => {
                    assert_eq!(p, path, "{name} cut at {keep}")
                }
                other => panic!("{name} cut at {keep}: {other:?}"),
            }
        }
    }
}

#[test]
fn scan_fit_reports_the_same_on_las_laz_and_ply_of_the_same_points() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    std::fs::write(d.join("drum.json"), DRUM).unwrap();
    let defects = "dent=25mm@EL4000/90°";
    for out in ["scan.las", "scan.laz"] {
        ok(&vesselcad(
            &[
                "scan",
                "simulate",
                "drum.json",
                "--vessel",
                "V-1",
                "--defects",
                defects,
                "--density",
                "60",
                "--seed",
                "4",
                "-o",
                out,
            ],
            d,
        ));
    }
    // The same draw, quantized alike.
    let las = load_points(&d.join("scan.las")).unwrap();
    assert_eq!(las, load_points(&d.join("scan.laz")).unwrap());
    write_points(&d.join("scan.ply"), PointFormat::PlyBinary, &las).unwrap();
    let mut reports = Vec::new();
    for scan in ["scan.ply", "scan.las", "scan.laz"] {
        let json = format!("{scan}.json");
        ok(&vesselcad(
            &[
                "scan",
                "fit",
                "drum.json",
                "--vessel",
                "V-1",
                scan,
                "-o",
                "r.html",
                "--json",
                &json,
            ],
            d,
        ));
        reports.push(std::fs::read_to_string(d.join(&json)).unwrap());
    }
    let report: serde_json::Value = serde_json::from_str(&reports[0]).unwrap();
    assert_eq!(report["points"], las.len());
    assert!(
        reports[0].contains("dent"),
        "the dent is reported: {}",
        reports[0]
    );
    assert_eq!(reports[0], reports[1], "PLY vs LAS");
    assert_eq!(reports[0], reports[2], "PLY vs LAZ");
}
