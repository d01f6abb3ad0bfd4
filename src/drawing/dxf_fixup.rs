//! What the `dxf` crate (0.6) does not write, added to its output as group-code
//! pairs: handles on the table heads (readers repair them otherwise), a handle
//! of its own for each `ENDBLK` (the crate repeats its `BLOCK`'s), the
//! layers' line weights (its `LineWeight` cannot be set to a value), and the
//! paper-space `VIEWPORT` entities (it has no such entity): the sheet's own
//! viewport, one on the drawing area at the sheet's scale and, for an enlarged
//! plan, one on the plan at its scale, and one on each detail view at its scale.
//! New handles continue from `$HANDSEED`,
//! which is moved past them.

use glam::DVec2;

use super::DrawingError;
use super::dxf_spaces::{line_weight, spaces};
use super::sheet::{Layer, Sheet};

/// The layer of the viewports' frames (not plotted).
pub const VIEWPORT_LAYER: &str = "VIEWPORTS";

/// One group code and its value, as written.
type Pair = (i32, String);

/// Parses DXF text into pairs.
fn pairs(text: &str) -> Result<Vec<Pair>, DrawingError> {
    let lines: Vec<&str> = text.lines().collect();
    lines
        .chunks(2)
        .filter(|c| c.len() == 2)
        .map(|c| {
            let code = c[0].trim().parse::<i32>().map_err(|e| {
                DrawingError::Dxf(format!("group code {:?} in the written DXF: {e}", c[0]))
            })?;
            Ok((code, c[1].to_string()))
        })
        .collect()
}

fn pair(code: i32, value: impl ToString) -> Pair {
    (code, value.to_string())
}

/// A viewport's group codes: centre and size on paper, the model point at its
/// centre and the model height it shows.
fn viewport(
    handle: u64,
    owner: &str,
    id: i32,
    centre: DVec2,
    size: DVec2,
    view_centre: DVec2,
    view_height: f64,
) -> Vec<Pair> {
    vec![
        pair(0, "VIEWPORT"),
        pair(5, format!("{handle:X}")),
        pair(330, owner),
        pair(100, "AcDbEntity"),
        pair(67, 1),
        pair(8, VIEWPORT_LAYER),
        pair(100, "AcDbViewport"),
        pair(10, centre.x),
        pair(20, centre.y),
        pair(30, 0.0),
        pair(40, size.x),
        pair(41, size.y),
        pair(68, if id == 1 { 1 } else { 2 }),
        pair(69, id),
        pair(12, view_centre.x),
        pair(22, view_centre.y),
        pair(13, 0.0),
        pair(23, 0.0),
        pair(14, 10.0),
        pair(24, 10.0),
        pair(15, 10.0),
        pair(25, 10.0),
        pair(16, 0.0),
        pair(26, 0.0),
        pair(36, 1.0),
        pair(17, 0.0),
        pair(27, 0.0),
        pair(37, 0.0),
        pair(42, 50.0),
        pair(43, 0.0),
        pair(44, 0.0),
        pair(45, view_height),
        pair(50, 0.0),
        pair(51, 0.0),
        pair(72, 1000),
        pair(90, 32864),
        pair(1, ""),
        pair(281, 0),
        pair(71, 1),
        pair(74, 0),
        pair(110, 0.0),
        pair(120, 0.0),
        pair(130, 0.0),
        pair(111, 1.0),
        pair(121, 0.0),
        pair(131, 0.0),
        pair(112, 0.0),
        pair(122, 1.0),
        pair(132, 0.0),
        pair(79, 0),
        pair(146, 0.0),
    ]
}

/// Adds table handles, layer line weights and viewports to the `dxf` crate's
/// output `text` of `sheet`.
pub fn fix_up(text: &str, sheet: &Sheet) -> Result<String, DrawingError> {
    let mut p = pairs(text)?;
    let missing = |what: &str| DrawingError::Dxf(format!("the written DXF has no {what}"));
    let seed_at = p
        .iter()
        .position(|(c, v)| *c == 9 && v.trim() == "$HANDSEED")
        .map(|i| i + 1)
        .ok_or_else(|| missing("$HANDSEED"))?;
    let mut next = u64::from_str_radix(p[seed_at].1.trim(), 16)
        .map_err(|e| DrawingError::Dxf(format!("$HANDSEED: {e}")))?;
    let mut fresh = || {
        let h = next;
        next += 1;
        h
    };
    // Table heads: `0 TABLE`, `2 NAME`, then a handle and owner.
    let mut i = 0;
    while i + 2 < p.len() {
        if p[i].0 == 0 && p[i].1.trim() == "TABLE" && p[i + 1].0 == 2 && p[i + 2].0 != 5 {
            let h = fresh();
            p.insert(i + 2, pair(5, format!("{h:X}")));
            p.insert(i + 3, pair(330, 0));
        }
        i += 1;
    }
    // Every ENDBLK its own handle (the crate repeats its BLOCK's).
    for i in 0..p.len().saturating_sub(1) {
        if p[i].0 == 0 && p[i].1.trim() == "ENDBLK" && p[i + 1].0 == 5 {
            let h = fresh();
            p[i + 1].1 = format!("{h:X}");
        }
    }
    // Layer line weights.
    let weight_of = |name: &str| {
        Layer::ALL
            .iter()
            .find(|l| l.name() == name)
            .map(|&l| line_weight(l))
            .or((name == VIEWPORT_LAYER).then_some(13))
    };
    let mut i = 0;
    while i < p.len() {
        if p[i].0 == 0 && p[i].1.trim() == "LAYER" {
            let end = (i + 1..p.len()).find(|&j| p[j].0 == 0).unwrap_or(p.len());
            let name = (i + 1..end)
                .find(|&j| p[j].0 == 2)
                .map(|j| p[j].1.trim().to_string());
            if let Some(w) = name.as_deref().and_then(weight_of) {
                match (i + 1..end).find(|&j| p[j].0 == 370) {
                    Some(j) => p[j].1 = format!("{w:>6}"),
                    None => p.insert(end, pair(370, format!("{w:>6}"))),
                }
            }
        }
        i += 1;
    }
    // Viewports, at the end of the ENTITIES section, owned by *PAPER_SPACE.
    let owner = (0..p.len())
        .find(|&j| p[j].0 == 2 && p[j].1.trim().eq_ignore_ascii_case("*PAPER_SPACE"))
        .and_then(|j| {
            (0..j)
                .rev()
                .take_while(|&k| p[k].0 != 0)
                .find(|&k| p[k].0 == 5)
                .map(|k| p[k].1.trim().to_string())
        })
        .ok_or_else(|| missing("*PAPER_SPACE block record"))?;
    let entities = (1..p.len())
        .find(|&j| p[j].0 == 2 && p[j].1.trim() == "ENTITIES" && p[j - 1].1.trim() == "SECTION")
        .ok_or_else(|| missing("ENTITIES section"))?;
    let end = (entities..p.len())
        .find(|&j| p[j].0 == 0 && p[j].1.trim() == "ENDSEC")
        .ok_or_else(|| missing("end of the ENTITIES section"))?;
    let paper = sheet.size.dimensions();
    let spaces = spaces(sheet);
    let (main, plan) = (spaces[1], spaces[2]);
    let area = sheet_area(sheet);
    let mut vps = viewport(fresh(), &owner, 1, paper / 2.0, paper, paper / 2.0, paper.y);
    let c = 0.5 * (area.0 + area.1);
    vps.extend(viewport(
        fresh(),
        &owner,
        2,
        c,
        area.1 - area.0,
        main.offset + c * main.factor,
        (area.1.y - area.0.y) * main.factor,
    ));
    if sheet.factors[1] > 1.0 {
        let r = sheet.plan_region;
        let c = 0.5 * (r.min + r.max);
        vps.extend(viewport(
            fresh(),
            &owner,
            3,
            c,
            r.size(),
            plan.offset + c * plan.factor,
            r.size().y * plan.factor,
        ));
    }
    for (k, d) in sheet.details.iter().enumerate() {
        let space = spaces[3 + k];
        let r = d.region;
        let c = 0.5 * (r.min + r.max);
        vps.extend(viewport(
            fresh(),
            &owner,
            4 + k as i32,
            c,
            r.size(),
            space.offset + c * space.factor,
            r.size().y * space.factor,
        ));
    }
    p.splice(end..end, vps);
    let seed = next;
    p[seed_at].1 = format!("{seed:X}");
    let mut out = String::with_capacity(text.len() + 4096);
    for (code, value) in p {
        out.push_str(&format!("{code:>3}\r\n{value}\r\n"));
    }
    Ok(out)
}

/// The drawing area (left of the tables, inside the border), mm.
fn sheet_area(sheet: &Sheet) -> (DVec2, DVec2) {
    let paper = sheet.size.dimensions();
    let margin = sheet.tables.min.y;
    (
        DVec2::splat(margin),
        DVec2::new(sheet.tables.min.x, paper.y - margin),
    )
}
