//! A simple weld-map sheet (SVG): the welds in elevation (the vessel frame's
//! x–z plane seen from −y, axis up), coloured by UW-3 category as in the GLB,
//! each labelled with its id, beside the weld table (id, category, length,
//! thickness, joint, metal) and a legend.

use std::fmt::Write as _;

use super::process::ProcessPlan;
use super::welds::Category;

fn colour(c: Option<Category>) -> &'static str {
    match c {
        Some(Category::A) => "#d91a1a",
        Some(Category::B) => "#1a4ce6",
        Some(Category::C) => "#1aa633",
        Some(Category::D) => "#f28c0d",
        None => "#808080",
    }
}

fn esc(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
}

/// The weld-map sheet of `plan`.
pub fn weld_svg(plan: &ProcessPlan) -> String {
    let drawn: Vec<_> = plan.welds.iter().filter(|w| w.path.len() >= 2).collect();
    let (mut x0, mut x1, mut z0, mut z1) = (f64::MAX, f64::MIN, f64::MAX, f64::MIN);
    for w in &drawn {
        for p in &w.path {
            x0 = x0.min(p.x);
            x1 = x1.max(p.x);
            z0 = z0.min(p.z);
            z1 = z1.max(p.z);
        }
    }
    if x0 > x1 {
        (x0, x1, z0, z1) = (0.0, 1.0, 0.0, 1.0);
    }
    // Drawing area 560 × 760 px at the left, table at the right.
    let (w_px, h_px, m) = (560.0, 760.0, 30.0);
    let scale = ((w_px - 2.0 * m) / (x1 - x0).max(1.0)).min((h_px - 2.0 * m) / (z1 - z0).max(1.0));
    let sx = |x: f64| m + (x - x0) * scale;
    let sy = |z: f64| h_px - m - (z - z0) * scale;
    let rows = plan.welds.len();
    let height = (h_px + 40.0).max(80.0 + 14.0 * rows as f64);
    let mut s = String::new();
    let _ = write!(
        s,
        "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"1200\" height=\"{height:.0}\" \
         viewBox=\"0 0 1200 {height:.0}\" font-family=\"sans-serif\" font-size=\"10\">\
         <rect width=\"1200\" height=\"{height:.0}\" fill=\"white\"/>\
         <text x=\"{m}\" y=\"20\" font-size=\"14\">Weld map — {} (elevation, 1:{:.0})</text>",
        esc(&plan.vessel),
        1.0 / scale
    );
    for w in &drawn {
        let pts: Vec<String> = w
            .path
            .iter()
            .map(|p| format!("{:.1},{:.1}", sx(p.x), sy(p.z)))
            .collect();
        let tag = if w.closed { "polygon" } else { "polyline" };
        let _ = write!(
            s,
            "<{tag} points=\"{}\" fill=\"none\" stroke=\"{}\" stroke-width=\"1.5\"><title>{}</title></{tag}>",
            pts.join(" "),
            colour(w.category),
            esc(&w.id)
        );
        let mid = w.path[w.path.len() / 2];
        let _ = write!(
            s,
            "<text x=\"{:.1}\" y=\"{:.1}\" fill=\"{}\">{}</text>",
            sx(mid.x) + 3.0,
            sy(mid.z) - 3.0,
            colour(w.category),
            esc(&w.id)
        );
    }
    let tx = 600.0;
    let _ = write!(
        s,
        "<text x=\"{tx}\" y=\"40\" font-weight=\"bold\">Weld  Cat  Length mm  t mm  Joint  Metal cm³</text>"
    );
    for (i, w) in plan.welds.iter().enumerate() {
        let _ = write!(
            s,
            "<text x=\"{tx}\" y=\"{:.0}\" fill=\"{}\">{}  {}  {:.0}  {:.1}  {} ({})  {:.0}</text>",
            56.0 + 14.0 * i as f64,
            colour(w.category),
            esc(&w.id),
            w.category.map_or("—".into(), |c| format!("{c:?}")),
            w.length,
            w.thickness,
            esc(&w.joint),
            esc(&w.prep),
            w.volume * 1e-3
        );
    }
    let legend = [
        (Some(Category::A), "A: long seams, hemi head"),
        (Some(Category::B), "B: circumferential seams"),
        (Some(Category::C), "C: flanges, flat heads"),
        (Some(Category::D), "D: nozzles, boots"),
        (None, "attachments (pads, supports)"),
    ];
    for (i, (c, text)) in legend.iter().enumerate() {
        let y = h_px + 10.0 - 14.0 * (legend.len() - i) as f64;
        let _ = write!(
            s,
            "<line x1=\"{m}\" y1=\"{y:.0}\" x2=\"{:.0}\" y2=\"{y:.0}\" stroke=\"{}\" stroke-width=\"3\"/>\
             <text x=\"{:.0}\" y=\"{:.0}\">{text}</text>",
            m + 20.0,
            colour(*c),
            m + 26.0,
            y + 3.0
        );
    }
    s.push_str("</svg>\n");
    s
}
