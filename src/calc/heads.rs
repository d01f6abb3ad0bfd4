//! Formed and flat heads under internal pressure: ellipsoidal (UG-32(d) for 2:1,
//! Appendix 1-4(c) with K otherwise), torispherical (Appendix 1-4(d) with M), and
//! flat unstayed heads (UG-34 with the attachment factor C). Inputs are corroded
//! inside dimensions (mm) and S·E (MPa); thickness results exclude the corrosion
//! allowance.

use super::{CalcError, Formula};

/// Appendix 1-4(c): K = (2 + (D / 2h)²) / 6, for 1 ≤ D/2h ≤ 3 (Table 1-4.1's range).
pub fn ellipsoidal_k(d: f64, h: f64) -> Result<f64, CalcError> {
    let ratio = d / (2.0 * h);
    if !(1.0 - 1e-9..=3.0 + 1e-9).contains(&ratio) {
        return Err(CalcError::OutOfScope {
            paragraph: "Appendix 1-4(c)",
            rule: format!("D/2h = {ratio} outside 1.0 to 3.0 (D = {d} mm, h = {h} mm)"),
        });
    }
    Ok((2.0 + ratio * ratio) / 6.0)
}

fn is_two_to_one(k: f64) -> bool {
    (k - 1.0).abs() < 1e-9
}

/// Ellipsoidal head: t = P·D·K / (2·S·E − 0.2·P); UG-32(d) when K = 1 (2:1).
pub fn ellipsoidal_thickness(d: f64, h: f64, p: f64, se: f64) -> Result<Formula, CalcError> {
    let k = ellipsoidal_k(d, h)?;
    Ok(if is_two_to_one(k) {
        Formula {
            value: p * d / (2.0 * se - 0.2 * p),
            paragraph: "UG-32(d)",
            formula: "t = P·D / (2·S·E − 0.2·P)",
        }
    } else {
        Formula {
            value: p * d * k / (2.0 * se - 0.2 * p),
            paragraph: "Appendix 1-4(c)",
            formula: "t = P·D·K / (2·S·E − 0.2·P), K = (2 + (D/2h)²)/6",
        }
    })
}

/// Ellipsoidal head: P = 2·S·E·t / (K·D + 0.2·t); UG-32(d) when K = 1.
pub fn ellipsoidal_mawp(d: f64, h: f64, t: f64, se: f64) -> Result<Formula, CalcError> {
    let k = ellipsoidal_k(d, h)?;
    Ok(if is_two_to_one(k) {
        Formula {
            value: 2.0 * se * t / (d + 0.2 * t),
            paragraph: "UG-32(d)",
            formula: "P = 2·S·E·t / (D + 0.2·t)",
        }
    } else {
        Formula {
            value: 2.0 * se * t / (k * d + 0.2 * t),
            paragraph: "Appendix 1-4(c)",
            formula: "P = 2·S·E·t / (K·D + 0.2·t), K = (2 + (D/2h)²)/6",
        }
    })
}

/// Appendix 1-4(d): M = (3 + √(L/r)) / 4, for 1 ≤ L/r ≤ 16⅔ (Table 1-4.2's range).
pub fn torispherical_m(l: f64, r: f64) -> Result<f64, CalcError> {
    let ratio = l / r;
    if !(1.0 - 1e-9..=50.0 / 3.0 + 1e-9).contains(&ratio) {
        return Err(CalcError::OutOfScope {
            paragraph: "Appendix 1-4(d)",
            rule: format!("L/r = {ratio} outside 1 to 16⅔ (L = {l} mm, r = {r} mm)"),
        });
    }
    Ok((3.0 + ratio.sqrt()) / 4.0)
}

/// Torispherical head: t = P·L·M / (2·S·E − 0.2·P). With L/r = 16⅔ (M = 1.77) this
/// is UG-32(e)'s t = 0.885·P·L / (S·E − 0.1·P).
pub fn torispherical_thickness(l: f64, r: f64, p: f64, se: f64) -> Result<Formula, CalcError> {
    let m = torispherical_m(l, r)?;
    Ok(Formula {
        value: p * l * m / (2.0 * se - 0.2 * p),
        paragraph: "Appendix 1-4(d)",
        formula: "t = P·L·M / (2·S·E − 0.2·P), M = (3 + √(L/r))/4",
    })
}

/// Torispherical head: P = 2·S·E·t / (L·M + 0.2·t).
pub fn torispherical_mawp(l: f64, r: f64, t: f64, se: f64) -> Result<Formula, CalcError> {
    let m = torispherical_m(l, r)?;
    Ok(Formula {
        value: 2.0 * se * t / (l * m + 0.2 * t),
        paragraph: "Appendix 1-4(d)",
        formula: "P = 2·S·E·t / (L·M + 0.2·t), M = (3 + √(L/r))/4",
    })
}

/// UG-34(c)(2) formula (1), flat head without bolting moment: t = d·√(C·P / (S·E)).
pub fn flat_thickness(d: f64, c: f64, p: f64, se: f64) -> Result<Formula, CalcError> {
    Ok(Formula {
        value: d * (c * p / se).sqrt(),
        paragraph: "UG-34(c)(2)",
        formula: "t = d·√(C·P / (S·E))",
    })
}

/// UG-34(c)(2) formula (1) solved for P: P = S·E·(t/d)² / C.
pub fn flat_mawp(d: f64, c: f64, t: f64, se: f64) -> Result<Formula, CalcError> {
    Ok(Formula {
        value: se * (t / d).powi(2) / c,
        paragraph: "UG-34(c)(2)",
        formula: "P = S·E·(t/d)² / C",
    })
}
