//! Minimum design metal temperature by ASME VIII-1 UCS-66: the impact-test
//! exemption curve of the part's material (Fig. UCS-66 curve A, B, C or D, from
//! the materials table), the governing thickness, and the coldest metal
//! temperature at which the part needs no impact test.
//!
//! Shipped here is the part of Fig. UCS-66 that the figure itself states without
//! its licensed Table UCS-66: the flat segment of every curve up to the Charpy
//! specimen thickness 0.394 in (10 mm) — curve A 18 °F, curve B −20 °F, curves C
//! and D −55 °F (ASME BPVC VIII-1 2019, Fig. UCS-66, the values read off the
//! temperature axis where each curve starts) — and UCS-66(d): a Part UCS material
//! 0.10 in (2.5 mm) thick or thinner needs no impact test down to −55 °F
//! (−48 °C). Above 10 mm the curves rise along Table UCS-66's tabular values,
//! which are not shipped: the part's MDMT is then reported as not computed, with
//! the reason. Temperatures are converted from °F exactly (°C = (°F − 32)/1.8).
//!
//! Choice where the code leaves detail: the governing thickness is the part's own
//! nominal thickness (UCS-66(a)(1)(a) for a butt-welded part taken alone; the
//! thicker neighbour of a butt joint and the fillet-weld cases of Fig. UCS-66.3
//! are not assessed), and a material with no curve (austenitic stainless, Part
//! UHA) gets no UCS-66 figure.

use serde::Serialize;

/// The Charpy specimen thickness where the curves leave their flat segment, mm
/// (0.394 in).
pub const FLAT_SEGMENT_LIMIT: f64 = 10.0;

/// UCS-66(d): thickness at or below which no impact test is needed down to
/// [`THIN_MDMT`], mm (0.10 in).
pub const THIN_LIMIT: f64 = 2.5;

/// UCS-66(d)'s temperature for thin material, °C (−55 °F).
pub const THIN_MDMT: f64 = (-55.0 - 32.0) / 1.8;

/// One part's UCS-66 figures.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Mdmt {
    /// Fig. UCS-66 curve letter of the material.
    pub curve: String,
    /// Governing thickness tg, mm.
    pub governing_thickness: f64,
    /// MDMT without impact testing, °C; `None` when not computed (see `basis`).
    pub temperature: Option<f64>,
    /// The rule that gave the figure, or why there is none.
    pub basis: String,
}

/// The flat-segment temperature of curve `letter`, °F, or `None` for a letter
/// that is not A–D.
pub fn flat_segment_f(letter: &str) -> Option<f64> {
    match letter {
        "A" => Some(18.0),
        "B" => Some(-20.0),
        "C" | "D" => Some(-55.0),
        _ => None,
    }
}

/// The UCS-66 MDMT of a part of curve `curve` and governing thickness `tg` mm.
pub fn mdmt(curve: &str, tg: f64) -> Mdmt {
    let (temperature, basis) = match flat_segment_f(curve) {
        None => (
            None,
            format!("curve \"{curve}\" is not one of Fig. UCS-66's A, B, C, D"),
        ),
        Some(_) if tg <= THIN_LIMIT => (
            Some(THIN_MDMT),
            format!("UCS-66(d): tg = {tg} mm <= {THIN_LIMIT} mm, no impact test down to -55 F"),
        ),
        Some(f) if tg <= FLAT_SEGMENT_LIMIT => (
            Some((f - 32.0) / 1.8),
            format!(
                "Fig. UCS-66 curve {curve}, tg = {tg} mm <= {FLAT_SEGMENT_LIMIT} mm (0.394 in): {f} F"
            ),
        ),
        Some(_) => (
            None,
            format!(
                "Fig. UCS-66 curve {curve} above tg = {FLAT_SEGMENT_LIMIT} mm needs Table UCS-66's \
                 tabular values, which are licensed and not shipped (tg = {tg} mm)"
            ),
        ),
    };
    Mdmt {
        curve: curve.to_string(),
        governing_thickness: tg,
        temperature,
        basis,
    }
}

/// The vessel's MDMT: the warmest of its parts' computed MDMTs (the vessel can go
/// no colder than its least tough part), with the part id; `None` when no part
/// has one.
pub fn vessel_mdmt<'a>(
    parts: impl IntoIterator<Item = (&'a str, &'a Mdmt)>,
) -> Option<(String, f64)> {
    parts
        .into_iter()
        .filter_map(|(id, m)| m.temperature.map(|t| (id.to_string(), t)))
        .fold(None, |best: Option<(String, f64)>, (id, t)| match best {
            Some((_, b)) if b >= t => best,
            _ => Some((id, t)),
        })
}
