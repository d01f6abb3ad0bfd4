//! The shop traveler of a plan as CSV and as one HTML page (process sheet:
//! header, operations by level with item, method and inputs from the model,
//! then the bill of materials and the weld map), and the weld map as CSV.
//! The CSVs quote every text field (RFC 4180).

use std::fmt::Write as _;

use super::process::ProcessPlan;

/// A CSV field, quoted.
fn q(s: &str) -> String {
    format!("\"{}\"", s.replace('"', "\"\""))
}

/// HTML text, escaped.
fn h(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}

/// The traveler as CSV: level, operation id, operation, item, method,
/// predecessors, inputs.
pub fn traveler_csv(plan: &ProcessPlan) -> String {
    let mut out = String::from("level,operation_id,operation,item,method,after,inputs\n");
    for o in &plan.operations {
        let _ = writeln!(
            out,
            "{},{},{},{},{},{},{}",
            o.level,
            q(&o.id),
            q(&o.name),
            q(&o.item),
            q(&o.method),
            q(&o.after.join(" ")),
            q(&o.inputs)
        );
    }
    out
}

/// The weld map as CSV.
pub fn welds_csv(plan: &ProcessPlan) -> String {
    let mut out = String::from(
        "weld_id,kind,category,joins,item,length_mm,thickness_mm,prep,joint,volume_mm3\n",
    );
    for w in &plan.welds {
        let _ = writeln!(
            out,
            "{},{},{},{},{},{:.3},{:.2},{},{},{:.0}",
            q(&w.id),
            q(&format!("{:?}", w.kind)),
            w.category.map_or("—".into(), |c| format!("{c:?}")),
            q(&w.joins.join(" + ")),
            q(&w.item),
            w.length,
            w.thickness,
            q(&w.prep),
            q(&w.joint),
            w.volume
        );
    }
    out
}

/// The BOM as CSV.
pub fn bom_csv(plan: &ProcessPlan) -> String {
    let mut out = String::from(
        "item,kind,description,material,thickness_mm,size,area_m2,quantity,mass_kg,bolting,gasket\n",
    );
    for l in &plan.bom.lines {
        let _ = writeln!(
            out,
            "{},{},{},{},{},{},{},{},{:.3},{},{}",
            q(&l.item),
            l.kind,
            q(&l.description),
            q(&l.material),
            l.thickness.map_or(String::new(), |t| format!("{t:.2}")),
            q(&l.size),
            l.area.map_or(String::new(), |a| format!("{a:.4}")),
            l.quantity,
            l.mass,
            q(l.bolting.as_deref().unwrap_or("")),
            q(l.gasket.as_deref().unwrap_or(""))
        );
    }
    let _ = writeln!(out, "\"total\",,,,,,,,{:.3},,", plan.bom.total_mass);
    out
}

/// The traveler as one HTML page.
pub fn traveler_html(plan: &ProcessPlan, source: &str) -> String {
    let mut b = String::new();
    let _ = write!(
        b,
        "<!DOCTYPE html><html lang=\"en\"><head><meta charset=\"utf-8\"><title>Traveler {tag}</title>\
         <style>body{{font:13px sans-serif;margin:1.5em}}table{{border-collapse:collapse;margin-bottom:1.5em}}\
         td,th{{border:1px solid #999;padding:2px 6px;text-align:left;vertical-align:top}}\
         th{{background:#eee}}tr.level td:first-child{{font-weight:bold}}</style></head><body>\
         <h1>Traveler — {tag}</h1><p>Design {src}. {n} operations in {levels} levels; \
         operations of one level can run at once. PWHT: {pwht} ({group}, nominal thickness \
         {t:.1} mm; {rule}).</p>",
        tag = h(&plan.vessel),
        src = h(source),
        n = plan.operations.len(),
        levels = plan.level_count(),
        pwht = if plan.pwht.required {
            "required"
        } else {
            "not required"
        },
        group = h(&plan.pwht.group),
        t = plan.pwht.thickness,
        rule = h(&plan.pwht.rule),
    );
    b.push_str(
        "<h2>Operations</h2><table><tr><th>Level</th><th>Operation id</th><th>Operation</th>\
         <th>Item</th><th>Method</th><th>After</th><th>Inputs</th><th>Done</th></tr>",
    );
    for o in &plan.operations {
        let _ = write!(
            b,
            "<tr class=\"level\" data-level=\"{}\"><td>{}</td><td>{}</td><td>{}</td><td>{}</td>\
             <td>{}</td><td>{}</td><td>{}</td><td></td></tr>",
            o.level,
            o.level,
            h(&o.id),
            h(&o.name),
            h(&o.item),
            h(&o.method),
            h(&o.after.join(", ")),
            h(&o.inputs)
        );
    }
    b.push_str(
        "</table><h2>Bill of materials</h2><table><tr><th>Item</th><th>Kind</th>\
         <th>Description</th><th>Material</th><th>t, mm</th><th>Size, mm</th><th>Area, m²</th>\
         <th>Qty</th><th>Mass, kg</th><th>Bolting / gasket</th></tr>",
    );
    for l in &plan.bom.lines {
        let _ = write!(
            b,
            "<tr><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td>\
             <td>{}</td><td>{:.1}</td><td>{}</td></tr>",
            h(&l.item),
            l.kind,
            h(&l.description),
            h(&l.material),
            l.thickness.map_or(String::new(), |t| format!("{t:.1}")),
            h(&l.size),
            l.area.map_or(String::new(), |a| format!("{a:.3}")),
            l.quantity,
            l.mass,
            h(&[l.bolting.clone(), l.gasket.clone()]
                .into_iter()
                .flatten()
                .collect::<Vec<_>>()
                .join("; "))
        );
    }
    let _ = write!(
        b,
        "<tr><th colspan=\"8\">Total</th><th>{:.1}</th><th></th></tr></table>",
        plan.bom.total_mass
    );
    b.push_str(
        "<h2>Weld map</h2><table><tr><th>Weld</th><th>Category</th><th>Joins</th>\
         <th>Length, mm</th><th>t, mm</th><th>Joint</th><th>Prep</th><th>Metal, cm³</th></tr>",
    );
    for w in &plan.welds {
        let _ = write!(
            b,
            "<tr><td>{}</td><td>{}</td><td>{}</td><td>{:.1}</td><td>{:.1}</td><td>{}</td>\
             <td>{}</td><td>{:.0}</td></tr>",
            h(&w.id),
            w.category.map_or("—".into(), |c| format!("{c:?}")),
            h(&w.joins.join(" + ")),
            w.length,
            w.thickness,
            h(&w.joint),
            h(&w.prep),
            w.volume * 1e-3
        );
    }
    b.push_str("</table></body></html>\n");
    b
}
