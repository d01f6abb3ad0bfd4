//! A vessel's drawing as a set of sheets, by the legibility rule
//! ([`super::legibility`]): sheet 1 with every view when that is legible, else
//! sheet 1 with the elevation and the tables and sheet 2 with the plan, side
//! elevation and isometric; then as many sheets of detail views as the details
//! need. Every sheet carries the title block with `SHEET n OF N`; the design
//! data, nozzle schedule and notes are on sheet 1.

use super::compose::{Content, compose_content, details_per_sheet};
use super::data::VesselData;
use super::legibility::{MAX_ONE_SHEET_SCALE, details};
use super::sheet::{Sheet, SheetOptions};

/// The front elevation alone.
const ELEVATION: [bool; 4] = [true, false, false, false];

/// The plan, side elevation and isometric.
const OTHER_VIEWS: [bool; 4] = [false, true, true, true];

/// Composes every sheet of one vessel's drawing.
pub fn compose_sheets(data: &VesselData, options: &SheetOptions) -> Vec<Sheet> {
    let one = compose_content(data, options, &Content::single());
    let split = one.scale > MAX_ONE_SHEET_SCALE;
    let first_views = if split { ELEVATION } else { [true; 4] };
    let elevation_scale = if split {
        let alone = Content {
            shown: ELEVATION,
            ..Content::single()
        };
        compose_content(data, options, &alone).scale
    } else {
        one.scale
    };
    let specs = details(data, elevation_scale, options.size);
    let per_sheet = details_per_sheet(data, &specs, options.size).max(1);
    let detail_sheets: Vec<_> = specs.chunks(per_sheet).collect();
    let of = 1 + usize::from(split) + detail_sheets.len();
    let mut contents = vec![Content {
        shown: first_views,
        full_tables: true,
        number: (1, of),
        marks: specs.clone(),
        details: Vec::new(),
    }];
    if split {
        contents.push(Content {
            shown: OTHER_VIEWS,
            full_tables: false,
            number: (2, of),
            marks: Vec::new(),
            details: Vec::new(),
        });
    }
    for chunk in detail_sheets {
        contents.push(Content {
            shown: [false; 4],
            full_tables: false,
            number: (contents.len() + 1, of),
            marks: Vec::new(),
            details: chunk.to_vec(),
        });
    }
    contents
        .iter()
        .map(|c| compose_content(data, options, c))
        .collect()
}
