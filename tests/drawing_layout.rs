//! The layout of every sheet: on every example vessel and on generated vessels,
//! on every sheet size, the one-sheet drawing and every sheet of the drawing's
//! set (elevation, other views, details) have no two texts overlapping, no text
//! crossing a view's outline and every text on the paper. (`examples/drawing_layout.rs`
//! runs the same check over 100 generated vessels.)

mod common;

use common::examples::{EXAMPLES, example};
use vesselcad::design::Design;
use vesselcad::drawing::{SheetOptions, SheetSize, layout_problems, sheet, sheet_model, sheets};
use vesselcad::mesh::TessellationOptions;
use vesselcad::plant::generate_plant;

/// Every layout problem of vessel `tag`'s sheets on every size.
fn problems(design: &Design, tag: &str) -> Vec<String> {
    let (model, _) = sheet_model(design, tag, TessellationOptions::chord(2.0)).unwrap();
    let mut out = Vec::new();
    for size in SheetSize::ALL {
        let options = SheetOptions::sized(size);
        let one = sheet(&model, tag, &options).unwrap();
        out.extend(
            layout_problems(&one)
                .into_iter()
                .map(|p| format!("{tag} {size:?}: {p}")),
        );
        for s in sheets(&model, tag, &options).unwrap() {
            out.extend(
                layout_problems(&s)
                    .into_iter()
                    .map(|p| format!("{tag} {size:?} sheet {} of {}: {p}", s.number, s.of)),
            );
        }
    }
    out
}

#[test]
fn example_sheets_have_no_colliding_text() {
    let mut all = Vec::new();
    for name in EXAMPLES {
        let design = example(name);
        for v in &design.vessels {
            all.extend(problems(&design, &v.tag));
        }
    }
    assert!(
        all.is_empty(),
        "{} problems:\n{}",
        all.len(),
        all.join("\n")
    );
}

#[test]
fn generated_vessel_sheets_have_no_colliding_text() {
    let design = generate_plant(4, 39).unwrap();
    let mut all = Vec::new();
    for v in &design.vessels {
        all.extend(problems(&design, &v.tag));
    }
    assert!(
        all.is_empty(),
        "{} problems:\n{}",
        all.len(),
        all.join("\n")
    );
}
