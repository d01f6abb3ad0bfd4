//! API 650 welded storage tanks: shell courses by the one-foot method (5.6.3),
//! the allowable stresses by the standard's rule (5.6.2.1, 5.6.2.2) and the
//! minimum nominal shell thickness by diameter (5.6.1.1).
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
