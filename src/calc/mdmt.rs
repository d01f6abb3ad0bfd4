//! Minimum design metal temperature by ASME VIII-1 UCS-66: the coldest metal
//! temperature at which a part of a Part UCS material needs no impact test, from
//! its material's Fig. UCS-66 curve (A, B, C or D, from the materials table), its
//! governing thickness and its coincident ratio (how hard the calculation
//! stresses it), and whether a required MDMT is met without impact testing. The
//! curves themselves are [`super::ucs66`]; a part's figures come from
//! `calc::part` (the part calculation).
//!
//! The rules applied, coldest permitted wins:
//! - Fig. UCS-66 at the governing thickness (UCS-66(a));
//! - UCS-66(b)(1): colder by the Fig. UCS-66.1 reduction at the coincident ratio
//!   Rts = tr E* / (tn − c) when 0.35 < Rts < 1, but not below −55 °F (−48 °C);
//! - UCS-66(b)(3): down to −155 °F (−104 °C) when Rts ≤ 0.35;
//! - UCS-66(d): −55 °F for material 0.10 in (2.5 mm) thick or thinner;
//! - a welded part whose governing thickness exceeds 4 in (101.6 mm) needs impact
//!   testing below 120 °F (49 °C) whatever its curve (UCS-66(a)), so that is its
//!   MDMT and no reduction applies.
//!
//! Temperatures convert from °F exactly (°C = (°F − 32)/1.8), nothing rounded.
//!
//! Choices where the code leaves detail: the governing thickness is the part's
//! own nominal thickness (UCS-66(a)(1)(a) for a butt-welded part taken alone; the
//! thicker neighbour of a butt joint and Fig. UCS-66.3's fillet-weld cases are not
//! assessed); every shell, head and cone is taken as welded; the coincident ratio
//! is taken at the design pressure and the design temperature's required
//! thickness (a stress at the MDMT is at least as high, so the ratio is not
//! understated); a material with no curve (austenitic stainless, Part UHA) gets no
//! UCS-66 figure.

use serde::Serialize;

use super::ucs66::{CHARPY_THICKNESS_IN, celsius, curve_f, reduction_f};

/// UCS-66(d): thickness at or below which no impact test is needed down to
/// [`THIN_MDMT`], mm (0.10 in).
pub const THIN_LIMIT: f64 = 2.5;

/// UCS-66(d)'s temperature for thin material, and the floor of a UCS-66.1
/// reduction above Rts = 0.35, °C (−55 °F).
pub const THIN_MDMT: f64 = (-55.0 - 32.0) / 1.8;

/// UCS-66(b)(3)'s temperature at Rts ≤ 0.35, °C (−155 °F).
pub const LOW_STRESS_MDMT: f64 = (-155.0 - 32.0) / 1.8;

/// The governing thickness above which a welded part needs impact testing below
/// [`THICK_MDMT`], mm (4 in).
pub const THICK_LIMIT: f64 = 101.6;

/// The MDMT of a welded part thicker than [`THICK_LIMIT`], °C (120 °F).
pub const THICK_MDMT: f64 = (120.0 - 32.0) / 1.8;

/// One part's UCS-66 figures.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Mdmt {
    /// Fig. UCS-66 curve letter of the material.
    pub curve: String,
    /// Governing thickness tg, mm.
    pub governing_thickness: f64,
    /// Fig. UCS-66 alone at tg, °C, when computed.
    pub curve_temperature: Option<f64>,
    /// UCS-66.1 coincident ratio Rts = tr E* / (tn − c), when given.
    pub ratio: Option<f64>,
    /// Fig. UCS-66.1 reduction applied, K, when one was.
    pub reduction: Option<f64>,
    /// MDMT without impact testing, °C; `None` when not computed (see `basis`).
    pub temperature: Option<f64>,
    /// The rules that gave the figure, or why there is none.
    pub basis: String,
}

impl Mdmt {
    /// Whether a part with this figure may run down to `required` °C without
    /// impact testing: `Some(true)` when its MDMT is at or below `required`,
    /// `Some(false)` when impact testing is needed, `None` when not computed.
    pub fn exempt_at(&self, required: f64) -> Option<bool> {
        self.temperature.map(|t| t <= required + 1e-9)
    }
}

/// The flat-segment temperature of curve `letter`, °F, or `None` for a letter
/// that is not A–D.
pub fn flat_segment_f(letter: &str) -> Option<f64> {
    curve_f(letter, CHARPY_THICKNESS_IN).ok()
}

/// The UCS-66 MDMT of a part of curve `curve`, governing thickness `tg` mm and,
/// when known, coincident ratio `ratio` (UCS-66.1's Rts).
pub fn mdmt(curve: &str, tg: f64, ratio: Option<f64>) -> Mdmt {
    let ratio = ratio.filter(|r| r.is_finite() && *r >= 0.0);
    let mut m = Mdmt {
        curve: curve.to_string(),
        governing_thickness: tg,
        curve_temperature: None,
        ratio,
        reduction: None,
        temperature: None,
        basis: String::new(),
    };
    if flat_segment_f(curve).is_none() {
        m.basis = format!("curve \"{curve}\" is not one of Fig. UCS-66's A, B, C, D");
        return m;
    }
    if tg > THICK_LIMIT {
        m.temperature = Some(THICK_MDMT);
        m.basis = format!(
            "UCS-66(a): a welded part with tg = {tg} mm > {THICK_LIMIT} mm (4 in) needs impact \
             testing below 120 F"
        );
        return m;
    }
    let t_f = match curve_f(curve, tg / 25.4) {
        Ok(t) => t,
        Err(e) => {
            m.basis = format!("{e}: the MDMT is not computed");
            return m;
        }
    };
    m.curve_temperature = Some(celsius(t_f));
    let mut steps = vec![format!(
        "Fig. UCS-66 curve {curve} at tg = {tg} mm: {t_f:.1} F"
    )];
    let mut best = t_f;
    match ratio {
        Some(r) if r <= 0.35 => {
            best = best.min(-155.0);
            steps.push(format!("UCS-66(b)(3): Rts = {r:.3} <= 0.35, -155 F"));
        }
        Some(r) => {
            if let Some(red) = reduction_f(r).filter(|&x| x > 0.0) {
                let reduced = (t_f - red).max(-55.0);
                m.reduction = Some((t_f - reduced) / 1.8);
                best = best.min(reduced);
                steps.push(format!(
                    "UCS-66(b)(1): Fig. UCS-66.1 at Rts = {r:.3} lowers it {red:.1} F, not below -55 F: \
                     {reduced:.1} F"
                ));
            }
        }
        None => {}
    }
    if tg <= THIN_LIMIT && -55.0 < best {
        best = -55.0;
        steps.push(format!("UCS-66(d): tg <= {THIN_LIMIT} mm, -55 F"));
    }
    m.temperature = Some(celsius(best));
    m.basis = steps.join("; ");
    m
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
