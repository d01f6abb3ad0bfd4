//! `vesselcad fab <design> --vessel TAG -o out/ [--rules shop_rules.json]
//! [--shop plates.json]`: the fabrication files of one vessel (see
//! `vesselcad::fab`): flat patterns, head blanks, seams with their
//! deficiencies, one DXF per plate (a boot's too), per head blank (its
//! openings marked), per pad and per neck template (the saddle cut wrapped
//! round the neck) and the nesting; the process plan on that
//! plate layout — traveler (HTML, CSV), BOM, weld map (CSV, JSON, GLB, SVG) —
//! written into the output directory with a summary printed (and saved as
//! `summary.txt`). One shop file holds it all (`data/shop_rules.json`: its
//! `plates` object is the plate data); `--shop` overrides `plates` field by
//! field.

use std::path::PathBuf;
use std::process::ExitCode;

use clap::Args;
use vesselcad::design::load;
use vesselcad::fab::blank_dxf::write_blank;
use vesselcad::fab::boot::boot_drawing;
use vesselcad::fab::plate_dxf::write_plate;
use vesselcad::fab::process_files::write_process_files;
use vesselcad::fab::template_dxf::write_templates;
use vesselcad::fab::{
    BLANK_RULE, FabError, FabPlan, Nesting, Outline, PlanError, ProcessPlan, Shop, ShopRules, plan,
    process_plan,
};

use super::output::outln;

/// Arguments of `vesselcad fab`.
#[derive(Args)]
pub struct FabArgs {
    /// The design file.
    design: PathBuf,
    /// The vessel to plan.
    #[arg(long)]
    vessel: String,
    /// The output directory (created if missing).
    #[arg(short, long)]
    output: PathBuf,
    /// Plate data (the `plates` object of the shop rules alone) overriding
    /// the rules' plates field by field.
    #[arg(long)]
    shop: Option<PathBuf>,
    /// Shop rules (plates, operations, precedence, weld preparations, PWHT)
    /// replacing the built-in `data/shop_rules.json`.
    #[arg(long)]
    rules: Option<PathBuf>,
}

fn fail(error: &FabError) -> ExitCode {
    eprintln!("error: {error}");
    ExitCode::from(1)
}

fn plan_failed(error: &PlanError) -> ExitCode {
    eprintln!("error: {error}");
    ExitCode::from(match error {
        PlanError::Io { .. } => 2,
        _ => 1,
    })
}

/// Runs `vesselcad fab`.
pub fn run(args: FabArgs) -> ExitCode {
    let design = match load(&args.design) {
        Ok(d) => d,
        Err(e) => return super::fail(&e),
    };
    let mut rules = match &args.rules {
        Some(path) => match ShopRules::from_path(path) {
            Ok(r) => r,
            Err(e) => return plan_failed(&e),
        },
        None => ShopRules::builtin(),
    };
    if let Some(path) = &args.shop {
        match Shop::load_over(path, rules.plates.clone()) {
            Ok(s) => rules.plates = s,
            Err(e) => return fail(&e),
        }
    }
    let shop = rules.plates.clone();
    let plan = match plan(&design, &args.vessel, &shop) {
        Ok(p) => p,
        Err(e) => return fail(&e),
    };
    if let Err(source) = std::fs::create_dir_all(&args.output) {
        return fail(&FabError::Io {
            path: args.output.clone(),
            source,
        });
    }
    let mut lines = developments(&plan);
    lines.extend(seams(&plan));
    for plate in &plan.plates {
        let course = &plan.seams.courses[plate.course_index];
        let rolled = &plan.developments.rolled[course.rolled];
        if let Err(e) = write_plate(&args.output, plate, &plan.grade, rolled, course) {
            return fail(&e);
        }
    }
    let boot_plates = plan.boot_plates();
    for plate in &boot_plates {
        let path = args.output.join(plate.file_name());
        if let Err(e) = boot_drawing(plate, &plan.grade).save_file(&path) {
            return fail(&FabError::Dxf {
                path,
                message: e.to_string(),
            });
        }
    }
    let mut blanks = 0;
    for blank in plan.blanks() {
        let formed: Vec<_> = plan
            .openings
            .formed
            .iter()
            .filter(|f| f.host == blank.id)
            .collect();
        match write_blank(&args.output, &plan.tag, blank, &plan.grade, &formed) {
            Ok(_) => blanks += 1,
            Err(e) => return fail(&e),
        }
    }
    let mut templates = 0;
    for cut in &plan.openings.cuts {
        let shell = plan.developments.rolled[cut.rolled].outside.0;
        match write_templates(&args.output, &plan.tag, cut, &plan.grade, shell) {
            Ok(w) => templates += w.len(),
            Err(e) => return fail(&e),
        }
    }
    for c in &plan.openings.cones {
        // A cone pad is rolled about its apex, not to a shell radius.
        let shell = plan.developments.rolled[c.rolled].outside_at(c.centre.y);
        match write_templates(&args.output, &plan.tag, c, &plan.grade, shell) {
            Ok(w) => templates += w.len(),
            Err(e) => return fail(&e),
        }
    }
    lines.push(format!(
        "{} plate DXF files, {} boot plate, {blanks} head blank, {templates} pad and neck template DXF files in {}",
        plan.plates.len(),
        boot_plates.len(),
        args.output.display()
    ));
    lines.extend(nesting(&plan.nesting(&shop)));
    let process = match process_plan(&plan, &rules) {
        Ok(p) => p,
        Err(e) => return plan_failed(&e),
    };
    let source = args.design.display().to_string();
    let written = match write_process_files(&process, plan.resolved.frame, &source, &args.output) {
        Ok(w) => w,
        Err(e) => return plan_failed(&e),
    };
    lines.push(process_summary(&process));
    lines.extend(written.iter().map(|p| format!("  wrote {}", p.display())));
    for line in &lines {
        outln!("{line}");
    }
    let summary = args.output.join("summary.txt");
    if let Err(source) = std::fs::write(&summary, lines.join("\n") + "\n") {
        return fail(&FabError::Io {
            path: summary,
            source,
        });
    }
    ExitCode::SUCCESS
}

fn process_summary(plan: &ProcessPlan) -> String {
    format!(
        "{}: {} BOM lines, {:.1} kg; {} welds, {:.1} m; {} operations in {} levels; PWHT {}",
        plan.vessel,
        plan.bom.lines.len(),
        plan.bom.total_mass,
        plan.welds.len(),
        plan.welds.iter().map(|w| w.length).sum::<f64>() * 1e-3,
        plan.operations.len(),
        plan.level_count(),
        if plan.pwht.required {
            "required"
        } else {
            "not required"
        }
    )
}

fn seams(plan: &FabPlan) -> Vec<String> {
    let mut out = vec!["courses:".to_string()];
    for c in &plan.seams.courses {
        let rolled = &plan.developments.rolled[c.rolled];
        let seams: Vec<String> = (0..c.plates)
            .map(|k| format!("{:.2}", c.seam(k).to_degrees()))
            .collect();
        out.push(format!(
            "  {:<8} z {:>8.1}..{:<8.1} {} plate(s), long seams at {} deg (local to {})",
            c.id,
            c.z.0,
            c.z.1,
            c.plates,
            seams.join(", "),
            rolled.id
        ));
    }
    if plan.seams.deficiencies.is_empty() {
        out.push("seam rules: all met".into());
    } else {
        out.push(format!("deficiencies ({}):", plan.seams.deficiencies.len()));
        for d in &plan.seams.deficiencies {
            out.push(format!("  {d}"));
        }
    }
    out
}

fn nesting(n: &Nesting) -> Vec<String> {
    let mut out = vec![format!(
        "nesting (first-fit shelves): {} sheet(s), utilisation {:.1} %",
        n.sheets.len(),
        100.0 * n.utilisation
    )];
    for (i, s) in n.sheets.iter().enumerate() {
        let ids: Vec<&str> = s.pieces.iter().map(|p| p.id.as_str()).collect();
        out.push(format!(
            "  sheet {} t {} mm {:.0} x {:.0}: {:.1} %  {}",
            i + 1,
            s.thickness,
            s.size.x,
            s.size.y,
            100.0 * s.utilisation,
            ids.join(" ")
        ));
    }
    for p in &n.oversize {
        out.push(format!(
            "  oversize (special plate): {} {:.0} x {:.0} t {} mm",
            p.id, p.size.x, p.size.y, p.thickness
        ));
    }
    out
}

fn developments(plan: &FabPlan) -> Vec<String> {
    let mut out = Vec::new();
    out.push(format!("{} ({})", plan.tag, plan.grade));
    for r in &plan.developments.rolled {
        let from = r.flat_side.unwrap_or(0.0);
        let outline = r.outline(from, std::f64::consts::TAU, r.z.0, r.z.1);
        let shape = match outline {
            Outline::Rectangle { width, height } => {
                format!("rectangle {width:.1} x {height:.1} mm")
            }
            Outline::Sector {
                inner,
                outer,
                angle,
            } => format!(
                "sector R {inner:.1}..{outer:.1} mm, {:.3} deg",
                angle.to_degrees()
            ),
            Outline::Oblique(plate) => {
                let (w, h) = outline.extent();
                format!(
                    "oblique cone {w:.1} x {h:.1} mm, {:.3} deg, cut open on its flat side",
                    plate.developed_angle().to_degrees()
                )
            }
        };
        out.push(format!(
            "  {:<6} t {:>5.1} mm  developed {shape}, {:.3} m²",
            r.id,
            r.thickness,
            outline.area() * 1e-6
        ));
    }
    for p in plan.boot_plates() {
        let (w, h) = p.extent();
        out.push(format!(
            "  {:<6} t {:>5.1} mm  boot plate {} {w:.1} x {h:.1} mm (host end saddle-cut), {:.3} m², roll to R {:.1}",
            p.part,
            p.thickness,
            p.id,
            p.mid_area * 1e-6,
            p.radius
        ));
    }
    for h in plan.blanks() {
        out.push(format!(
            "  {:<6} t {:>5.1} mm  blank diameter {:.1} mm",
            h.id, h.thickness, h.diameter
        ));
    }
    if plan.blanks().next().is_some() {
        out.push(format!("  (head blanks: {BLANK_RULE})"));
    }
    for s in &plan.developments.skipped {
        out.push(format!("  {:<6} not developed: {}", s.id, s.reason));
    }
    for c in &plan.openings.cones {
        let plate = plan
            .plates
            .iter()
            .find(|p| p.openings.iter().any(|o| o.mark == c.mark))
            .map_or("-", |p| p.id.as_str());
        let rolled = &plan.developments.rolled[c.rolled];
        let kind = if rolled.flat_side.is_some() {
            "eccentric reducer (oblique cone)"
        } else {
            "cone"
        };
        out.push(format!(
            "  {:<6} opening on {}: developed on {kind} plate {plate}",
            c.mark, rolled.id
        ));
    }
    for f in &plan.openings.formed {
        let on_blank = if f.blank.is_some() {
            " (outline marked on the blank)"
        } else {
            ""
        };
        out.push(format!(
            "  {:<6} opening on {}: marked and cut after forming{on_blank}",
            f.mark, f.host
        ));
    }
    out
}
