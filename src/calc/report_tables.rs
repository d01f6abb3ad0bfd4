//! Pieces of the HTML calculation report: the cell helpers every table uses,
//! the external-pressure table (UG-28 / UG-33 per part: factors A and B, the
//! allowable Pa against the design's external pressure) and the saddle table
//! (Zick's stresses per saddle and load case, each against its allowable), and
//! a tank's annular bottom plates (API 650 5.5).

use std::fmt::Write;

use super::PartCalc;
use super::annular::Annular;
use super::saddles::SaddleCase;

pub(super) fn esc(text: &str) -> String {
    text.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}

pub(super) fn row(out: &mut String, cells: &[String]) {
    out.push_str("<tr>");
    for c in cells {
        let _ = write!(out, "<td>{}</td>", esc(c));
    }
    out.push_str("</tr>\n");
}

pub(super) fn head(out: &mut String, cells: &[&str]) {
    out.push_str("<tr>");
    for c in cells {
        let _ = write!(out, "<th>{}</th>", esc(c));
    }
    out.push_str("</tr>\n");
}

pub(super) fn opt(v: Option<f64>, digits: usize, unit: &str) -> String {
    v.map_or("—".into(), |v| format!("{v:.digits$} {unit}"))
}

/// The external-pressure table of the parts that have a UG-28 / UG-33 figure.
pub(super) fn external(o: &mut String, parts: &[PartCalc]) {
    let rows: Vec<_> = parts
        .iter()
        .filter_map(|p| Some((p, p.external.as_ref()?)))
        .collect();
    if rows.is_empty() {
        return;
    }
    o.push_str("<h3>External pressure (UG-28 / UG-33, corroded, elastic range)</h3><table>\n");
    head(
        o,
        &["Part", "Paragraph", "A", "B", "Pa allowable", "Status"],
    );
    for (p, x) in rows {
        match x {
            Ok(x) => {
                let status = if p
                    .deficiency
                    .as_deref()
                    .is_some_and(|d| d.contains("external"))
                {
                    "DEFICIENT"
                } else {
                    "OK"
                };
                row(
                    o,
                    &[
                        p.id.clone(),
                        x.paragraph.into(),
                        format!("{:.6}", x.a),
                        format!("{:.2} MPa", x.b),
                        format!("{:.4} MPa", x.allowable),
                        status.into(),
                    ],
                );
            }
            Err(e) => {
                let mut cells = vec![p.id.clone(), "—".into(), "—".into(), "—".into()];
                cells.push("not computed".into());
                cells.push(e.clone());
                row(o, &cells);
            }
        }
    }
    o.push_str("</table>\n");
}

/// The saddle table: Zick's inputs and each check per saddle and load case.
pub(super) fn saddles(o: &mut String, cases: &[SaddleCase]) {
    if cases.is_empty() {
        return;
    }
    o.push_str("<h3>Saddles — Zick's method</h3><table>\n");
    head(
        o,
        &[
            "Saddle",
            "Case",
            "Inputs",
            "Check",
            "Stress",
            "Allowable",
            "Status",
        ],
    );
    for c in cases {
        let i = &c.input;
        let inputs = format!(
            "Q = {:.1} kN ({:.0} kg case mass), A = {:.0}, L = {:.0}, R = {:.1}, ts = {:.2}, \
             th = {:.2}, H = {:.1}, b = {:.0} mm, θ = {}°, wear plate {} mm, P = {:.4} MPa",
            i.load * 1e-3,
            c.mass,
            i.a,
            i.l,
            i.r,
            i.ts,
            i.th,
            i.h,
            i.b,
            i.theta,
            i.wear_plate,
            c.pressure
        );
        for (k, check) in c.checks.iter().enumerate() {
            let (who, case, inp) = if k == 0 {
                (c.saddle.clone(), c.case.to_string(), inputs.clone())
            } else {
                (String::new(), String::new(), String::new())
            };
            row(
                o,
                &[
                    who,
                    case,
                    inp,
                    check.name.into(),
                    format!("{:.1} MPa", check.stress),
                    format!("{:.1} MPa ({})", check.allowable, check.rule),
                    if check.ok() { "OK" } else { "DEFICIENT" }.into(),
                ],
            );
        }
    }
    o.push_str(
        "</table><p>Zick (1951/1971) as Moss Procedure 3-9 and Megyesy give it: \
        operating = operating weight, design pressure, corroded walls, S at the design \
        temperature; hydrotest = full of water, UG-99(b) pressure, new walls, S at the test \
        temperature; each saddle's load by statics from the case's centre of gravity. \
        B of UG-23(b) on the elastic line A·E/2, capped at Sy/4.</p>\n",
    );
}

/// A tank's annular bottom plates (API 650 5.5), when it is a tank.
pub(super) fn annular(o: &mut String, annular: Option<&Result<Annular, String>>) {
    let Some(a) = annular else { return };
    o.push_str("<h3>Annular bottom plates (API 650 5.5)</h3>");
    let a = match a {
        Ok(a) => a,
        Err(e) => {
            let _ = writeln!(o, "<p>Not computed: {}</p>", esc(e));
            return;
        }
    };
    o.push_str("<table>\n");
    head(o, &["Quantity", "Formula", "Value", "Paragraph"]);
    let rows = [
        (
            "First course t",
            "nominal",
            a.course_thickness,
            "mm",
            "5.5.3",
        ),
        (
            "Product stress",
            "(t_d − CA)/(t − CA)·Sd",
            a.product_stress,
            "MPa",
            "Table 5.1a Note b",
        ),
        (
            "Test stress",
            "t_t/t·St",
            a.test_stress,
            "MPa",
            "Table 5.1a Note b",
        ),
        (
            "Table thickness",
            "at the greater stress",
            a.table_thickness,
            "mm",
            "Table 5.1a",
        ),
        ("Least t_b", "table + CA", a.thickness, "mm", "5.5.3"),
        ("L", "215·t_b/(H·G)^0.5", a.width_formula, "mm", "5.5.2"),
        (
            "Least radial width inside the shell",
            "max(600 mm, L)",
            a.width,
            "mm",
            "5.5.2",
        ),
    ];
    for (q, f, v, unit, para) in rows {
        row(
            o,
            &[q.into(), f.into(), format!("{v:.1} {unit}"), para.into()],
        );
    }
    let needed = match a.required {
        Some(true) => "required",
        Some(false) => "not required",
        None => "not assessed",
    };
    row(
        o,
        &[
            "Annular plates".into(),
            a.reason.clone(),
            needed.into(),
            "5.5.1".into(),
        ],
    );
    o.push_str("</table>\n");
}
