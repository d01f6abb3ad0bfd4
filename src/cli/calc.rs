//! `vesselcad calc`: the code calculation report of a design's vessels — text on
//! standard output, JSON (`vesselcad-calc/1`), or an HTML or PDF file (PDF printed
//! by headless Chromium). Also the deficiency list `check` prints.

use std::path::{Path, PathBuf};
use std::process::ExitCode;

use clap::Args;
use serde_json::json;
use vesselcad::calc::html::{ReportVessel, html};
use vesselcad::calc::{Calculation, MaterialTable, calculate};
use vesselcad::design::{Design, DesignError, load, resolve};
use vesselcad::weights::{Weights, weights};

/// The format tag of `calc --json`.
pub const CALC_FORMAT: &str = "vesselcad-calc/1";

/// Arguments of `vesselcad calc`.
#[derive(Args)]
pub struct CalcArgs {
    /// The design file.
    design: PathBuf,
    /// Only this vessel (default: every vessel).
    #[arg(long)]
    vessel: Option<String>,
    /// Print JSON (`vesselcad-calc/1`) instead of text.
    #[arg(long)]
    json: bool,
    /// Write the report to this file: `.html`, or `.pdf` (headless Chromium).
    #[arg(short, long)]
    output: Option<PathBuf>,
    /// A materials table in the built-in table's format (e.g. a licensed II-D table).
    #[arg(long)]
    materials: Option<PathBuf>,
}

/// One vessel's calculation and weights.
pub struct Calculated {
    /// Index in the design.
    pub index: usize,
    /// The calculation.
    pub calculation: Calculation,
    /// The weights, or why not.
    pub weights: Result<Weights, String>,
}

/// Calculates the vessels of `design` (or only `only`).
pub fn calculate_design(
    design: &Design,
    only: Option<&str>,
    table: &MaterialTable,
) -> Result<Vec<Calculated>, DesignError> {
    let resolved = resolve(design)?;
    Ok(design
        .vessels
        .iter()
        .zip(&resolved)
        .enumerate()
        .filter(|(_, (d, _))| only.is_none_or(|t| t == d.tag))
        .map(|(index, (d, r))| Calculated {
            index,
            calculation: calculate(d, r, table),
            weights: weights(d, r).map_err(|e| e.to_string()),
        })
        .collect())
}

/// The deficiencies of every vessel of `design`, as `(tag, sentence)`.
pub fn deficiencies(design: &Design) -> Vec<(String, String)> {
    let Ok(all) = calculate_design(design, None, &MaterialTable::builtin()) else {
        return Vec::new();
    };
    all.into_iter()
        .flat_map(|c| {
            let tag = c.calculation.vessel.tag.clone();
            c.calculation
                .vessel
                .deficiencies
                .into_iter()
                .map(move |d| (tag.clone(), d))
        })
        .collect()
}

fn fail(message: impl std::fmt::Display, code: u8) -> ExitCode {
    eprintln!("error: {message}");
    ExitCode::from(code)
}

/// Runs `vesselcad calc`.
pub fn run(args: CalcArgs) -> ExitCode {
    let design = match load(&args.design) {
        Ok(d) => d,
        Err(e) => {
            let code = if matches!(e, DesignError::Io { .. }) {
                2
            } else {
                1
            };
            return fail(e, code);
        }
    };
    let table = match &args.materials {
        Some(p) => match MaterialTable::from_path(p) {
            Ok(t) => t,
            Err(e) => return fail(e, 2),
        },
        None => MaterialTable::builtin(),
    };
    if let Some(tag) = &args.vessel
        && !design.vessels.iter().any(|v| &v.tag == tag)
    {
        let known: Vec<&str> = design.vessels.iter().map(|v| v.tag.as_str()).collect();
        return fail(
            format!(
                "--vessel {tag}: no such vessel; the design has {}",
                known.join(", ")
            ),
            1,
        );
    }
    let all = match calculate_design(&design, args.vessel.as_deref(), &table) {
        Ok(a) => a,
        Err(e) => return fail(e, 1),
    };
    let source = args.design.display().to_string();
    if let Some(out) = &args.output {
        let report: Vec<ReportVessel> = all
            .iter()
            .map(|c| ReportVessel {
                design: &design.vessels[c.index],
                calculation: &c.calculation,
                weights: c.weights.as_ref().map_err(Clone::clone),
            })
            .collect();
        let page = html(&source, &report);
        let pdf = out
            .extension()
            .is_some_and(|e| e.eq_ignore_ascii_case("pdf"));
        let written = if pdf {
            print_pdf(&page, out)
        } else {
            std::fs::write(out, page).map_err(|e| format!("{}: {e}", out.display()))
        };
        if let Err(e) = written {
            return fail(e, 2);
        }
        eprintln!("wrote {}", out.display());
    } else if args.json {
        let vessels: Vec<_> = all
            .iter()
            .map(|c| {
                json!({
                    "calculation": c.calculation,
                    "weights": c.weights.as_ref().ok(),
                    "weights_problem": c.weights.as_ref().err(),
                })
            })
            .collect();
        let doc = json!({
            "format": CALC_FORMAT,
            "file": source,
            "units": {"pressure": "MPa", "length": "mm", "mass": "kg", "volume": "m3", "stress": "MPa"},
            "vessels": vessels,
        });
        println!("{}", serde_json::to_string_pretty(&doc).unwrap_or_default());
    } else {
        for c in &all {
            print_text(c);
        }
    }
    ExitCode::SUCCESS
}

fn print_text(c: &Calculated) {
    let v = &c.calculation.vessel;
    println!("{} ({})", v.tag, v.code);
    for p in &v.problems {
        println!("  not calculated:   {p}");
    }
    for p in &c.calculation.parts {
        println!(
            "  {:<8} {:<20} t req {:>7.2} mm  t {:>7} mm  MAWP {:>8} MPa  {}  {}",
            p.id,
            p.shape,
            p.required.value.max(p.minimum),
            p.thickness.map_or("—".into(), |t| format!("{t:.2}")),
            p.mawp
                .as_ref()
                .map_or("—".into(), |m| format!("{:.4}", m.value)),
            p.required.paragraph,
            if p.deficiency.is_some() {
                "DEFICIENT"
            } else {
                "ok"
            }
        );
    }
    for n in &c.calculation.nozzles {
        println!(
            "  {:<8} UG-45 neck {:>6.2} mm available, {:>6.2} mm required  {}",
            n.mark,
            n.available,
            n.required,
            if n.deficiency.is_some() {
                "DEFICIENT"
            } else {
                "ok"
            }
        );
        for r in n.reinforcement.iter().chain(&n.reinforcement_external) {
            println!(
                "  {:<8} {:<11} area {:>8.0} mm² available, {:>8.0} mm² required  {}",
                n.mark,
                r.paragraph,
                r.a_available,
                r.a_required,
                match (r.exempt, r.deficient()) {
                    (Some(_), _) => "exempt (UG-36(c)(3))",
                    (None, true) => "DEFICIENT",
                    (None, false) => "ok",
                }
            );
        }
        if let Some(f) = &n.flange {
            println!(
                "  {:<8} B16.5 Class {} group {}: {:.3} MPa at {} °C for {:.3} MPa  {}",
                n.mark,
                f.class,
                f.group,
                f.rating,
                f.temperature,
                f.pressure,
                if f.deficiency.is_some() {
                    "DEFICIENT"
                } else {
                    "ok"
                }
            );
        }
    }
    if let Some(m) = v.mawp {
        println!(
            "  MAWP (top):       {:.0} kPa(g), governed by {}",
            m * 1e3,
            v.governing.as_deref().unwrap_or("—")
        );
    }
    let mdmt = vesselcad::calc::mdmt::vessel_mdmt(
        c.calculation
            .parts
            .iter()
            .filter_map(|p| p.mdmt.as_ref().map(|m| (p.id.as_str(), m))),
    );
    if let Some((id, t)) = mdmt {
        println!("  MDMT (UCS-66):    {t:.1} °C, governed by {id}");
    }
    for p in &c.calculation.parts {
        match &p.external {
            Some(Ok(x)) => println!(
                "  {:<8} {} external: A {:.3e}, B {:.1} MPa, Pa {:.4} MPa",
                p.id, x.paragraph, x.a, x.b, x.allowable
            ),
            Some(Err(e)) => println!("  {:<8} external pressure not computed: {e}", p.id),
            None => {}
        }
    }
    for p in &c.calculation.parts {
        if let Some(m) = p.mdmt.as_ref().filter(|m| m.temperature.is_none()) {
            println!("  MDMT {:<8}     not computed: {}", p.id, m.basis);
        }
    }
    if let Some(h) = &v.hydrotest {
        println!(
            "  hydrotest (top):  {:.0} kPa(g) ({})",
            h.value * 1e3,
            h.paragraph
        );
    }
    match &v.annular {
        Some(Ok(a)) => println!(
            "  annular (5.5):    t_b >= {:.1} mm, width >= {:.0} mm inside the shell; {}",
            a.thickness, a.width, a.reason
        ),
        Some(Err(e)) => println!("  annular (5.5):    not computed: {e}"),
        None => {}
    }
    match &c.weights {
        Ok(w) => println!(
            "  weights:          empty {:.0} kg, operating {:.0} kg, test {:.0} kg",
            w.empty, w.operating, w.test
        ),
        Err(e) => println!("  weights:          not computed: {e}"),
    }
    for s in &v.saddles {
        let worst = s
            .checks
            .iter()
            .max_by(|a, b| (a.stress / a.allowable).total_cmp(&(b.stress / b.allowable)));
        if let Some(w) = worst {
            println!(
                "  {:<8} Zick {:<9} Q {:.1} kN, A {:.0} mm; highest: {} {:.1} of {:.1} MPa ({}) {}",
                s.saddle,
                s.case,
                s.input.load * 1e-3,
                s.input.a,
                w.name,
                w.stress,
                w.allowable,
                w.rule,
                if s.checks.iter().all(|c| c.ok()) {
                    "ok"
                } else {
                    "DEFICIENT"
                }
            );
        }
    }
    supports(v);
    for d in &v.deficiencies {
        println!("  DEFICIENCY:       {d}");
    }
}

/// Prints a vertical vessel's wind, earthquake and skirt, legs and lugs figures.
fn supports(v: &vesselcad::calc::VesselCalc) {
    if let Some(l) = &v.lateral {
        if let Some((s, m, _)) = l.wind {
            println!(
                "  wind (base):      shear {:.1} kN, moment {:.1} kN·m (ASCE 7-16)",
                s * 1e-3,
                m * 1e-6
            );
        }
        if let Some((cs, eq, _, s, m)) = l.seismic {
            println!(
                "  seismic (base):   Cs {cs:.4} (Eq. {eq}), shear {:.1} kN, moment {:.1} kN·m",
                s * 1e-3,
                m * 1e-6
            );
        }
    }
    let status = |ok: bool| if ok { "ok" } else { "DEFICIENT" };
    for s in &v.skirts {
        let worst = s
            .cases
            .iter()
            .flat_map(|c| c.checks.iter().map(move |k| (c, k)))
            .max_by(|a, b| (a.1.stress / a.1.allowable).total_cmp(&(b.1.stress / b.1.allowable)));
        if let Some((c, k)) = worst {
            println!(
                "  {:<8} skirt {} {}: {} {:.1} of {:.1} MPa ({}) {}",
                s.id,
                c.plane,
                c.load.name,
                k.name,
                k.stress,
                k.allowable,
                k.rule,
                status(k.ok())
            );
        }
        if let (Some(r), Some(b)) = (s.ring_required, s.bearing) {
            println!(
                "  {:<8} base ring {:.1} mm required (bearing {:.2} MPa), {:.1} mm modelled {}",
                s.id,
                r,
                b,
                s.thickness,
                status(r <= s.thickness)
            );
        }
        match s.bolts {
            Some(n) => println!(
                "  {:<8} anchor bolts {n} on Ø{:.0} mm: {:.1} kN per bolt ({}){}",
                s.id,
                s.bolt_circle,
                s.bolt_load * 1e-3,
                s.bolt_case,
                if s.bolt_load <= 0.0 {
                    ", no uplift"
                } else {
                    ""
                }
            ),
            None => println!(
                "  {:<8} anchor bolts on Ø{:.0} mm: {:.1} N per mm of circle ({}){}",
                s.id,
                s.bolt_circle,
                s.bolt_load,
                s.bolt_case,
                if s.bolt_load <= 0.0 {
                    ", no uplift"
                } else {
                    ""
                }
            ),
        }
    }
    for l in &v.legs {
        if let Some(c) = l
            .cases
            .iter()
            .max_by(|a, b| a.check.stress.total_cmp(&b.check.stress))
        {
            println!(
                "  {:<8} legs {}: P {:.1} kN, uplift {:.1} kN, KL/r {:.0}, {} = {:.2} {}",
                l.id,
                c.load.name,
                c.reaction * 1e-3,
                (-c.uplift).max(0.0) * 1e-3,
                l.slenderness,
                c.check.rule,
                c.check.stress,
                status(c.check.ok())
            );
        }
    }
    for l in &v.lugs {
        for k in &l.checks {
            println!(
                "  {:<8} lugs {}: Q {:.1} kN, {} {:.1} of {:.1} MPa ({}) {}",
                l.id,
                l.case,
                l.reaction * 1e-3,
                k.name,
                k.stress,
                k.allowable,
                k.rule,
                status(k.ok())
            );
        }
    }
}

/// Prints `page` to `out` as PDF with headless Chromium.
fn print_pdf(page: &str, out: &Path) -> Result<(), String> {
    super::pdf::print_html(page, out, ".html")
}
