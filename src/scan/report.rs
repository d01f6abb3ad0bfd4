//! The inspection report: HTML for people, JSON for programs. Findings first, as
//! an inspector writes them (what, where by elevation and orientation, how much,
//! against which limit), then the figures they come from.

use std::fmt::Write;

use super::inspect::Inspection;
use super::unrolled::{Layout, UnrolledMap, to_svg};

/// `text` with HTML's special characters escaped.
fn escape(text: &str) -> String {
    text.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}

/// The report as pretty JSON.
pub fn to_json(inspection: &Inspection) -> String {
    serde_json::to_string_pretty(inspection).unwrap_or_else(|e| format!("{{\"error\": \"{e}\"}}"))
}

/// A finding's size with its unit.
fn size(value: f64, unit: &str) -> String {
    match unit {
        "ratio" if value > 0.0 => format!("1/{:.0}", 1.0 / value),
        "%" => format!("{value:.3} % of D"),
        _ => format!("{value:.1} {unit}"),
    }
}

/// The report as a self-contained HTML page.
pub fn to_html(inspection: &Inspection) -> String {
    to_html_with_maps(inspection, &[], 1.0)
}

/// The report with each part's unrolled deviation map (see
/// [`unrolled_maps`](super::unrolled::unrolled_maps)) as SVG after the
/// findings, `scale` mm full colour as in the GLB.
pub fn to_html_with_maps(inspection: &Inspection, maps: &[UnrolledMap], scale: f64) -> String {
    let mut h = String::new();
    let i = inspection;
    let _ = write!(
        h,
        "<!DOCTYPE html><html><head><meta charset=\"utf-8\"><title>Scan of {tag}</title>\
         <style>body{{font-family:sans-serif;margin:2em}}table{{border-collapse:collapse;margin:1em 0}}\
         td,th{{border:1px solid #999;padding:3px 8px;text-align:right}}th{{background:#eee}}\
         .bad{{background:#fcc}}td:first-child{{text-align:left}}</style></head><body>\
         <h1>As built against as designed: {tag}</h1>",
        tag = escape(&i.vessel)
    );
    let flagged = i.checks.findings.iter().filter(|f| f.exceeds).count();
    let _ = write!(
        h,
        "<p>{} points read; {} fitted on the envelope, {} on nozzles, {} outliers. \
         {} findings, {} over their limits.</p>",
        i.points,
        i.fitted,
        i.on_nozzles,
        i.outliers,
        i.checks.findings.len(),
        flagged
    );
    let r = &i.registration;
    if r.kept_frame {
        h.push_str("<p>Registration: the given (plant) frame was kept.</p>");
    } else {
        let t = r.site_to_plant;
        let _ = write!(
            h,
            "<p>Registration (site → plant): turn {:.4}° about up, shift ({:.1}, {:.1}, {:.1}) mm; \
             residual RMS {:.3} mm on {} of {} points, {} iterations.</p>",
            r.yaw, t[0][3], t[1][3], t[2][3], r.rms, r.kept, r.used, r.iterations
        );
    }
    h.push_str("<h2>Findings</h2>");
    if i.checks.findings.is_empty() {
        h.push_str("<p>None: no defect past its detection floor.</p>");
    } else {
        h.push_str(
            "<table><tr><th>Finding</th><th>Part</th><th>Size</th><th>Elevation, mm</th>\
             <th>Orientation</th><th>Extent, mm</th><th>Limit</th><th>Rule</th></tr>",
        );
        for f in &i.checks.findings {
            let _ = write!(
                h,
                "<tr{}><td>{}</td><td>{}</td><td>{}</td><td>{:.0}</td><td>{:.1}°</td><td>{}</td><td>{}</td><td>{}</td></tr>",
                if f.exceeds { " class=\"bad\"" } else { "" },
                f.kind.replace('_', " "),
                escape(&f.part),
                size(f.size, f.unit),
                f.elevation,
                f.orientation,
                f.extent.map_or(String::new(), |e| format!("{e:.0}")),
                f.limit.map_or("—".to_string(), |l| size(l, f.unit)),
                escape(f.rule)
            );
        }
        h.push_str("</table>");
    }
    if !maps.is_empty() {
        let _ = write!(
            h,
            "<h2>Deviation maps</h2><p>The fitted surface's deviation from the design along its \
             normal: blue inward, red outward, full colour at ±{scale:.1} mm (as the GLB), grey \
             without data. Courses and cones unrolled (orientation across, elevation up); heads \
             in plan (0° up, orientation clockwise, distance from the axis out).</p>"
        );
        for m in maps {
            let extreme = m.extreme().and_then(|c| {
                let where_ = match m.layout {
                    Layout::Unrolled => format!("EL {:.0}", (c.band.0 + c.band.1) / 2.0),
                    Layout::Polar => format!("r {:.0}", (c.band.0 + c.band.1) / 2.0),
                };
                c.deviation.map(|d| {
                    format!(
                        "; extreme cell {d:+.1} mm at {where_} / {:.1}°",
                        (c.orientation.0 + c.orientation.1) / 2.0
                    )
                })
            });
            let _ = write!(
                h,
                "<h3>{}</h3><p>{} × {} cells{}</p>{}",
                escape(&m.part),
                m.sectors,
                m.rows,
                extreme.unwrap_or_default(),
                to_svg(m, scale)
            );
        }
    }
    h.push_str(
        "<h2>Parts</h2><table><tr><th>Part</th><th>Role</th><th>Points</th><th>Mean, mm</th>\
         <th>RMS, mm</th><th>Min, mm</th><th>Max, mm</th></tr>",
    );
    for p in &i.parts {
        let _ = write!(
            h,
            "<tr><td>{}</td><td>{:?}</td><td>{}</td><td>{:.2}</td><td>{:.2}</td><td>{:.2}</td><td>{:.2}</td></tr>",
            escape(&p.id),
            p.role,
            p.points,
            p.mean,
            p.rms,
            p.min,
            p.max
        );
    }
    h.push_str("</table><h2>Code checks</h2><table><tr><th>Check</th><th>Part</th><th>Value</th><th>Limit</th></tr>");
    for (id, pct) in &i.checks.roundness {
        let _ = write!(
            h,
            "<tr{}><td>out-of-roundness (UG-80(a))</td><td>{}</td><td>{pct:.3} % of D</td><td>1 %</td></tr>",
            if *pct > 1.0 { " class=\"bad\"" } else { "" },
            escape(id)
        );
    }
    for (id, out, inward) in &i.checks.heads {
        let _ = write!(
            h,
            "<tr><td>head shape (UG-81)</td><td>{}</td><td>+{out:.2} / {inward:.2} mm</td><td>+1¼ % / −⅝ % of D</td></tr>",
            escape(id)
        );
    }
    if let Some(p) = i.checks.plumbness {
        let _ = write!(
            h,
            "<tr{}><td>plumbness</td><td>{}</td><td>{}</td><td>1/200</td></tr>",
            if p > 0.005 { " class=\"bad\"" } else { "" },
            escape(&i.vessel),
            size(p, "ratio")
        );
    }
    h.push_str("</table>");
    if let Some(s) = &i.checks.settlement {
        let allowable = s.allowable.map_or_else(
            || "not known (the shell material is not in the table)".to_string(),
            |a| format!("{a:.1} mm"),
        );
        let _ = write!(
            h,
            "<h2>Settlement (API 653 Annex B)</h2><p>Cosine fit of the bottom edge at {} stations \
             {:.0} mm apart: amplitude {:.1} mm, lowest at {:.1}°, R² = {:.4} ({}). \
             Largest out-of-plane settlement {:.1} mm; permissible S = 11·L²·Y / (2·E·H) with \
             H = {:.0} mm: {}.</p><table><tr><th>Station</th><th>Bottom edge, mm</th>\
             <th>Out of plane S<sub>i</sub>, mm</th></tr>",
            s.stations.len(),
            s.spacing,
            s.amplitude,
            s.lowest,
            s.r_squared,
            if s.cosine_valid {
                "≥ 0.9: a planar tilt"
            } else {
                "< 0.9: not a planar tilt, B.2.2.5 applies"
            },
            s.out_of_plane,
            s.height,
            allowable
        );
        for ((o, z), d) in s.stations.iter().zip(&s.elevations).zip(&s.deviations) {
            let bad = s.allowable.is_some_and(|a| d.abs() > a);
            let _ = write!(
                h,
                "<tr{}><td>{o:.1}°</td><td>{z:.1}</td><td>{d:+.1}</td></tr>",
                if bad { " class=\"bad\"" } else { "" }
            );
        }
        h.push_str("</table>");
    }
    let v = &i.volume;
    let _ = write!(
        h,
        "<h2>Volume</h2><p>Design {:.4} m³, as built {:.4} m³ ({:+.3} %).</p>",
        v.design,
        v.as_built,
        if v.design > 0.0 {
            100.0 * (v.as_built / v.design - 1.0)
        } else {
            0.0
        }
    );
    h.push_str("<h2>Fits</h2><table><tr><th>Patch</th><th>Points</th><th>Net</th><th>Spacing, mm</th><th>RMS, mm</th><th>Max, mm</th><th>Without data</th></tr>");
    for (k, f) in i.fits.iter().enumerate() {
        if let Some(f) = f {
            let _ = write!(
                h,
                "<tr><td>{k}</td><td>{}</td><td>{}×{}</td><td>{:.0}</td><td>{:.3}</td><td>{:.2}</td><td>{}</td></tr>",
                f.points, f.net.0, f.net.1, f.spacing, f.rms, f.max, f.unsupported
            );
        }
    }
    h.push_str("</table></body></html>\n");
    h
}
