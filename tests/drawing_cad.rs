//! The sheet for CAD and print: the DXF's model space measures millimetres
//! (`$INSUNITS` = 4) with real DIMENSION entities whose definition points are
//! the dimensioned model distance apart, its layers carry line weights, its
//! paper space holds the border, tables and viewports at the sheet's scale, and
//! ezdxf audits it with nothing to fix; `vesselcad drawing -o sheet.pdf` prints
//! a PDF page of the sheet's size.

mod common;

use std::path::Path;
use std::process::Command;

use common::examples::example;
use dxf::entities::EntityType;
use vesselcad::drawing::{Measure, SheetOptions, SheetSize, sheet, to_dxf_bytes};
use vesselcad::mesh::TessellationOptions;
use vesselcad::model::Model;

const PYTHON: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/target/occt-venv/bin/python");

#[test]
fn dxf_model_space_measures_millimetres_with_real_dimensions() {
    let model =
        Model::from_design(&example("horizontal-drum"), TessellationOptions::chord(1.0)).unwrap();
    let s = sheet(&model, "V-101", &SheetOptions::sized(SheetSize::IsoA3)).unwrap();
    let bytes = to_dxf_bytes(&s).unwrap();
    let drawing = dxf::Drawing::load(&mut bytes.as_slice()).expect("DXF reads back");
    assert_eq!(
        drawing.header.default_drawing_units,
        dxf::enums::Units::Millimeters
    );
    let mut linear = 0;
    let mut ordinate = 0;
    for e in drawing.entities() {
        match &e.specific {
            EntityType::RotatedDimension(d) => {
                linear += 1;
                assert_eq!(d.dimension_base.dimension_style_name, "VESSELCAD");
                assert!(
                    drawing
                        .blocks()
                        .any(|b| b.name == d.dimension_base.block_name && !b.entities.is_empty()),
                    "dimension block {} missing",
                    d.dimension_base.block_name
                );
            }
            EntityType::OrdinateDimension(_) => ordinate += 1,
            _ => {}
        }
    }
    let linear_on_sheet = s
        .dimensions
        .iter()
        .filter(|d| matches!(d.measure, Measure::Linear { .. }))
        .count();
    assert_eq!(linear, linear_on_sheet);
    assert_eq!(ordinate, s.dimensions.len() - linear_on_sheet);
    // T/T 7300: its two definition points are 7300 model mm apart along x.
    let tt = drawing
        .entities()
        .find_map(|e| match &e.specific {
            EntityType::RotatedDimension(d) if d.dimension_base.text == "T/T <>" => Some(d),
            _ => None,
        })
        .expect("the T/T dimension is a DIMENSION entity");
    let run = (tt.definition_point_3.x - tt.definition_point_2.x).abs();
    assert!((run - 7300.0).abs() < 1e-6, "T/T measures {run} mm");
    // Every handle is unique (the dxf crate gives an ENDBLK its BLOCK's).
    let mut handles = std::collections::BTreeSet::new();
    let lines: Vec<&str> = std::str::from_utf8(&bytes).unwrap().lines().collect();
    for pair in lines.chunks(2) {
        if pair.len() == 2 && pair[0].trim() == "5" {
            assert!(
                handles.insert(pair[1].trim()),
                "handle {} repeated",
                pair[1]
            );
        }
    }
    // Layers with line weights, HIDDEN and CENTER line types.
    let text = String::from_utf8(bytes.clone()).unwrap();
    assert!(text.contains("HIDDEN") && text.contains("CENTER"));
    // Paper space holds the border and tables; ° is %%d.
    assert!(drawing.entities().any(|e| e.common.is_in_paper_space));
    assert!(text.contains("%%d"));
    assert!(!text.contains("\\U+"), "no \\U+ escapes");
    // ezdxf: layers' weights, viewports, and an audit with nothing to fix.
    assert!(
        Path::new(PYTHON).exists(),
        "{PYTHON} missing (.ci/run makes the venv and installs ezdxf)"
    );
    let path = std::env::temp_dir().join(format!("vesselcad-cad-{}.dxf", std::process::id()));
    std::fs::write(&path, &bytes).unwrap();
    let script = r#"
import sys, ezdxf
from ezdxf import recover
doc, auditor = recover.readfile(sys.argv[1])
a = doc.audit()
print("fixes", len(auditor.fixes) + len(a.fixes), "errors", len(auditor.errors) + len(a.errors))
for f in list(auditor.fixes) + list(a.fixes) + list(auditor.errors) + list(a.errors):
    print(" ", f.message)
w = {l.dxf.name: l.dxf.lineweight for l in doc.layers}
print("weights", w["OUTLINE"], w["HIDDEN"], w["CENTER"], w["DIMENSIONS"])
print("units", doc.header.get("$INSUNITS"))
ps = doc.paperspace()
print("viewports", len(ps.query("VIEWPORT")))
print("dimensions", len(doc.modelspace().query("DIMENSION")))
"#;
    let out = Command::new(PYTHON)
        .args(["-c", script])
        .arg(&path)
        .output()
        .unwrap();
    std::fs::remove_file(&path).ok();
    let report = format!(
        "{}{}",
        String::from_utf8_lossy(&out.stdout),
        String::from_utf8_lossy(&out.stderr)
    );
    // Every handle once (ezdxf warns of a repeated one and validates).
    assert!(!report.contains("non-unique"), "{report}");
    assert!(
        out.status.success(),
        "ezdxf failed (is it installed?): {}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert!(report.contains("fixes 0 errors 0"), "{report}");
    assert!(report.contains("weights 50 25 18 18"), "{report}");
    assert!(report.contains("units 4"), "{report}");
    assert!(!report.contains("viewports 0"), "{report}");
}

#[test]
fn the_drawing_command_prints_a_pdf_of_the_sheets_size() {
    let dir = std::env::temp_dir().join(format!("vesselcad-pdf-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let pdf = dir.join("drum.pdf");
    let out = Command::new(env!("CARGO_BIN_EXE_vesselcad"))
        .arg("drawing")
        .arg(common::examples::example_path("horizontal-drum"))
        .args(["--vessel", "V-101", "--sheet", "a3", "-o"])
        .arg(&pdf)
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let bytes = std::fs::read(&pdf).unwrap();
    assert!(bytes.starts_with(b"%PDF-"), "not a PDF");
    let text = String::from_utf8_lossy(&bytes);
    // One page, A3 landscape: 420 × 297 mm = 1190.55 × 841.89 pt.
    let media = text
        .split("/MediaBox")
        .nth(1)
        .and_then(|rest| rest.split(']').next())
        .expect("a MediaBox");
    let numbers: Vec<f64> = media
        .trim_start_matches([' ', '['])
        .split_whitespace()
        .filter_map(|n| n.parse().ok())
        .collect();
    assert_eq!(numbers.len(), 4, "{media}");
    assert!((numbers[2] - 1190.55).abs() < 2.0, "{media}");
    assert!((numbers[3] - 841.89).abs() < 2.0, "{media}");
    std::fs::remove_dir_all(&dir).ok();
}
