//! The HTML report's table of a vertical vessel's supports: the wind and
//! earthquake at the base, then each skirt, legs and lugs check per load
//! combination against its allowable.

use std::fmt::Write;

use super::report_tables::{esc, head, row};
use super::saddles::Check;
use super::summary::VesselCalc;

fn check_row(o: &mut String, who: &str, case: &str, k: &Check) {
    row(
        o,
        &[
            who.into(),
            case.into(),
            k.name.into(),
            format!("{:.2}", k.stress),
            format!("{:.2} ({})", k.allowable, k.rule),
            if k.ok() { "OK" } else { "DEFICIENT" }.into(),
        ],
    );
}

/// The supports table (nothing for a vessel without checked skirts, legs or lugs).
pub(super) fn supports(o: &mut String, v: &VesselCalc) {
    if v.skirts.is_empty() && v.legs.is_empty() && v.lugs.is_empty() {
        return;
    }
    o.push_str("<h3>Supports under weight, wind and earthquake</h3>\n");
    if let Some(l) = &v.lateral {
        let mut text = format!("Base {:.0} mm above grade. ", l.base_elevation);
        match l.wind {
            Some((s, m, q)) => {
                let _ = write!(
                    text,
                    "Wind (ASCE 7-16 §26.10, §29.4): base shear {:.1} kN, moment {:.1} kN·m, qz at \
                     the top {:.0} Pa. ",
                    s * 1e-3,
                    m * 1e-6,
                    q
                );
            }
            None => text.push_str("No wind given. "),
        }
        match l.seismic {
            Some((cs, eq, k, s, m)) => {
                let _ = write!(
                    text,
                    "Earthquake (ASCE 7-16 §12.8, §15.4): Cs = {cs:.4} (Eq. {eq}), k = {k:.2}, base \
                     shear {:.1} kN, moment {:.1} kN·m.",
                    s * 1e-3,
                    m * 1e-6
                );
            }
            None => text.push_str("No earthquake given."),
        }
        let _ = writeln!(o, "<p>{}</p>", esc(&text));
    }
    o.push_str("<table>\n");
    head(
        o,
        &[
            "Part",
            "Combination",
            "Check",
            "Value",
            "Allowable",
            "Status",
        ],
    );
    for s in &v.skirts {
        for c in &s.cases {
            for k in &c.checks {
                check_row(o, &format!("{} ({})", s.id, c.plane), c.load.name, k);
            }
        }
        let ring = match (s.ring_required, s.bearing) {
            (Some(r), Some(b)) => format!(
                "bearing {b:.2} MPa; ring t = l·√(3·fc/S) = {r:.1} mm required, {:.1} mm given",
                s.ring_thickness
            ),
            _ => "no base ring".into(),
        };
        let bolts = match s.bolts {
            Some(n) => format!(
                "{n} bolts on Ø{:.0} mm: {:.1} kN per bolt ({})",
                s.bolt_circle,
                s.bolt_load * 1e-3,
                s.bolt_case
            ),
            None => format!(
                "bolt circle Ø{:.0} mm: {:.1} N/mm of circle ({}); give anchor_bolts for a \
                 load per bolt",
                s.bolt_circle, s.bolt_load, s.bolt_case
            ),
        };
        row(
            o,
            &[
                s.id.clone(),
                "base ring".into(),
                ring,
                String::new(),
                String::new(),
                String::new(),
            ],
        );
        row(
            o,
            &[
                s.id.clone(),
                "anchor bolts".into(),
                bolts,
                String::new(),
                String::new(),
                String::new(),
            ],
        );
    }
    for l in &v.legs {
        for c in &l.cases {
            let k = Check {
                name: c.check.rule,
                ..c.check.clone()
            };
            check_row(
                o,
                &format!("{} (P {:.1} kN)", l.id, c.reaction * 1e-3),
                c.load.name,
                &k,
            );
        }
    }
    for l in &v.lugs {
        for k in &l.checks {
            check_row(
                o,
                &format!("{} (Q {:.1} kN)", l.id, l.reaction * 1e-3),
                l.case,
                k,
            );
        }
    }
    o.push_str(
        "</table><p>Allowable stress combinations of ASCE 7-16 §2.4.1 (0.6W, 0.7E with Ev = \
         0.2·SDS·D); UG-23(d)'s 1.2 on the skirt's allowables with wind or earthquake. Skirt \
         σ = 4M/(π·D²·t) ± W/(π·D·t), B of UG-23(b) at A = 0.125·t/Ro on the elastic line capped \
         at Sy/4. Legs: AISC ASD (9th ed.) E2-1/E2-2, H1-1/H1-2/H1-3, K = 2.0, standard-wall \
         SA-106-B pipe. Lugs: simplified (bearing plate as a simple beam; the shell under the \
         lug's couple as a membrane stress, not WRC 107).</p>\n",
    );
}
