//! Data a vessel carries for drawings, weights and analysis rather than for its
//! shape: design conditions and wall thicknesses.
//!
//! No part builder reads these numbers, so nothing downstream of the shape would
//! notice a negative wall or a pressure below full vacuum; they are checked here so
//! that everything a design file is allowed to say makes physical sense:
//!
//! - design pressure (kPa gauge) is finite, at least full vacuum (−101.325 kPa)
//!   and at most [`MAX_PRESSURE`];
//! - external design pressure (kPa), when given, is finite, ≥ 0 and at most
//!   [`MAX_PRESSURE`];
//! - design temperature (°C) is finite, above absolute zero and at most
//!   [`MAX_TEMPERATURE`];
//! - a wall thickness given for a shell course, head or reducer lies between
//!   [`MIN_DIMENSION`] and the smallest outside radius of that part;
//! - the corrosion allowance is finite, ≥ 0 and thinner than every wall thickness
//!   the design gives;
//! - the drawing's title-block texts, when given, are non-empty single lines of at
//!   most [`MAX_TITLE_TEXT`] characters, the revision at most [`MAX_REVISION`], and
//!   the date a calendar date `YYYY-MM-DD`.

use super::{Report, ResolvedPart};
use crate::format::{PartDesign, VesselDesign};
use crate::parts::MIN_DIMENSION;
use crate::parts::PartGeometry;

/// Full vacuum as a gauge pressure, kPa.
pub const FULL_VACUUM: f64 = -101.325;
/// Largest design pressure accepted, kPa gauge (1 GPa).
pub const MAX_PRESSURE: f64 = 1e6;
/// Absolute zero, °C.
pub const ABSOLUTE_ZERO: f64 = -273.15;
/// Largest design temperature accepted, °C.
pub const MAX_TEMPERATURE: f64 = 1e4;

/// Longest title-block text accepted (drawing number, title), characters.
pub const MAX_TITLE_TEXT: usize = 80;
/// Longest revision accepted, characters.
pub const MAX_REVISION: usize = 8;

/// Whether `date` is a calendar date written `YYYY-MM-DD`.
fn is_iso_date(date: &str) -> bool {
    let b = date.as_bytes();
    if b.len() != 10 || b[4] != b'-' || b[7] != b'-' {
        return false;
    }
    let num = |r: std::ops::Range<usize>| date.get(r).and_then(|t| t.parse::<u32>().ok());
    let (Some(y), Some(m), Some(d)) = (num(0..4), num(5..7), num(8..10)) else {
        return false;
    };
    if !date
        .chars()
        .enumerate()
        .all(|(i, c)| i == 4 || i == 7 || c.is_ascii_digit())
    {
        return false;
    }
    let leap = (y % 4 == 0 && y % 100 != 0) || y % 400 == 0;
    let days = match m {
        1 | 3 | 5 | 7 | 8 | 10 | 12 => 31,
        4 | 6 | 9 | 11 => 30,
        2 if leap => 29,
        2 => 28,
        _ => return false,
    };
    (1..=days).contains(&d)
}

/// Checks the title-block data of the vessel's drawing.
fn check_drawing_info(vessel: &VesselDesign, report: &mut Report) {
    let info = &vessel.drawing;
    let texts = [
        ("number", &info.number, MAX_TITLE_TEXT),
        ("title", &info.title, MAX_TITLE_TEXT),
        ("revision", &info.revision, MAX_REVISION),
    ];
    for (field, value, max) in texts {
        let Some(text) = value else { continue };
        let shown = format!("{text:?}");
        if text.trim().is_empty() {
            report.push(
                format!("drawing.{field}"),
                None,
                field,
                shown.clone(),
                "must not be empty when given (leave it out instead)",
            );
        } else if text.chars().count() > max || text.chars().any(char::is_control) {
            report.push(
                format!("drawing.{field}"),
                None,
                field,
                shown.clone(),
                format!("must be one line of at most {max} characters"),
            );
        }
    }
    if let Some(date) = &info.date
        && !is_iso_date(date)
    {
        report.push(
            "drawing.date",
            None,
            "date",
            format!("{date:?}"),
            "must be a calendar date written YYYY-MM-DD",
        );
    }
}

/// Largest basic wind speed a design may give, m/s (ASCE 7-16's maps reach
/// about 90 m/s in hurricane-prone regions; twice that is certainly a typo).
pub const MAX_WIND_SPEED: f64 = 150.0;
/// Largest design spectral acceleration a design may give, g.
pub const MAX_SPECTRAL_ACCELERATION: f64 = 5.0;

/// Checks the wind and earthquake inputs: every value finite and in range.
fn check_lateral(c: &crate::format::DesignConditions, report: &mut Report) {
    let mut check = |path: &str, field: &str, value: Option<f64>, ok: bool, rule: &str| {
        if let Some(v) = value
            && !(v.is_finite() && ok)
        {
            report.push(format!("design.{path}.{field}"), None, field, v, rule);
        }
    };
    if let Some(w) = &c.wind {
        let s = w.speed;
        check(
            "wind",
            "speed",
            Some(s),
            s > 0.0 && s <= MAX_WIND_SPEED,
            &format!("must be a basic wind speed in m/s, above 0 and at most {MAX_WIND_SPEED}"),
        );
        for (field, v) in [
            ("importance", w.importance),
            ("topographic_factor", w.topographic_factor),
            ("directionality_factor", w.directionality_factor),
            ("gust_factor", w.gust_factor),
            ("force_coefficient", w.force_coefficient),
        ] {
            let ok = v.is_some_and(|v| v > 0.0 && v <= 5.0);
            check(
                "wind",
                field,
                v,
                ok,
                "must be a factor above 0 and at most 5",
            );
        }
        let e = w.base_elevation;
        check(
            "wind",
            "base_elevation",
            e,
            e.is_some_and(|e| (0.0..=1e6).contains(&e)),
            "must be a height above grade from 0 to 1e6 mm",
        );
        let a = w.area_factor;
        check(
            "wind",
            "area_factor",
            a,
            a.is_some_and(|a| (1.0..=5.0).contains(&a)),
            "must be a factor from 1 (the bare outside diameter) to 5",
        );
    }
    if let Some(e) = &c.seismic {
        for (field, v) in [("sds", e.sds), ("sd1", e.sd1)] {
            check(
                "seismic",
                field,
                Some(v),
                (0.0..=MAX_SPECTRAL_ACCELERATION).contains(&v),
                &format!(
                    "must be a design spectral acceleration in g from 0 to \
                     {MAX_SPECTRAL_ACCELERATION}"
                ),
            );
        }
        let r = e.response_modification;
        check(
            "seismic",
            "response_modification",
            Some(r),
            (1.0..=8.0).contains(&r),
            "must be a response modification coefficient R from 1 to 8 (ASCE 7-16 Table 15.4-2)",
        );
        let ie = e.importance;
        check(
            "seismic",
            "importance",
            ie,
            ie.is_some_and(|i| (1.0..=1.5).contains(&i)),
            "must be an importance factor Ie from 1 to 1.5 (ASCE 7-16 Table 1.5-2)",
        );
        let t = e.period;
        check(
            "seismic",
            "period",
            t,
            t.is_some_and(|t| t > 0.0 && t <= 20.0),
            "must be a period in s, above 0 and at most 20",
        );
    }
}

/// Checks the design conditions and the wall thicknesses of the resolved stack
/// parts (parts that failed to resolve were reported already).
pub(crate) fn check(vessel: &VesselDesign, parts: &[Option<ResolvedPart>], report: &mut Report) {
    check_drawing_info(vessel, report);
    let c = &vessel.design;
    if let Some(p) = c.pressure
        && !(p.is_finite() && (FULL_VACUUM..=MAX_PRESSURE).contains(&p))
    {
        report.push(
            "design.pressure",
            None,
            "pressure",
            p,
            format!(
                "must be a gauge pressure between full vacuum ({FULL_VACUUM} kPa) and \
                 {MAX_PRESSURE} kPa"
            ),
        );
    }
    if let Some(p) = c.external_pressure
        && !(p.is_finite() && (0.0..=MAX_PRESSURE).contains(&p))
    {
        report.push(
            "design.external_pressure",
            None,
            "external_pressure",
            p,
            format!(
                "must be an external pressure between 0 and {MAX_PRESSURE} kPa \
                 (full vacuum is 101.325)"
            ),
        );
    }
    check_lateral(c, report);
    if let Some(t) = c.temperature
        && !(t.is_finite() && t > ABSOLUTE_ZERO && t <= MAX_TEMPERATURE)
    {
        report.push(
            "design.temperature",
            None,
            "temperature",
            t,
            format!(
                "must lie above absolute zero ({ABSOLUTE_ZERO} °C) and at most {MAX_TEMPERATURE} °C"
            ),
        );
    }
    if let Some(e) = c.joint_efficiency
        && !(e.is_finite() && e > 0.0 && e <= 1.0)
    {
        report.push(
            "design.joint_efficiency",
            None,
            "joint_efficiency",
            e,
            "must lie in (0, 1] (ASME VIII-1 UW-12)",
        );
    }
    if c.material.as_deref().is_some_and(|m| m.trim().is_empty()) {
        report.push(
            "design.material",
            None,
            "material",
            "\"\"",
            "must not be empty when given (leave it out instead)",
        );
    }
    // Wall thicknesses, and the thinnest of them for the corrosion allowance.
    let mut thinnest: Option<(f64, &str)> = None;
    for (i, (design, resolved)) in vessel.parts.iter().zip(parts).enumerate() {
        let Some(resolved) = resolved else { continue };
        let (thickness, radius) = match (design, &resolved.geometry) {
            (PartDesign::Shell(s), PartGeometry::Shell(g)) => {
                (s.thickness, g.outside_diameter / 2.0)
            }
            (PartDesign::Head(h), PartGeometry::Head(g)) => (h.thickness, g.outside_diameter / 2.0),
            (PartDesign::Reducer(r), PartGeometry::Reducer(g)) => {
                (r.thickness, g.small_diameter / 2.0)
            }
            _ => continue,
        };
        let Some(t) = thickness else { continue };
        if !(t.is_finite() && t >= MIN_DIMENSION && t < radius) {
            report.push(
                format!("parts[{i}].{}.thickness", design.kind()),
                Some(design.id()),
                "thickness",
                t,
                format!(
                    "must lie between {MIN_DIMENSION} mm and the part's smallest outside \
                     radius ({radius} mm)"
                ),
            );
            continue;
        }
        if thinnest.is_none_or(|(least, _)| t < least) {
            thinnest = Some((t, design.id()));
        }
    }
    if let Some(ca) = c.corrosion_allowance {
        if !(ca.is_finite() && ca >= 0.0) {
            report.push(
                "design.corrosion_allowance",
                None,
                "corrosion_allowance",
                ca,
                "must be a finite number ≥ 0 mm",
            );
        } else if let Some((least, id)) = thinnest
            && ca >= least
        {
            report.push(
                "design.corrosion_allowance",
                None,
                "corrosion_allowance",
                ca,
                format!("must be thinner than every wall: {id} is {least} mm thick"),
            );
        }
    }
}

#[cfg(test)]
mod tests {
    use super::is_iso_date;

    #[test]
    fn iso_dates() {
        assert!(is_iso_date("2026-11-23"));
        assert!(is_iso_date("2024-02-29"));
        assert!(!is_iso_date("2023-02-29"));
        assert!(!is_iso_date("2026-13-01"));
        assert!(!is_iso_date("2026-1-01"));
        assert!(!is_iso_date("20261-1-01"));
        assert!(!is_iso_date("+026-11-23"));
    }
}
