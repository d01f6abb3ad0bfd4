//! Drawings of several sheets: the legibility rule splits a column on A3 into
//! an elevation sheet and a sheet of the other views and adds detail views of
//! the nozzles too small to read; every sheet is numbered, laid out without
//! collisions and written as SVG, DXF (audited) and one PDF of as many pages.

mod common;

use std::path::Path;
use std::process::Command;

use common::examples::{EXAMPLES, example, example_path};
use glam::DVec2;
use vesselcad::drawing::{
    Item, Layer, MAX_ONE_SHEET_SCALE, Measure, Sheet, SheetOptions, SheetSize, layout_problems,
    legibility_problems, sheet, sheet_model, sheets, vessel_data,
};
use vesselcad::mesh::TessellationOptions;
use vesselcad::model::Model;

fn column() -> Model {
    sheet_model(
        &example("vertical-column"),
        "C-201",
        TessellationOptions::chord(1.0),
    )
    .unwrap()
    .0
}

fn texts(s: &Sheet) -> Vec<&str> {
    s.items
        .iter()
        .filter_map(|i| match i {
            Item::Text { text, .. } => Some(text.as_str()),
            _ => None,
        })
        .collect()
}

/// The column on A3: one sheet is 1:300 and breaks the rule; the drawing is
/// the elevation with the tables at 1:150 or finer, the other views on sheet 2
/// and detail sheets, numbered in their title blocks, and keeps the rule.
#[test]
fn the_column_on_a3_takes_several_legible_sheets() {
    let model = column();
    let data = vessel_data(&model, "C-201").unwrap();
    let options = SheetOptions::sized(SheetSize::IsoA3);
    let one = sheet(&model, "C-201", &options).unwrap();
    assert!(one.scale > MAX_ONE_SHEET_SCALE, "1:{}", one.scale);
    assert!(
        !legibility_problems(&data, std::slice::from_ref(&one)).is_empty(),
        "the one sheet at 1:{} passes the rule",
        one.scale
    );
    let all = sheets(&model, "C-201", &options).unwrap();
    assert!(all.len() >= 3, "{} sheets", all.len());
    let problems = legibility_problems(&data, &all);
    assert!(problems.is_empty(), "{problems:#?}");
    assert_eq!(all[0].shown, [true, false, false, false]);
    assert!(all[0].scale <= MAX_ONE_SHEET_SCALE, "1:{}", all[0].scale);
    assert_eq!(all[1].shown, [false, true, true, true]);
    assert!(all[2..].iter().all(|s| !s.details.is_empty()));
    for (i, s) in all.iter().enumerate() {
        assert_eq!((s.number, s.of), (i + 1, all.len()));
        let t = texts(s);
        let number = format!("{} OF {}", i + 1, all.len());
        assert!(t.contains(&number.as_str()), "sheet {}: no {number}", i + 1);
        // The schedule on sheet 1 only; the title block on every sheet.
        assert_eq!(t.contains(&"NOZZLE SCHEDULE"), i == 0, "sheet {}", i + 1);
        assert!(t.contains(&"VESSEL"), "sheet {}", i + 1);
    }
    // Each detail is marked and lettered on the elevation, titled with its scale.
    let details: Vec<_> = all.iter().flat_map(|s| &s.details).collect();
    assert_eq!(details.len(), all[0].detail_marks.len());
    for d in &details {
        let mark = all[0]
            .detail_marks
            .iter()
            .find(|m| m.label == d.label)
            .expect("a mark on the elevation");
        assert!(texts(&all[0]).contains(&d.label.as_str()));
        // The same model circle on both.
        let parent = mark.radius * all[0].scale;
        assert!((parent - d.radius * d.scale).abs() < 1e-6 * parent);
        let title = format!("DETAIL {} (SCALE 1:{})", d.label, d.scale);
        assert!(
            all.iter().any(|s| texts(s).contains(&title.as_str())),
            "{title}"
        );
    }
}

/// Distance from `p` to the nearest segment of a visible outline of `items`.
fn distance_to_outlines(items: &[Item], p: DVec2) -> f64 {
    items
        .iter()
        .filter_map(|i| match i {
            Item::Line {
                layer: Layer::Outline,
                points,
                ..
            } => Some(points),
            _ => None,
        })
        .flat_map(|ps| ps.windows(2))
        .map(|w| {
            let (a, b) = (w[0], w[1]);
            let d = b - a;
            let t = if d.length_squared() > 0.0 {
                ((p - a).dot(d) / d.length_squared()).clamp(0.0, 1.0)
            } else {
                0.0
            };
            (a + d * t - p).length()
        })
        .fold(f64::INFINITY, f64::min)
}

/// A detail is the elevation scaled: every outline vertex inside a detail's
/// circle, taken back through the detail's scale onto its mark on sheet 1,
/// lies on the elevation's outlines; and a dimension drawn in a detail
/// measures its model value at the detail's scale.
#[test]
fn details_are_the_elevation_enlarged() {
    let model = column();
    let all = sheets(&model, "C-201", &SheetOptions::sized(SheetSize::IsoA3)).unwrap();
    let parent = &all[0];
    let mut checked = 0;
    let mut dimensioned = 0;
    for s in &all[1..] {
        for d in &s.details {
            let mark = parent
                .detail_marks
                .iter()
                .find(|m| m.label == d.label)
                .unwrap();
            let ratio = d.scale / parent.scale;
            for item in &s.items {
                let Item::Line {
                    layer: Layer::Outline,
                    points,
                    ..
                } = item
                else {
                    continue;
                };
                for &p in points {
                    if (p - d.centre).length() > 0.98 * d.radius {
                        continue;
                    }
                    let q = mark.centre + (p - d.centre) * ratio;
                    let off = distance_to_outlines(&parent.items, q);
                    // The parent's lines are the same model lines at its scale.
                    assert!(
                        off < 1e-6,
                        "detail {}: {p:?} lands {off} mm off the elevation",
                        d.label
                    );
                    checked += 1;
                }
            }
            for dim in &s.dimensions {
                if let Measure::Linear {
                    a,
                    b,
                    vertical,
                    value,
                    ..
                } = dim.measure
                    && (a - d.centre).length() <= d.radius
                {
                    let drawn = if vertical { b.y - a.y } else { b.x - a.x }.abs();
                    assert!(
                        (drawn * d.scale - value).abs() < 1e-6 * value.max(1.0),
                        "detail {} {}: drawn {drawn} mm at 1:{} is not {value}",
                        d.label,
                        dim.text,
                        d.scale
                    );
                    dimensioned += 1;
                }
            }
        }
    }
    assert!(checked > 20, "{checked} detail vertices checked");
    assert!(dimensioned > 0, "no detail carries a dimension");
}

/// Every sheet of every example vessel on every size: no colliding text, every
/// nozzle legible by the rule.
#[test]
fn every_sheet_of_every_example_is_laid_out_and_legible() {
    let mut all = Vec::new();
    for name in EXAMPLES {
        let design = example(name);
        for v in &design.vessels {
            let (model, _) = sheet_model(&design, &v.tag, TessellationOptions::chord(2.0)).unwrap();
            let data = vessel_data(&model, &v.tag).unwrap();
            for size in SheetSize::ALL {
                let set = sheets(&model, &v.tag, &SheetOptions::sized(size)).unwrap();
                for s in &set {
                    all.extend(
                        layout_problems(s)
                            .into_iter()
                            .map(|p| format!("{} {size:?} sheet {}: {p}", v.tag, s.number)),
                    );
                }
                all.extend(
                    legibility_problems(&data, &set)
                        .into_iter()
                        .map(|p| format!("{} {size:?}: {p}", v.tag)),
                );
            }
        }
    }
    assert!(
        all.is_empty(),
        "{} problems:\n{}",
        all.len(),
        all.join("\n")
    );
}

/// `vesselcad drawing` writes sheet 1 under the name given and sheet n beside
/// it as `name-n.svg`, a DXF per sheet likewise (each audited by ezdxf with
/// nothing to fix), and one PDF of as many pages.
#[test]
fn the_drawing_command_writes_every_sheet() {
    let dir = std::env::temp_dir().join(format!("vesselcad-sheets-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let run = |out: &str, dxf: Option<&str>| {
        let mut c = Command::new(env!("CARGO_BIN_EXE_vesselcad"));
        c.arg("drawing")
            .arg(example_path("vertical-column"))
            .args(["--vessel", "C-201", "--sheet", "a3", "-o"])
            .arg(dir.join(out));
        if let Some(d) = dxf {
            c.arg("--dxf").arg(dir.join(d));
        }
        let o = c.output().unwrap();
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        String::from_utf8_lossy(&o.stdout).into_owned()
    };
    let model = column();
    let n = sheets(&model, "C-201", &SheetOptions::sized(SheetSize::IsoA3))
        .unwrap()
        .len();
    let summary = run("col.svg", Some("col.dxf"));
    assert!(summary.contains(&format!("{n} sheets")), "{summary}");
    assert!(!dir.join("col-1.svg").exists());
    let named = |k: usize, ext: &str| {
        if k == 1 {
            dir.join(format!("col.{ext}"))
        } else {
            dir.join(format!("col-{k}.{ext}"))
        }
    };
    for k in 1..=n {
        let svg = std::fs::read_to_string(named(k, "svg")).unwrap();
        assert!(svg.contains(&format!("{k} OF {n}")), "sheet {k}");
        assert_eq!(svg.contains("NOZZLE SCHEDULE"), k == 1, "sheet {k}");
        let dxf = named(k, "dxf");
        assert!(dxf.exists(), "{}", dxf.display());
        audit(&dxf);
    }
    assert!(!dir.join(format!("col-{}.svg", n + 1)).exists());
    // Standard output takes one sheet only: refused with the reason.
    let o = Command::new(env!("CARGO_BIN_EXE_vesselcad"))
        .arg("drawing")
        .arg(example_path("vertical-column"))
        .args(["--vessel", "C-201", "--sheet", "a3", "-o", "-"])
        .output()
        .unwrap();
    assert!(!o.status.success());
    assert!(String::from_utf8_lossy(&o.stderr).contains("sheets"));
    // One PDF, a page per sheet.
    run("col.pdf", None);
    let pdf = std::fs::read(dir.join("col.pdf")).unwrap();
    let text = String::from_utf8_lossy(&pdf);
    let pages = text.matches("/Type /Page").count() - text.matches("/Type /Pages").count();
    assert_eq!(pages, n, "{n} sheets, {pages} PDF pages");
    std::fs::remove_dir_all(&dir).ok();
}

const PYTHON: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/target/occt-venv/bin/python");

/// ezdxf's recover and audit of `path` find nothing to fix.
fn audit(path: &Path) {
    assert!(
        Path::new(PYTHON).exists(),
        "{PYTHON} missing (.ci/run makes it)"
    );
    let script = r#"
import sys
from ezdxf import recover
doc, auditor = recover.readfile(sys.argv[1])
a = doc.audit()
print("fixes", len(auditor.fixes) + len(a.fixes), "errors", len(auditor.errors) + len(a.errors))
for f in list(auditor.fixes) + list(a.fixes) + list(auditor.errors) + list(a.errors):
    print(" ", f.message)
print("viewports", len(doc.paperspace().query("VIEWPORT")))
"#;
    let out = Command::new(PYTHON)
        .args(["-c", script])
        .arg(path)
        .output()
        .unwrap();
    let report = String::from_utf8_lossy(&out.stdout);
    assert!(
        out.status.success() && report.contains("fixes 0 errors 0"),
        "{}: {report}{}",
        path.display(),
        String::from_utf8_lossy(&out.stderr)
    );
}
