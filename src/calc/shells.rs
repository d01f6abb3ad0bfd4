//! Shells under internal pressure: UG-27(c) cylinders (circumferential and
//! longitudinal stress), UG-27(d) spheres and hemispherical heads (UG-32(f)), and
//! UG-32(g) cones. Each function takes corroded inside dimensions (mm), S·E (MPa)
//! and returns the thickness without corrosion allowance, or the MAWP for a
//! corroded thickness, with the paragraph's scope limits checked.

use super::{CalcError, Formula};

fn out_of_scope(paragraph: &'static str, rule: String) -> CalcError {
    CalcError::OutOfScope { paragraph, rule }
}

/// UG-27(c)(1), circumferential stress: t = P·R / (S·E − 0.6·P), for P ≤ 0.385·S·E.
pub fn circumferential_thickness(r: f64, p: f64, se: f64) -> Result<Formula, CalcError> {
    const PARA: &str = "UG-27(c)(1)";
    if p > 0.385 * se {
        return Err(out_of_scope(
            PARA,
            format!(
                "P = {p} MPa exceeds 0.385·S·E = {} MPa; use Appendix 1-2",
                0.385 * se
            ),
        ));
    }
    Ok(Formula {
        value: p * r / (se - 0.6 * p),
        paragraph: PARA,
        formula: "t = P·R / (S·E − 0.6·P)",
    })
}

/// UG-27(c)(1): P = S·E·t / (R + 0.6·t), for t ≤ R/2.
pub fn circumferential_mawp(r: f64, t: f64, se: f64) -> Result<Formula, CalcError> {
    const PARA: &str = "UG-27(c)(1)";
    if t > r / 2.0 {
        return Err(out_of_scope(
            PARA,
            format!("t = {t} mm exceeds R/2 = {} mm; use Appendix 1-2", r / 2.0),
        ));
    }
    Ok(Formula {
        value: se * t / (r + 0.6 * t),
        paragraph: PARA,
        formula: "P = S·E·t / (R + 0.6·t)",
    })
}

/// UG-27(c)(2), longitudinal stress: t = P·R / (2·S·E + 0.4·P), for P ≤ 1.25·S·E.
pub fn longitudinal_thickness(r: f64, p: f64, se: f64) -> Result<Formula, CalcError> {
    const PARA: &str = "UG-27(c)(2)";
    if p > 1.25 * se {
        return Err(out_of_scope(
            PARA,
            format!(
                "P = {p} MPa exceeds 1.25·S·E = {} MPa; use Appendix 1-2",
                1.25 * se
            ),
        ));
    }
    Ok(Formula {
        value: p * r / (2.0 * se + 0.4 * p),
        paragraph: PARA,
        formula: "t = P·R / (2·S·E + 0.4·P)",
    })
}

/// UG-27(c)(2): P = 2·S·E·t / (R − 0.4·t), for t ≤ R/2.
pub fn longitudinal_mawp(r: f64, t: f64, se: f64) -> Result<Formula, CalcError> {
    const PARA: &str = "UG-27(c)(2)";
    if t > r / 2.0 {
        return Err(out_of_scope(
            PARA,
            format!("t = {t} mm exceeds R/2 = {} mm; use Appendix 1-2", r / 2.0),
        ));
    }
    Ok(Formula {
        value: 2.0 * se * t / (r - 0.4 * t),
        paragraph: PARA,
        formula: "P = 2·S·E·t / (R − 0.4·t)",
    })
}

/// UG-27(d) / UG-32(f), sphere or hemispherical head: t = P·R / (2·S·E − 0.2·P),
/// for P ≤ 0.665·S·E.
pub fn sphere_thickness(r: f64, p: f64, se: f64) -> Result<Formula, CalcError> {
    const PARA: &str = "UG-27(d)";
    if p > 0.665 * se {
        return Err(out_of_scope(
            PARA,
            format!(
                "P = {p} MPa exceeds 0.665·S·E = {} MPa; use Appendix 1-3",
                0.665 * se
            ),
        ));
    }
    Ok(Formula {
        value: p * r / (2.0 * se - 0.2 * p),
        paragraph: PARA,
        formula: "t = P·R / (2·S·E − 0.2·P)",
    })
}

/// UG-27(d): P = 2·S·E·t / (R + 0.2·t), for t ≤ 0.356·R.
pub fn sphere_mawp(r: f64, t: f64, se: f64) -> Result<Formula, CalcError> {
    const PARA: &str = "UG-27(d)";
    if t > 0.356 * r {
        return Err(out_of_scope(
            PARA,
            format!(
                "t = {t} mm exceeds 0.356·R = {} mm; use Appendix 1-3",
                0.356 * r
            ),
        ));
    }
    Ok(Formula {
        value: 2.0 * se * t / (r + 0.2 * t),
        paragraph: PARA,
        formula: "P = 2·S·E·t / (R + 0.2·t)",
    })
}

fn cone_scope(alpha: f64) -> Result<f64, CalcError> {
    if alpha > 30.0 {
        return Err(out_of_scope(
            "UG-32(g)",
            format!("half apex angle α = {alpha}° exceeds 30°; use Appendix 1-5(g)"),
        ));
    }
    Ok(alpha.to_radians().cos())
}

/// UG-32(g), cone: t = P·D / (2·cos α·(S·E − 0.6·P)), for α ≤ 30° and P ≤ 0.385·S·E.
pub fn cone_thickness(d: f64, alpha: f64, p: f64, se: f64) -> Result<Formula, CalcError> {
    const PARA: &str = "UG-32(g)";
    let cos = cone_scope(alpha)?;
    if p > 0.385 * se {
        return Err(out_of_scope(
            PARA,
            format!("P = {p} MPa exceeds 0.385·S·E = {} MPa", 0.385 * se),
        ));
    }
    Ok(Formula {
        value: p * d / (2.0 * cos * (se - 0.6 * p)),
        paragraph: PARA,
        formula: "t = P·D / (2·cos α·(S·E − 0.6·P))",
    })
}

/// UG-32(g): P = 2·S·E·t·cos α / (D + 1.2·t·cos α), for α ≤ 30°.
pub fn cone_mawp(d: f64, alpha: f64, t: f64, se: f64) -> Result<Formula, CalcError> {
    let cos = cone_scope(alpha)?;
    Ok(Formula {
        value: 2.0 * se * t * cos / (d + 1.2 * t * cos),
        paragraph: "UG-32(g)",
        formula: "P = 2·S·E·t·cos α / (D + 1.2·t·cos α)",
    })
}
