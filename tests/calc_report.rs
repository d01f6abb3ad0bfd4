//! `vesselcad calc` and the one weight model: the report renders as HTML and as
//! PDF (headless Chromium), and `info --json`, `calc --json` and the drawing
//! sheet's design data print the same weights and MAWP for every example vessel.

use std::path::Path;
use std::process::Command;

use serde_json::Value;

const EXAMPLES: [(&str, &str); 3] = [
    ("horizontal-drum", "V-101"),
    ("vertical-column", "C-201"),
    ("storage-tank", "TK-301"),
];

fn vesselcad(args: &[&str]) -> std::process::Output {
    let o = Command::new(env!("CARGO_BIN_EXE_vesselcad"))
        .args(args)
        .output()
        .unwrap();
    assert!(
        o.status.success(),
        "vesselcad {args:?}: {}",
        String::from_utf8_lossy(&o.stderr)
    );
    o
}

fn json(args: &[&str]) -> Value {
    serde_json::from_slice(&vesselcad(args).stdout).unwrap()
}

fn example(name: &str) -> String {
    format!("examples/designs/{name}.json")
}

/// Whether one text line of the SVG reads exactly `text`.
fn has_line(svg: &str, text: &str) -> bool {
    svg.lines().any(|l| l.trim() == text)
}

#[test]
fn info_calc_and_the_sheet_print_the_same_weights() {
    let dir = tempfile::tempdir().unwrap();
    for (name, tag) in EXAMPLES {
        let file = example(name);
        let design: Value = serde_json::from_str(&std::fs::read_to_string(&file).unwrap()).unwrap();
        assert_eq!(design["vessels"][0]["tag"], tag, "{name}");
        let info = json(&["info", &file, "--json"]);
        let o = &info["vessels"][0]["operating"];
        let calc = json(&["calc", &file, "--json"]);
        let w = &calc["vessels"][0]["weights"];
        for (a, b) in [
            ("metal_mass", "empty"),
            ("operating_mass", "operating"),
            ("test_mass", "test"),
            ("interior_volume", "capacity"),
        ] {
            assert_eq!(o[a], w[b], "{name}: info {a} vs calc {b}");
        }
        // The empty weight counts more than the walls: supports, nozzles, flanges.
        let (empty, walls) = (w["empty"].as_f64().unwrap(), w["walls"].as_f64().unwrap());
        assert!(empty > walls, "{name}: {empty} vs walls {walls}");
        let svg = dir.path().join(format!("{name}.svg"));
        vesselcad(&[
            "drawing",
            &file,
            "--vessel",
            tag,
            "-o",
            svg.to_str().unwrap(),
        ]);
        let svg = std::fs::read_to_string(svg).unwrap();
        for (label, value) in [
            ("WEIGHT EMPTY (ALL METAL)", w["empty"].as_f64().unwrap()),
            ("WEIGHT OPERATING", w["operating"].as_f64().unwrap()),
            ("WEIGHT TEST (FULL OF WATER)", w["test"].as_f64().unwrap()),
        ] {
            assert!(svg.contains(label), "{name}: {label}");
            let text = format!("{} kg", value.round());
            assert!(
                has_line(&svg, &text),
                "{name}: the sheet lacks {label} {text}"
            );
        }
        let capacity = format!("{:.2} m³", w["capacity"].as_f64().unwrap());
        assert!(has_line(&svg, &capacity), "{name}: capacity {capacity}");
        match calc["vessels"][0]["calculation"]["vessel"]["mawp"].as_f64() {
            Some(mawp) => {
                let text = format!("{} kPa(g)", (mawp * 1e3).round());
                assert!(has_line(&svg, &text), "{name}: MAWP {text}");
                assert_eq!(
                    info["vessels"][0]["calculation"]["mawp"].as_f64(),
                    Some(mawp)
                );
            }
            None => assert_eq!(name, "storage-tank", "only the tank has no MAWP"),
        }
    }
}

#[test]
fn the_report_renders_as_html_and_pdf() {
    let dir = tempfile::tempdir().unwrap();
    let html = dir.path().join("drum.html");
    vesselcad(&[
        "calc",
        &example("horizontal-drum"),
        "-o",
        html.to_str().unwrap(),
    ]);
    let page = std::fs::read_to_string(&html).unwrap();
    for part in [
        "<h2>V-101 — ASME VIII-1</h2>",
        "Design data",
        "UG-27(c)(1)",
        "t = P·R / (S·E − 0.6·P)",
        "UG-45",
        "MAWP at the top",
        "MDMT",
        "Hydrotest pressure",
        "Empty",
        "Operating",
        "Test",
        "Deficiencies",
    ] {
        assert!(page.contains(part), "the HTML report lacks {part:?}");
    }
    assert!(
        Path::new("/usr/bin/chromium").exists(),
        "/usr/bin/chromium is not installed (.ci/run installs Debian's chromium)"
    );
    let pdf = dir.path().join("column.pdf");
    vesselcad(&[
        "calc",
        &example("vertical-column"),
        "--vessel",
        "C-201",
        "-o",
        pdf.to_str().unwrap(),
    ]);
    let bytes = std::fs::read(&pdf).unwrap();
    assert!(bytes.starts_with(b"%PDF-"), "not a PDF");
    assert!(
        bytes.len() > 10_000,
        "a near-empty PDF: {} bytes",
        bytes.len()
    );
    let pages = bytes.windows(10).filter(|w| w == b"/Type /Pag").count();
    assert!(pages >= 2, "the PDF has no page ({pages} page objects)");
}

#[test]
fn check_lists_deficiencies_and_strict_fails_on_them() {
    // The example drum with its manway on a standard-wall neck: UG-45's t_b3 is
    // that wall less 12.5 % plus the 3 mm corrosion allowance, which the same
    // wall less 12.5 % cannot meet.
    let dir = tempfile::tempdir().unwrap();
    let text = std::fs::read_to_string(example("horizontal-drum")).unwrap();
    let std_manway = text.replace(
        r#""flange": "blind", "schedule": "40","#,
        r#""flange": "blind","#,
    );
    assert_ne!(text, std_manway, "the example's manway schedule moved");
    let drum = dir.path().join("drum.json");
    std::fs::write(&drum, std_manway).unwrap();
    let drum = drum.to_str().unwrap();
    let o = vesselcad(&["check", drum]);
    let text = String::from_utf8_lossy(&o.stdout);
    assert!(text.contains("deficiency: V-101/M1: neck wall"), "{text}");
    let strict = Command::new(env!("CARGO_BIN_EXE_vesselcad"))
        .args(["check", "--strict", drum])
        .output()
        .unwrap();
    assert_eq!(strict.status.code(), Some(1));
    let j = json(&["check", "--json", drum]);
    assert_eq!(j["valid"], true);
    assert!(!j["deficiencies"].as_array().unwrap().is_empty());
    let strict = Command::new(env!("CARGO_BIN_EXE_vesselcad"))
        .args(["check", "--strict", "--json", drum])
        .output()
        .unwrap();
    assert_eq!(strict.status.code(), Some(1));
}

/// Every shipped example is a sound design: `check --strict` finds no
/// deficiency in any file of `examples/designs/` (walls, nozzle necks and
/// reinforcement, flanges, supports, base rings).
#[test]
fn every_shipped_example_passes_check_strict() {
    let mut files: Vec<_> = std::fs::read_dir("examples/designs")
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|x| x == "json"))
        .collect();
    files.sort();
    assert!(files.len() >= 4, "{files:?}");
    for f in &files {
        let f = f.to_str().unwrap();
        let o = vesselcad(&["check", "--strict", f]);
        let text = String::from_utf8_lossy(&o.stdout);
        assert!(!text.contains("deficiency"), "{f}: {text}");
        let j = json(&["check", "--strict", "--json", f]);
        assert_eq!(
            j["deficiencies"].as_array().map(Vec::len),
            Some(0),
            "{f}: {j}"
        );
    }
}
