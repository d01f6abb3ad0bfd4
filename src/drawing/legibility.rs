//! The legibility rule: when a drawing takes more than one sheet, and which
//! parts of the elevation get enlarged detail views (the thesis's details A, B, …).
//!
//! The rule, in paper millimetres:
//! 1. All four views share the first sheet when the sheet's scale is
//!    [`MAX_ONE_SHEET_SCALE`] or finer. Coarser (a tall column on A3 comes out
//!    at 1:300), the first sheet holds the elevation alone with the tables, drawn
//!    as large as the sheet allows, and a second sheet holds the plan, side
//!    elevation and isometric.
//! 2. A plan smaller than the sheet's minimum plan size is drawn at a larger
//!    scale of its own (see `compose`).
//! 3. Every nozzle's neck is at least [`MIN_NOZZLE_PAPER`] across on the
//!    elevation; a smaller one gets a detail view at the coarsest standard scale
//!    that draws it at least [`MIN_DETAIL_NOZZLE_PAPER`] across. A detail's
//!    circle takes in the other small nozzles near it; details go on sheets of
//!    their own after the views, as many as the sheet's grid holds.
//!
//! [`legibility_problems`] checks a drawing against the rule.

use glam::{DVec2, DVec3};

use super::data::{NozzleData, VesselData};
use super::layout::enlarged_scale;
use super::sheet::{Sheet, SheetSize};

/// The coarsest scale (the `n` of 1:n) at which all four views share one
/// sheet: at 1:150 the outline pen (0.45 mm) covers 68 mm of model, the outside
/// diameter of a 2 in nozzle, so anything coarser loses the small nozzles in
/// their own outlines.
pub const MAX_ONE_SHEET_SCALE: f64 = 150.0;

/// The smallest nozzle neck drawn without a detail, paper mm: below 1 mm the
/// neck's two outlines (0.45 mm each) run into one line.
pub const MIN_NOZZLE_PAPER: f64 = 1.0;

/// How large a detail draws the smallest nozzle it shows, paper mm at least.
pub const MIN_DETAIL_NOZZLE_PAPER: f64 = 3.0;

/// Radius of a detail's circle on its own sheet, mm.
pub fn detail_radius(size: SheetSize) -> f64 {
    match size {
        SheetSize::AnsiB | SheetSize::IsoA3 => 30.0,
        SheetSize::AnsiD | SheetSize::IsoA1 => 50.0,
    }
}

/// A detail chosen by the rule: a circle of the front elevation and its scale.
#[derive(Clone, Debug, PartialEq)]
pub struct DetailSpec {
    /// Its letter.
    pub label: String,
    /// The scale it is drawn at (the `n` of 1:n).
    pub scale: f64,
    /// Centre of the circle, front view model coordinates, mm.
    pub centre: DVec2,
    /// Radius of the circle, model mm.
    pub radius: f64,
    /// Marks of the nozzles it is drawn for.
    pub nozzles: Vec<String>,
}

/// The `i`-th detail letter: A, B, …, Z without I, O and Q (read as figures),
/// then AA, AB, ….
pub fn detail_label(i: usize) -> String {
    const LETTERS: &[u8] = b"ABCDEFGHJKLMNPRSTUVWXYZ";
    let n = LETTERS.len();
    if i < n {
        (LETTERS[i] as char).to_string()
    } else {
        format!(
            "{}{}",
            LETTERS[(i / n - 1) % n] as char,
            LETTERS[i % n] as char
        )
    }
}

/// A nozzle's neck start and face centre in the front view, model mm.
fn nozzle_points(data: &VesselData, n: &NozzleData) -> (DVec2, DVec2) {
    let front = data.views[0].projection;
    let axis = (n.frame.matrix3 * DVec3::Z).normalize();
    let foot = n.frame.translation;
    let face = foot + axis * n.design.projection;
    (front.project(foot), front.project(face))
}

/// The details the rule asks for when the elevation is drawn at 1:`scale` on
/// `size`: smallest nozzles first, each uncovered one the centre of a new
/// circle on its neck, half the circle's radius in from the face (or the neck's
/// middle when shorter): the flange, the neck and where it meets the shell.
/// The circle covers every small nozzle whose face lies well inside it.
pub fn details(data: &VesselData, scale: f64, size: SheetSize) -> Vec<DetailSpec> {
    let mut small: Vec<(f64, &NozzleData)> = data
        .nozzles
        .iter()
        .map(|n| (n.geometry.outside_diameter(), n))
        .filter(|&(od, _)| od / scale < MIN_NOZZLE_PAPER)
        .collect();
    small.sort_by(|a, b| a.0.total_cmp(&b.0));
    let paper_radius = detail_radius(size);
    let mut covered = vec![false; small.len()];
    let mut out: Vec<DetailSpec> = Vec::new();
    for i in 0..small.len() {
        if covered[i] {
            continue;
        }
        let (od, n) = small[i];
        let detail_scale = enlarged_scale(od, MIN_DETAIL_NOZZLE_PAPER).min(scale);
        let radius = paper_radius * detail_scale;
        let (foot, face) = nozzle_points(data, n);
        let neck = face - foot;
        let centre = face - neck.normalize_or_zero() * (0.5 * neck.length()).min(0.5 * radius);
        let mut nozzles = Vec::new();
        for (j, &(_, other)) in small.iter().enumerate().skip(i) {
            let (_, face) = nozzle_points(data, other);
            if !covered[j] && (face - centre).length() <= 0.7 * radius {
                covered[j] = true;
                nozzles.push(other.design.mark.clone());
            }
        }
        out.push(DetailSpec {
            label: detail_label(out.len()),
            scale: detail_scale,
            centre,
            radius,
            nozzles,
        });
    }
    out
}

/// Where a drawing's `sheets` break the rule, each described for a failing
/// test: all views on one sheet coarser than [`MAX_ONE_SHEET_SCALE`]; a nozzle
/// under [`MIN_NOZZLE_PAPER`] on the elevation without a detail that draws it
/// at least [`MIN_DETAIL_NOZZLE_PAPER`] across.
pub fn legibility_problems(data: &VesselData, sheets: &[Sheet]) -> Vec<String> {
    let mut out = Vec::new();
    let Some(elevation) = sheets.iter().find(|s| s.shown[0]) else {
        return vec!["no sheet shows the elevation".to_string()];
    };
    if elevation.shown.iter().all(|&s| s) && elevation.scale > MAX_ONE_SHEET_SCALE {
        out.push(format!(
            "all views on sheet {} at 1:{}, coarser than 1:{MAX_ONE_SHEET_SCALE}",
            elevation.number, elevation.scale
        ));
    }
    for n in &data.nozzles {
        let od = n.geometry.outside_diameter();
        if od / elevation.scale >= MIN_NOZZLE_PAPER {
            continue;
        }
        let shown = sheets
            .iter()
            .flat_map(|s| &s.details)
            .any(|d| d.nozzles.contains(&n.design.mark) && od / d.scale >= MIN_DETAIL_NOZZLE_PAPER);
        if !shown {
            out.push(format!(
                "nozzle {} ({od} mm) is {:.2} mm across at 1:{} and no detail draws it",
                n.design.mark,
                od / elevation.scale,
                elevation.scale
            ));
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn detail_letters_skip_i_o_and_q() {
        let letters: Vec<String> = (0..26).map(detail_label).collect();
        assert_eq!(letters[..9].join(""), "ABCDEFGHJ");
        assert!(!letters.iter().any(|l| l == "I" || l == "O" || l == "Q"));
        assert_eq!(letters[23], "AA");
    }
}
