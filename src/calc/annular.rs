//! API 650 annular bottom plates (5.5): whether the tank needs them (5.5.1), how
//! thick they must be (5.5.3, Table 5.1a, SI) and how wide (5.5.2), from the
//! first (bottom) shell course.
//!
//! The stress in the first course that selects Table 5.1a's column is its Note
//! b's: the product stress (t_d − CA)/(t − CA) · Sd and the hydrostatic test
//! stress t_t/t · St, with t the course's nominal thickness, the greater of the
//! two taken; 5.5.3 then asks for the table's thickness plus the corrosion
//! allowance for product design, or the table's thickness for the test, the
//! greater — with one column for both, the table's value plus CA (the reading
//! ITSdesign gave, itsdesign.blogspot.com, 10 Dec 2012, "Annular Ring Thickness
//! Calculations"). The radial width between the inside of the shell and any
//! lap-welded joint of the remaining bottom is at least 600 mm and at least
//! L = 215·t_b/(H·G)^0.5 mm (5.5.2, SI), taken here with t_b the required annular
//! thickness (corrosion allowance included) and H the design liquid level of the
//! first course.
//!
//! Choices where the standard leaves them to the purchaser: one corrosion
//! allowance for shell and bottom (the design's); annular plates are reported —
//! needed or not, with their least thickness and width — and not modelled as a
//! part, so a tank that needs them is told so, not marked deficient.

use serde::Serialize;

use super::CalcError;
use super::error::{non_negative, positive};

/// Table 5.1a's rows: the upper bound of each band of first-course thickness, mm.
pub const COURSE_BANDS: [f64; 5] = [19.0, 25.0, 32.0, 40.0, 45.0];

/// Table 5.1a's columns: the upper bound of each band of first-course stress, MPa.
pub const STRESS_BANDS: [f64; 4] = [190.0, 210.0, 220.0, 250.0];

/// Table 5.1a (SI), annular bottom-plate thickness t_b, mm, by first-course
/// thickness band (rows, [`COURSE_BANDS`]) and stress band (columns,
/// [`STRESS_BANDS`]); API 650 12th edition (2013). The row 40 < t ≤ 45 mm, 16 mm
/// at ≤ 220 MPa and 19 mm at ≤ 250 MPa, is the one ITSdesign's worked question
/// (2012) reads; no public copy of the whole table was found, so check the other
/// rows against your edition.
pub const TABLE_5_1A: [[f64; 4]; 5] = [
    [6.0, 6.0, 7.0, 9.0],
    [6.0, 7.0, 10.0, 11.0],
    [6.0, 9.0, 12.0, 14.0],
    [8.0, 11.0, 14.0, 17.0],
    [9.0, 13.0, 16.0, 19.0],
];

/// 5.5.2: the least radial width inside the shell, mm.
pub const MINIMUM_WIDTH: f64 = 600.0;

/// 5.5.1: the first course's product stress at or below which lap-welded bottom
/// plates may replace annular plates, MPa.
pub const LAP_PRODUCT_STRESS: f64 = 160.0;

/// 5.5.1: the first course's hydrostatic test stress at or below which
/// lap-welded bottom plates may replace annular plates, MPa.
pub const LAP_TEST_STRESS: f64 = 171.0;

/// 5.5.3: the largest effective product height H·G Table 5.1a covers, m.
pub const MAX_PRODUCT_HEIGHT: f64 = 23.0;

/// The first course as Table 5.1a needs it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FirstCourse {
    /// Nominal (as-constructed) thickness t, mm.
    pub thickness: f64,
    /// One-foot design thickness t_d, corrosion allowance included, mm.
    pub design: f64,
    /// One-foot hydrostatic test thickness t_t, mm.
    pub test: f64,
    /// Corrosion allowance, mm.
    pub corrosion_allowance: f64,
    /// Product design stress Sd, MPa.
    pub design_stress: f64,
    /// Hydrostatic test stress St, MPa.
    pub test_stress: f64,
    /// Design liquid level H above the course's bottom, m.
    pub level: f64,
    /// Design specific gravity G.
    pub gravity: f64,
}

/// The annular plates of a tank.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Annular {
    /// The first course's nominal thickness t, mm.
    pub course_thickness: f64,
    /// Table 5.1a Note b product stress (t_d − CA)/(t − CA)·Sd, MPa.
    pub product_stress: f64,
    /// Table 5.1a Note b hydrostatic test stress t_t/t·St, MPa.
    pub test_stress: f64,
    /// Table 5.1a's thickness at the greater stress, mm.
    pub table_thickness: f64,
    /// 5.5.3: least annular plate thickness t_b, corrosion allowance included, mm.
    pub thickness: f64,
    /// 5.5.2: L = 215·t_b/(H·G)^0.5, mm.
    pub width_formula: f64,
    /// 5.5.2: least radial width inside the shell, max(600 mm, L), mm.
    pub width: f64,
    /// 5.5.1: whether annular plates are required (`None`: the material's API
    /// 650 group is not known).
    pub required: Option<bool>,
    /// Why they are or are not required.
    pub reason: String,
}

/// Table 5.1a Note b: the first course's product stress and hydrostatic test
/// stress, MPa.
pub fn course_stresses(c: &FirstCourse) -> Result<(f64, f64), CalcError> {
    const E: &str = "first shell course";
    let t = positive(E, "thickness", c.thickness)?;
    let ca = non_negative(E, "corrosion_allowance", c.corrosion_allowance)?;
    positive(E, "thickness less corrosion", t - ca)?;
    non_negative(E, "t_d", c.design)?;
    non_negative(E, "t_t", c.test)?;
    positive(E, "design_stress", c.design_stress)?;
    positive(E, "test_stress", c.test_stress)?;
    let product = ((c.design - ca).max(0.0) / (t - ca)) * c.design_stress;
    Ok((product, c.test / t * c.test_stress))
}

/// Table 5.1a: the annular thickness for a first course `t` mm thick under
/// `stress` MPa (the greater of Note b's two), mm; an error outside the table.
pub fn table_thickness(t: f64, stress: f64) -> Result<f64, CalcError> {
    let row = COURSE_BANDS.iter().position(|&b| t <= b);
    let col = STRESS_BANDS.iter().position(|&b| stress <= b);
    match (row, col) {
        (Some(r), Some(c)) if t > 0.0 && stress.is_finite() => Ok(TABLE_5_1A[r][c]),
        _ => Err(CalcError::OutOfScope {
            paragraph: "API 650 5.5.3",
            rule: format!(
                "Table 5.1a covers a first course up to 45 mm under up to 250 MPa; t = {t} mm, \
                 stress = {stress:.1} MPa (an elastic analysis is needed)"
            ),
        }),
    }
}

/// 5.5.1–5.5.3 for the tank whose first course is `c`, of a material in API 650
/// group `group` (Table 4.4a, e.g. `IV`; `None` when unknown).
pub fn annular(c: &FirstCourse, group: Option<&str>) -> Result<Annular, CalcError> {
    let (product, test) = course_stresses(c)?;
    positive("tank", "liquid_level", c.level)?;
    positive("tank", "specific_gravity", c.gravity)?;
    let hg = c.level * c.gravity;
    if hg > MAX_PRODUCT_HEIGHT {
        return Err(CalcError::OutOfScope {
            paragraph: "API 650 5.5.3",
            rule: format!(
                "Table 5.1a covers H·G ≤ {MAX_PRODUCT_HEIGHT} m, H·G = {hg:.2} m (an elastic \
                 analysis is needed)"
            ),
        });
    }
    let table = table_thickness(c.thickness, product.max(test))?;
    let thickness = table + c.corrosion_allowance;
    let width_formula = 215.0 * thickness / hg.sqrt();
    let (required, reason) = match group {
        None => (
            None,
            "5.5.1 not assessed: the material's API 650 group (Table 4.4a) is not in the \
             materials table"
                .to_string(),
        ),
        Some(g) if !matches!(g, "IV" | "IVA" | "V" | "VI") => (
            Some(false),
            format!("5.5.1: first course of Group {g} (not IV, IVA, V or VI): lap-welded bottom"),
        ),
        Some(g) if product <= LAP_PRODUCT_STRESS || test <= LAP_TEST_STRESS => (
            Some(false),
            format!(
                "5.5.1: Group {g}, but product stress {product:.1} ≤ {LAP_PRODUCT_STRESS} MPa or \
                 test stress {test:.1} ≤ {LAP_TEST_STRESS} MPa: lap-welded bottom permitted"
            ),
        ),
        Some(g) => (
            Some(true),
            format!(
                "5.5.1: Group {g} with product stress {product:.1} > {LAP_PRODUCT_STRESS} MPa and \
                 test stress {test:.1} > {LAP_TEST_STRESS} MPa: butt-welded annular plates"
            ),
        ),
    };
    Ok(Annular {
        course_thickness: c.thickness,
        product_stress: product,
        test_stress: test,
        table_thickness: table,
        thickness,
        width_formula,
        width: width_formula.max(MINIMUM_WIDTH),
        required,
        reason,
    })
}
