//! API 650 welded storage tanks: shell courses by the one-foot method (5.6.3),
//! the allowable stresses by the standard's rule (5.6.2.1, 5.6.2.2), the
//! minimum nominal shell thickness by diameter (5.6.1.1), the bottom plates'
//! minimum (5.4.1) and the roof plates' (5.10.2.2, 5.10.5.1, 5.10.6.1).
//!
//! SI units as the standard prints them: D in m, H in m, stresses in MPa, and
//! thicknesses in mm. The design liquid level H of a course is the height from its
//! bottom to the top of the shell (the standard's default when the purchaser
//! names no overflow or lower level); G is the stored liquid's specific gravity
//! (the operating density / 1000, water when the design gives none).

use serde::Serialize;

use super::CalcError;
use super::error::{non_negative, positive};

/// Largest diameter the one-foot method may be used for, m (5.6.3.1).
pub const ONE_FOOT_MAX_DIAMETER: f64 = 61.0;

/// The product design stress Sd and hydrostatic test stress St of a plate with
/// specified minimum `yield_strength` and `tensile_strength` MPa, by 5.6.2.1
/// (Sd = min(2/3·Sy, 2/5·Su)) and 5.6.2.2 (St = min(3/4·Sy, 3/7·Su)), rounded to
/// the whole MPa as Table 5-2a lists them.
pub fn allowable_stresses(yield_strength: f64, tensile_strength: f64) -> (f64, f64) {
    let sd = (2.0 / 3.0 * yield_strength).min(0.4 * tensile_strength);
    let st = (0.75 * yield_strength).min(3.0 / 7.0 * tensile_strength);
    (sd.round(), st.round())
}

/// Minimum nominal shell thickness for a tank of nominal diameter `d` m, mm
/// (5.6.1.1: 5 mm below 15 m, 6 mm to 36 m, 8 mm to 60 m, 10 mm above).
pub fn minimum_nominal(d: f64) -> f64 {
    if d < 15.0 {
        5.0
    } else if d < 36.0 {
        6.0
    } else if d <= 60.0 {
        8.0
    } else {
        10.0
    }
}

/// The one-foot method's result for one course, mm.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Course {
    /// Nominal tank diameter D (centreline of the bottom course), m.
    pub diameter: f64,
    /// Design liquid level H above the course's bottom, m.
    pub level: f64,
    /// Design specific gravity G.
    pub gravity: f64,
    /// t_d = 4.9·D·(H − 0.3)·G / Sd + CA.
    pub design: f64,
    /// t_t = 4.9·D·(H − 0.3) / St.
    pub test: f64,
    /// 5.6.1.1 minimum nominal thickness.
    pub minimum: f64,
    /// The governing thickness: the greatest of the three.
    pub required: f64,
}

/// 5.6.3.2: the course of a tank of nominal diameter `d` m under `h` m of liquid
/// of specific gravity `g`, with stresses `sd`, `st` MPa and corrosion `ca` mm.
pub fn one_foot(d: f64, h: f64, g: f64, sd: f64, st: f64, ca: f64) -> Result<Course, CalcError> {
    const E: &str = "tank course";
    positive(E, "diameter", d)?;
    non_negative(E, "liquid_level", h)?;
    positive(E, "specific_gravity", g)?;
    positive(E, "design_stress", sd)?;
    positive(E, "test_stress", st)?;
    non_negative(E, "corrosion_allowance", ca)?;
    if d > ONE_FOOT_MAX_DIAMETER {
        return Err(CalcError::OutOfScope {
            paragraph: "API 650 5.6.3.1",
            rule: format!(
                "the one-foot method is for D ≤ {ONE_FOOT_MAX_DIAMETER} m, D = {d:.2} m; the \
                 variable-design-point method (5.6.4) is not computed"
            ),
        });
    }
    let head = (h - 0.3).max(0.0);
    let design = 4.9 * d * head * g / sd + ca;
    let test = 4.9 * d * head / st;
    let minimum = minimum_nominal(d);
    Ok(Course {
        diameter: d,
        level: h,
        gravity: g,
        design,
        test,
        minimum,
        required: design.max(test).max(minimum),
    })
}

/// 5.4.1: least nominal thickness of bottom plates, mm, before the corrosion
/// allowance.
pub const BOTTOM_MINIMUM: f64 = 6.0;

/// 5.10.2.2: least nominal thickness of roof plates, mm.
pub const ROOF_MINIMUM: f64 = 5.0;

/// 5.10.5.1 / 5.10.6.1: most a self-supporting roof's plates need be, mm
/// (before the corrosion allowance).
pub const ROOF_MAXIMUM: f64 = 13.0;

/// The roof load T the self-supporting formulas are written for, kPa
/// (5.10.5.1: t = D/(4.8·sin θ)·√(T/2.2)); taken as the design load when the
/// design gives none (live load 1.0 kPa plus dead and snow loads).
pub const REFERENCE_ROOF_LOAD: f64 = 2.2;

/// 5.10.5.1: the plates of a self-supporting cone roof of a tank of diameter `d`
/// m whose elements rise at `theta` degrees from the horizontal, under the
/// reference load, mm before the corrosion allowance: D/(4.8·sin θ), at least
/// [`ROOF_MINIMUM`], at most [`ROOF_MAXIMUM`]. An error outside the slopes the
/// paragraph covers (9.5° to 37°).
pub fn self_supporting_cone(d: f64, theta: f64) -> Result<f64, CalcError> {
    positive("cone roof", "diameter", d)?;
    if !(9.5..=37.0).contains(&theta) {
        return Err(CalcError::OutOfScope {
            paragraph: "API 650 5.10.5.1",
            rule: format!("a self-supporting cone roof slopes 9.5° to 37°, θ = {theta:.2}°"),
        });
    }
    Ok((d / (4.8 * theta.to_radians().sin())).clamp(ROOF_MINIMUM, ROOF_MAXIMUM))
}

/// 5.10.6.1: the plates of a self-supporting dome roof of radius `rr` m on a tank
/// of diameter `d` m, under the reference load, mm before the corrosion
/// allowance: rr/2.4, at least [`ROOF_MINIMUM`], at most [`ROOF_MAXIMUM`]. An
/// error outside 0.8·D ≤ rr ≤ 1.2·D.
pub fn self_supporting_dome(d: f64, rr: f64) -> Result<f64, CalcError> {
    positive("dome roof", "diameter", d)?;
    positive("dome roof", "radius", rr)?;
    if !(0.8 * d..=1.2 * d).contains(&rr) {
        return Err(CalcError::OutOfScope {
            paragraph: "API 650 5.10.6.1",
            rule: format!(
                "a dome roof's radius is 0.8·D to 1.2·D ({:.3} to {:.3} m), rr = {rr:.3} m",
                0.8 * d,
                1.2 * d
            ),
        });
    }
    Ok((rr / 2.4).clamp(ROOF_MINIMUM, ROOF_MAXIMUM))
}

/// A bottom or roof plate's requirement.
#[derive(Clone, Debug, PartialEq)]
pub struct Plate {
    /// `tank bottom plate` or the roof's kind.
    pub shape: &'static str,
    /// Required nominal thickness, corrosion allowance included where it
    /// applies, mm.
    pub required: f64,
    /// Paragraph.
    pub paragraph: &'static str,
    /// The rule's text.
    pub formula: &'static str,
    /// A self-supporting roof's formula thickness (before the minimum), for the
    /// report; `None` otherwise.
    pub self_supporting: Option<f64>,
}

/// The plate requirement of a tank's head `kind`: the bottom (`bottom` true) by
/// 5.4.1 (6 mm plus `ca`), the roof by its kind. Choices: a cone roof is taken
/// as a supported cone roof (5.10.4; the model has no rafters to say otherwise)
/// whose plates need 5.10.2.2's 5 mm, with the self-supporting thickness of
/// 5.10.5.1 reported beside it; a dished roof (torispherical, hemispherical) as
/// a self-supporting dome of its crown radius (5.10.6.1); the design's single
/// corrosion allowance is taken for the wetted shell and bottom, not the roof
/// (API 650 lets the purchaser give each its own; put a roof's into its
/// thickness).
pub fn plate(
    kind: crate::parts::heads::HeadKind,
    outside_diameter: f64,
    bottom: bool,
    ca: f64,
) -> Result<Plate, CalcError> {
    use crate::parts::heads::HeadKind;
    let d = outside_diameter * 1e-3;
    if bottom {
        return Ok(Plate {
            shape: "tank bottom plate",
            required: BOTTOM_MINIMUM + ca,
            paragraph: "API 650 5.4.1",
            formula: "t = 6 mm + CA (annular plates: 5.5, with the vessel figures)",
            self_supporting: None,
        });
    }
    Ok(match kind {
        HeadKind::Conical { half_angle, .. } | HeadKind::Toriconical { half_angle, .. } => {
            let theta = 90.0 - half_angle;
            Plate {
                shape: "supported cone roof",
                required: ROOF_MINIMUM,
                paragraph: "API 650 5.10.2.2",
                formula: "supported cone roof plates: t = 5 mm",
                self_supporting: self_supporting_cone(d, theta).ok(),
            }
        }
        HeadKind::Torispherical { crown_radius, .. } => Plate {
            shape: "self-supporting dome roof",
            required: self_supporting_dome(d, crown_radius * 1e-3)?,
            paragraph: "API 650 5.10.6.1",
            formula: "t = rr / 2.4 (T = 2.2 kPa), 5 to 13 mm",
            self_supporting: None,
        },
        HeadKind::Hemispherical => Plate {
            shape: "self-supporting dome roof",
            required: self_supporting_dome(d, d / 2.0)?,
            paragraph: "API 650 5.10.6.1",
            formula: "t = rr / 2.4 (T = 2.2 kPa), 5 to 13 mm",
            self_supporting: None,
        },
        _ => Plate {
            shape: "roof",
            required: ROOF_MINIMUM,
            paragraph: "API 650 5.10.2.2",
            formula: "roof plates: t = 5 mm (this roof shape's structure not assessed)",
            self_supporting: None,
        },
    })
}
