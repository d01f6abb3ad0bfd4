//! Drawing sheets: the nozzle schedule lists exactly the model's nozzles, the
//! title block comes from the design file, dimensions do not overlap each other or
//! the views, the SVG is well-formed XML and the DXF reads back with its layers.

mod common;

use common::examples::example;
use std::collections::BTreeSet;

use vesselcad::design::{DesignError, parse};
use vesselcad::drawing::{
    HiddenLines, Item, Layer, Sheet, SheetOptions, SheetSize, sheet, sheet_svg, to_dxf_bytes,
    to_svg,
};
use vesselcad::mesh::TessellationOptions;
use vesselcad::model::{Edit, Model};
use vesselcad::project::ViewKind;

fn model(name: &str) -> Model {
    Model::from_design(&example(name), TessellationOptions::chord(0.5)).unwrap()
}

const EXAMPLES: [(&str, &str); 3] = [
    ("vertical-column", "C-201"),
    ("horizontal-drum", "V-101"),
    ("storage-tank", "TK-301"),
];

#[test]
fn the_nozzle_schedule_lists_exactly_the_models_nozzles() {
    for (name, tag) in EXAMPLES {
        let mut m = model(name);
        let s = sheet(&m, tag, &SheetOptions::default()).unwrap();
        let marks: Vec<&str> = s.schedule.iter().map(|r| r.cells[0].as_str()).collect();
        let design = m.design();
        let expected: Vec<&str> = design.vessels[0]
            .nozzles
            .iter()
            .map(|n| n.mark.as_str())
            .collect();
        assert_eq!(marks, expected, "{name}");
        for (row, n) in s.schedule.iter().zip(&design.vessels[0].nozzles) {
            assert_eq!(row.cells[11], vesselcad::drawing::format_mm(n.projection));
            assert_eq!(row.cells[3], format!("CL {}", n.rating));
            assert_eq!(row.cells[1], "1");
            assert!(["WN", "SO", "BLIND"].contains(&row.cells[5].as_str()));
            assert!(row.cells[6].starts_with(&n.schedule), "{row:?}");
            match &n.pad {
                Some(p) => assert_eq!(
                    row.cells[7],
                    format!(
                        "{}×{}",
                        vesselcad::drawing::format_mm(p.od),
                        vesselcad::drawing::format_mm(p.thickness)
                    )
                ),
                None => assert_eq!(row.cells[7], "—"),
            }
        }
        // Remove one nozzle (one no note points at): the schedule follows.
        let gone = expected
            .iter()
            .find(|m| !design.vessels[0].notes.iter().any(|n| n.target == **m))
            .unwrap()
            .to_string();
        m.edit(Edit::RemoveNozzle {
            vessel: tag.into(),
            mark: gone.clone(),
        })
        .unwrap();
        let s = sheet(&m, tag, &SheetOptions::default()).unwrap();
        assert_eq!(s.schedule.len(), expected.len() - 1);
        assert!(s.schedule.iter().all(|r| r.cells[0] != gone));
        let svg = to_svg(&s);
        assert!(
            !svg.contains(&format!(">{gone}<")),
            "{gone} still drawn in {name}"
        );
    }
}

fn text_of(sheet: &Sheet) -> BTreeSet<String> {
    sheet
        .items
        .iter()
        .filter_map(|i| match i {
            Item::Text { text, .. } => Some(text.clone()),
            _ => None,
        })
        .collect()
}

#[test]
fn the_title_block_and_design_data_come_from_the_design_file() {
    let mut design = example("vertical-column");
    let v = &mut design.vessels[0];
    v.drawing.number = Some("D-201-001".into());
    v.drawing.title = Some("CRUDE STABILISER".into());
    v.drawing.revision = Some("B".into());
    v.drawing.date = Some("2026-11-23".into());
    // Loads and saves canonically with the new fields.
    let text = vesselcad::design::to_canonical_json(&design);
    assert_eq!(parse(&text).unwrap(), design);
    let m = Model::from_design(&design, TessellationOptions::chord(0.5)).unwrap();
    let s = sheet(&m, "C-201", &SheetOptions::default()).unwrap();
    let texts = text_of(&s);
    for t in [
        "D-201-001",
        "CRUDE STABILISER",
        "B",
        "2026-11-23",
        "350 kPa(g)",
        "180 °C",
        "3 mm",
        "SA-516-70",
        "ANSI D",
    ] {
        assert!(texts.contains(t), "{t:?} missing from the sheet");
    }
    // The title block's signature rows and revision history, blank where no
    // value is known.
    for t in [
        "DRAWN",
        "CHECKED",
        "APPROVED",
        "REVISIONS",
        "DESCRIPTION",
        "ISSUED",
    ] {
        assert!(texts.contains(t), "{t:?} missing from the title block");
    }
    // Design data from the calculation: code, MAWP, hydrotest and MDMT rows.
    for t in [
        "CODE",
        "MAWP (HOT & CORRODED, TOP)",
        "HYDROTEST (UG-99(b), TOP)",
    ] {
        assert!(texts.contains(t), "{t:?} missing from the design data");
    }
    assert!(texts.iter().any(|t| t.starts_with("MDMT")), "MDMT row");
    assert!(texts.iter().any(|t| t.ends_with(" m³")), "volume");
    assert!(texts.iter().any(|t| t.ends_with(" kg")), "empty weight");
    // The revision triangle: a closed three-point border line.
    assert!(s.items.iter().any(|i| matches!(i,
        Item::Line { layer: Layer::Border, points, closed: true } if points.len() == 3)));
}

#[test]
fn bad_title_block_data_is_refused_with_its_field_named() {
    for (field, value, rule) in [
        ("date", "\"2026-02-30\"", "calendar date"),
        ("revision", "\"ABCDEFGHIJ\"", "at most 8"),
        ("number", "\"  \"", "must not be empty"),
    ] {
        let text = format!(
            r#"{{"format": "vesselcad/1", "vessels": [{{"tag": "V-1", "kind": "vertical",
            "drawing": {{"{field}": {value}}},
            "parts": [{{"shell": {{"id": "S1", "od": 1000, "length": 2000}}}}]}}]}}"#
        );
        let err = parse(&text).unwrap_err();
        let DesignError::Invalid(violations) = &err else {
            panic!("{field}: {err}");
        };
        assert_eq!(violations.len(), 1, "{field}: {err}");
        assert_eq!(violations[0].path, format!("vessels[0].drawing.{field}"));
        assert!(violations[0].rule.contains(rule), "{field}: {err}");
    }
    // An unknown field is refused too.
    let text = r#"{"format": "vesselcad/1", "vessels": [{"tag": "V-1", "kind": "vertical",
        "drawing": {"sheet": "A1"},
        "parts": [{"shell": {"id": "S1", "od": 1000, "length": 2000}}]}]}"#;
    assert!(parse(text).is_err());
}

#[test]
fn dimensions_do_not_overlap_each_other_or_the_views() {
    for (name, tag) in EXAMPLES {
        let m = model(name);
        for size in SheetSize::ALL {
            let s = sheet(&m, tag, &SheetOptions::sized(size)).unwrap();
            assert!(s.dimensions.len() >= 5, "{name} {size:?}");
            let paper = size.dimensions();
            for (i, a) in s.dimensions.iter().enumerate() {
                for b in &s.dimensions[i + 1..] {
                    assert!(
                        !a.text_box.overlaps(&b.text_box, 0.01),
                        "{name} {size:?}: {:?} overlaps {:?}",
                        a.text,
                        b.text
                    );
                }
                for (k, view) in s.view_boxes.iter().enumerate() {
                    for r in [&a.text_box, &a.line_box] {
                        assert!(
                            !r.overlaps(view, 0.01),
                            "{name} {size:?}: {:?} overlaps the {:?} view",
                            a.text,
                            ViewKind::ALL[k]
                        );
                    }
                }
                assert!(a.text_box.min.x >= 0.0 && a.text_box.max.x <= paper.x);
                assert!(a.text_box.min.y >= 0.0 && a.text_box.max.y <= paper.y);
            }
            // The views do not overlap each other.
            for i in 0..4 {
                for j in i + 1..4 {
                    assert!(
                        !s.view_boxes[i].overlaps(&s.view_boxes[j], 0.0),
                        "{name} {size:?}"
                    );
                }
            }
        }
    }
    // The overall dimension is the tangent-to-tangent length.
    let m = model("horizontal-drum");
    let s = sheet(&m, "V-101", &SheetOptions::default()).unwrap();
    assert!(s.dimensions.iter().any(|d| d.text == "T/T 7300"));
    assert!(s.dimensions.iter().any(|d| d.text == "OD 2400 (S1)"));
    assert!(s.dimensions.iter().any(|d| d.text.starts_with("SADDLES ")));
    assert!(s.dimensions.iter().any(|d| d.text == "N1 POS 800"));
    // Each head's depth runs from its tangent line to its crown: the line is as
    // long as its text says (the first head's once ran from the other tangent
    // line, 7300 mm long, labelled 650).
    let heads: Vec<_> = s
        .dimensions
        .iter()
        .filter(|d| d.text.starts_with("HEAD "))
        .collect();
    assert_eq!(heads.len(), 2);
    for d in heads {
        let said: f64 = d.text["HEAD ".len()..].parse().unwrap();
        let drawn = d.line_box.size().max_element() * s.scale;
        assert!((drawn - said).abs() < 0.5, "{}: drawn {drawn} mm", d.text);
        assert!(said > 500.0 && said < 800.0, "{}", d.text);
    }
}

#[test]
fn svg_is_well_formed_and_dxf_reads_back_with_its_layers() {
    for (name, tag) in EXAMPLES {
        let m = model(name);
        let options =
            SheetOptions::sized(SheetSize::AnsiB).with_hidden(ViewKind::Iso, HiddenLines::Omitted);
        let s = sheet(&m, tag, &options).unwrap();
        let svg = to_svg(&s);
        let doc = roxmltree::Document::parse(&svg).expect("well-formed XML");
        let root = doc.root_element();
        assert_eq!(root.tag_name().name(), "svg");
        assert_eq!(root.attribute("width"), Some("431.8mm"));
        for layer in [
            "OUTLINE",
            "HIDDEN",
            "CENTER",
            "DIMENSIONS",
            "TEXT",
            "BORDER",
        ] {
            let group = doc
                .descendants()
                .find(|n| n.attribute("id") == Some(layer))
                .unwrap_or_else(|| panic!("{name}: no {layer} group"));
            assert!(
                group.children().any(|c| c.is_element()),
                "{name}: {layer} empty"
            );
        }
        let bytes = to_dxf_bytes(&s).unwrap();
        let drawing = dxf::Drawing::load(&mut bytes.as_slice()).expect("DXF reads back");
        assert_eq!(drawing.header.version, dxf::enums::AcadVersion::R2000);
        let layers: BTreeSet<String> = drawing.layers().map(|l| l.name.clone()).collect();
        for layer in ["OUTLINE", "HIDDEN", "CENTER", "DIMENSIONS", "TEXT"] {
            assert!(layers.contains(layer), "{name}: DXF layer {layer} missing");
        }
        let line_types: BTreeSet<String> = drawing.line_types().map(|l| l.name.clone()).collect();
        assert!(line_types.contains("HIDDEN") && line_types.contains("CENTER"));
        let on = |layer: &str| {
            drawing
                .entities()
                .filter(|e| e.common.layer == layer)
                .count()
        };
        assert!(
            on("OUTLINE") > 50 && on("HIDDEN") > 5 && on("TEXT") > 50,
            "{name}"
        );
        let texts = drawing
            .entities()
            .filter(|e| matches!(e.specific, dxf::entities::EntityType::Text(_)))
            .count();
        // Dimension texts are in their dimensions' blocks.
        let block_texts: usize = drawing
            .blocks()
            .map(|b| {
                b.entities
                    .iter()
                    .filter(|e| matches!(e.specific, dxf::entities::EntityType::Text(_)))
                    .count()
            })
            .sum();
        let sheet_texts = s
            .items
            .iter()
            .filter(|i| matches!(i, Item::Text { .. }))
            .count();
        assert_eq!(texts + block_texts, sheet_texts);
    }
}

#[test]
fn omitted_hidden_lines_leave_that_view_only() {
    let m = model("vertical-column");
    let all = sheet(&m, "C-201", &SheetOptions::default()).unwrap();
    let some = sheet(
        &m,
        "C-201",
        &SheetOptions::default().with_hidden(ViewKind::Front, HiddenLines::Omitted),
    )
    .unwrap();
    let hidden_in = |s: &Sheet, k: usize| {
        s.items
            .iter()
            .filter(|i| match i {
                Item::Line {
                    layer: Layer::Hidden,
                    points,
                    ..
                } => s.view_boxes[k].contains(points[0]),
                _ => false,
            })
            .count()
    };
    assert!(hidden_in(&all, 0) > 0);
    assert_eq!(hidden_in(&some, 0), 0);
    assert_eq!(hidden_in(&some, 2), hidden_in(&all, 2));
}

#[test]
fn unknown_vessels_and_unbuilt_models_are_errors() {
    let m = model("storage-tank");
    let err = sheet_svg(&m, "NOPE", &SheetOptions::default()).unwrap_err();
    assert!(err.to_string().contains("NOPE"));
    let mut fresh = Model::new(TessellationOptions::chord(0.5)).unwrap();
    fresh
        .apply(Edit::ReplaceDesign(example("storage-tank")))
        .unwrap();
    let err = sheet_svg(&fresh, "TK-301", &SheetOptions::default()).unwrap_err();
    assert!(err.to_string().contains("update"), "{err}");
}

#[test]
fn the_drawing_command_writes_svg_and_dxf() {
    let dir = std::env::temp_dir().join(format!("vesselcad-drawing-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let svg = dir.join("drum.svg");
    let dxf = dir.join("drum.dxf");
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_vesselcad"))
        .args([
            "drawing",
            concat!(
                env!("CARGO_MANIFEST_DIR"),
                "/examples/designs/horizontal-drum.json"
            ),
        ])
        .args(["--vessel", "V-101", "-o"])
        .arg(&svg)
        .arg("--dxf")
        .arg(&dxf)
        .args(["--sheet", "a3", "--omit-hidden", "iso"])
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let text = std::fs::read_to_string(&svg).unwrap();
    assert!(roxmltree::Document::parse(&text).is_ok());
    assert!(text.contains("420mm"));
    assert!(dxf::Drawing::load_file(&dxf).is_ok());
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_vesselcad"))
        .args([
            "drawing",
            concat!(
                env!("CARGO_MANIFEST_DIR"),
                "/examples/designs/horizontal-drum.json"
            ),
        ])
        .args(["--vessel", "V-999", "-o"])
        .arg(&svg)
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(1));
    assert!(String::from_utf8_lossy(&out.stderr).contains("V-999"));
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn notes_follow_their_targets() {
    let mut m = model("vertical-column");
    let note_at = |m: &Model| {
        let s = sheet(m, "C-201", &SheetOptions::default()).unwrap();
        s.items
            .iter()
            .find_map(|i| match i {
                Item::Text { text, at, .. } if text == "Internal feed pipe by others" => Some(*at),
                _ => None,
            })
            .expect("note T3 drawn")
    };
    let before = note_at(&m);
    let mut n1 = m.design().vessels[0]
        .nozzles
        .iter()
        .find(|n| n.mark == "N1")
        .cloned()
        .unwrap();
    n1.elevation = Some(9000.0);
    m.edit(Edit::SetNozzle {
        vessel: "C-201".into(),
        nozzle: n1,
    })
    .unwrap();
    let after = note_at(&m);
    let s = sheet(&m, "C-201", &SheetOptions::default()).unwrap();
    // 1000 mm lower at the sheet's scale.
    assert!((before.x - after.x).abs() < 1e-9);
    assert!(
        ((before.y - after.y) - 1000.0 / s.scale).abs() < 1e-6,
        "{before} → {after}"
    );
}

/// The length a placed linear dimension is drawn at, in model mm.
fn drawn_length(s: &Sheet, d: &vesselcad::drawing::PlacedDimension) -> f64 {
    let k = ViewKind::ALL.iter().position(|v| *v == d.view).unwrap();
    d.line_box.size().max_element() * s.scale / s.factors[k]
}

#[test]
fn course_lengths_base_ring_and_side_view_projections_are_dimensioned() {
    let m = model("vertical-column");
    let s = sheet(&m, "C-201", &SheetOptions::default()).unwrap();
    let find = |text: &str| {
        s.dimensions
            .iter()
            .find(|d| d.text == text)
            .unwrap_or_else(|| panic!("no dimension {text:?} in {:?}", texts(&s)))
    };
    // The courses and the reducer as a chain that adds up to the T/T length,
    // each drawn as long as it says.
    let chain = ["S1 12000", "R1 900", "S2 8000"];
    let mut total = 0.0;
    for text in chain {
        let d = find(text);
        assert_eq!(d.view, ViewKind::Front);
        let said: f64 = text.rsplit(' ').next().unwrap().parse().unwrap();
        assert!((drawn_length(&s, d) - said).abs() < 0.5, "{text}");
        total += said;
    }
    // With the heads' straight flanges (inside the tangent lines), the chain
    // closes on the T/T length.
    let design = m.design();
    let flanges: f64 = design.vessels[0]
        .parts
        .iter()
        .filter_map(|p| match p {
            vesselcad::design::PartDesign::Head(h) => Some(h.straight_flange),
            _ => None,
        })
        .sum();
    assert!(flanges > 0.0);
    assert_eq!(format!("T/T {}", total + flanges), find("T/T 21000").text);
    // The skirt's base ring: the skirt's OD plus twice the ring's width.
    let ring = design.vessels[0]
        .parts
        .iter()
        .find_map(|p| match p {
            vesselcad::design::PartDesign::Skirt(s) => Some(s.base_ring_width),
            _ => None,
        })
        .unwrap();
    assert!(ring > 0.0);
    let d = find("BASE RING OD 2300");
    assert!((drawn_length(&s, d) - 2300.0).abs() < 0.5);
    // Shell nozzles the elevation foreshortens (at 0° and 180°) have their
    // projection on the side elevation, at true length; the others do not.
    let side: Vec<_> = s
        .dimensions
        .iter()
        .filter(|d| d.view == ViewKind::Side)
        .collect();
    let mut expected: Vec<String> = design.vessels[0]
        .nozzles
        .iter()
        .filter(|n| n.elevation.is_some() && [0.0, 180.0].contains(&n.orientation))
        .map(|n| format!("{} {}", n.mark, vesselcad::drawing::format_mm(n.projection)))
        .collect();
    let mut got: Vec<String> = side.iter().map(|d| d.text.clone()).collect();
    expected.sort();
    got.sort();
    assert!(!expected.is_empty());
    assert_eq!(got, expected);
    for d in side {
        let said: f64 = d.text.rsplit(' ').next().unwrap().parse().unwrap();
        assert!((drawn_length(&s, d) - said).abs() < 0.5, "{}", d.text);
    }
    // A one-course drum has no chain (the T/T is the course), but its side
    // nozzles are dimensioned on the end view.
    let m = model("horizontal-drum");
    let s = sheet(&m, "V-101", &SheetOptions::default()).unwrap();
    assert!(!s.dimensions.iter().any(|d| d.text.starts_with("S1 ")));
    let side: BTreeSet<&str> = s
        .dimensions
        .iter()
        .filter(|d| d.view == ViewKind::Side)
        .map(|d| d.text.as_str())
        .collect();
    assert_eq!(side, BTreeSet::from(["N6 1450", "N7 1450"]));
}

fn texts(s: &Sheet) -> Vec<&str> {
    s.dimensions.iter().map(|d| d.text.as_str()).collect()
}

#[test]
fn schedule_headers_are_whole_on_every_sheet_size() {
    for (name, tag) in EXAMPLES {
        let m = model(name);
        for size in SheetSize::ALL {
            let s = sheet(&m, tag, &SheetOptions::sized(size)).unwrap();
            let all = text_of(&s);
            for header in vesselcad::drawing::SCHEDULE_COLUMNS {
                assert!(all.contains(header), "{name} {size:?}: {header} cut");
            }
        }
    }
}

/// The drum's boot B1 (OD 610, 900 below the shell, at position 4000): its OD,
/// length and position are dimensioned, each drawn at its model length.
#[test]
fn the_boot_is_dimensioned() {
    let m = model("horizontal-drum");
    let s = sheet(&m, "V-101", &SheetOptions::default()).unwrap();
    for (text, value) in [("BOOT OD 610 (B1)", 610.0), ("BOOT 900 (B1)", 900.0)] {
        let d = s
            .dimensions
            .iter()
            .find(|d| d.text == text)
            .unwrap_or_else(|| panic!("no {text:?} dimension"));
        let drawn = drawn_length(&s, d);
        assert!((drawn - value).abs() < 1e-6, "{text}: drawn {drawn}");
    }
    assert!(
        s.dimensions.iter().any(|d| d.text == "B1 POS 4000"),
        "no boot position"
    );
}
