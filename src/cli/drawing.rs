//! `vesselcad drawing`: build a design and write one vessel's drawing as SVG,
//! or as PDF when the output ends in `.pdf` (the SVG printed by headless
//! Chromium on a page of the sheet's size, line weights as drawn), and
//! optionally as DXF.
//!
//! A drawing of several sheets (see `drawing::compose_sheets`) is one PDF of
//! as many pages, but one SVG and one DXF file per sheet: SVG has no pages, and
//! a DXF per sheet keeps each sheet's model space at 1:1 with its own
//! paper-space layout, as a CAD user opens and plots it. Sheet 1 (the
//! elevation, schedule and design data) keeps the name given, so a script that
//! reads `name.svg` reads the same sheet as before; sheet `n` is `name-n.svg`.

use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::time::Instant;

use clap::{Args, ValueEnum};
use vesselcad::design::load;
use vesselcad::drawing::{
    HiddenLines, Sheet, SheetModelError, SheetOptions, SheetSize, sheet_model, sheets,
    to_dxf_bytes, to_svg,
};
use vesselcad::mesh::TessellationOptions;
use vesselcad::model::ModelError;
use vesselcad::project::ViewKind;

use super::fail;
use super::output::outln;

/// Sheet sizes on the command line.
#[derive(Clone, Copy, Debug, ValueEnum)]
pub enum SheetArg {
    /// ANSI B, 17 × 11 in.
    AnsiB,
    /// ANSI D, 34 × 22 in.
    AnsiD,
    /// ISO A3.
    A3,
    /// ISO A1.
    A1,
}

/// Views on the command line.
#[derive(Clone, Copy, Debug, ValueEnum)]
pub enum ViewArg {
    /// Front elevation.
    Front,
    /// Plan.
    Top,
    /// Side elevation.
    Side,
    /// Isometric.
    Iso,
}

/// Arguments of `vesselcad drawing`.
#[derive(Args)]
pub struct DrawingArgs {
    /// The design file (JSON, vesselcad/1).
    design: PathBuf,
    /// Tag of the vessel to draw.
    #[arg(long)]
    vessel: String,
    /// Output SVG file, a `.pdf` file (printed with headless Chromium), or `-`
    /// for SVG on standard output. Of a drawing of several sheets, sheet 1 is
    /// written here and sheet n beside it as `name-n.svg` (one PDF of several
    /// pages).
    #[arg(short, long)]
    output: PathBuf,
    /// Also write the drawing as DXF (R2000) to this file (sheet n of several
    /// beside it as `name-n.dxf`).
    #[arg(long)]
    dxf: Option<PathBuf>,
    /// Sheet size.
    #[arg(long, value_enum, default_value = "ansi-d")]
    sheet: SheetArg,
    /// Leave hidden lines out of this view (repeatable).
    #[arg(long = "omit-hidden", value_enum)]
    omit_hidden: Vec<ViewArg>,
    /// Chordal tolerance of the meshes the views are classified against, mm.
    #[arg(long, default_value_t = TessellationOptions::DEFAULT.tolerance, allow_negative_numbers = true)]
    tolerance: f64,
}

/// Runs the command.
pub fn run(args: DrawingArgs) -> ExitCode {
    let start = Instant::now();
    let design = match load(&args.design) {
        Ok(d) => d,
        Err(e) => return fail(&e),
    };
    // Only the vessel drawn is built: a sheet costs what its vessel costs.
    let (model, work) = match sheet_model(
        &design,
        &args.vessel,
        TessellationOptions::chord(args.tolerance),
    ) {
        Ok(built) => built,
        Err(SheetModelError::Model(ModelError::Design(e))) => return fail(&e),
        Err(e @ SheetModelError::UnknownVessel { .. }) => {
            eprintln!("error: {e}");
            return ExitCode::from(1);
        }
        Err(e) => {
            eprintln!("error: {e}");
            return ExitCode::from(2);
        }
    };
    let size = match args.sheet {
        SheetArg::AnsiB => SheetSize::AnsiB,
        SheetArg::AnsiD => SheetSize::AnsiD,
        SheetArg::A3 => SheetSize::IsoA3,
        SheetArg::A1 => SheetSize::IsoA1,
    };
    let mut options = SheetOptions::sized(size);
    for v in args.omit_hidden {
        let view = match v {
            ViewArg::Front => ViewKind::Front,
            ViewArg::Top => ViewKind::Top,
            ViewArg::Side => ViewKind::Side,
            ViewArg::Iso => ViewKind::Iso,
        };
        options = options.with_hidden(view, HiddenLines::Omitted);
    }
    let sheets = match sheets(&model, &args.vessel, &options) {
        Ok(s) => s,
        Err(e) => {
            eprintln!("error: {e}");
            return ExitCode::from(1);
        }
    };
    let to_stdout = args.output.as_os_str() == "-";
    if to_stdout && sheets.len() > 1 {
        eprintln!(
            "error: the drawing of {} has {} sheets and standard output takes one SVG \
             document: give a file name (sheets 2, 3, … are written beside it as name-2.svg, …)",
            args.vessel,
            sheets.len()
        );
        return ExitCode::from(1);
    }
    let is_pdf = args
        .output
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("pdf"));
    let written = if is_pdf {
        let svgs: Vec<String> = sheets.iter().map(to_svg).collect();
        match print_pdf(&svgs, size, &args.output) {
            Ok(()) => Ok(()),
            Err(e) => {
                eprintln!("error: {e}");
                return ExitCode::from(2);
            }
        }
    } else if to_stdout {
        use std::io::Write;
        let mut out = std::io::stdout().lock();
        out.write_all(to_svg(&sheets[0]).as_bytes())
            .and_then(|()| out.flush())
    } else {
        sheets.iter().try_for_each(|s| {
            let path = sheet_path(&args.output, s);
            std::fs::write(&path, to_svg(s))
                .map_err(|e| std::io::Error::new(e.kind(), format!("{}: {e}", path.display())))
        })
    };
    match written {
        // The reader of standard output went away: it had what it wanted.
        Err(e) if to_stdout && e.kind() == std::io::ErrorKind::BrokenPipe => {}
        Err(e) => {
            eprintln!("error: writing {}: {e}", args.output.display());
            return ExitCode::from(2);
        }
        Ok(()) => {}
    }
    if let Some(path) = &args.dxf {
        for s in &sheets {
            let path = sheet_path(path, s);
            let written = to_dxf_bytes(s)
                .map_err(|e| e.to_string())
                .and_then(|bytes| {
                    std::fs::write(&path, bytes)
                        .map_err(|e| format!("writing {}: {e}", path.display()))
                });
            if let Err(e) = written {
                eprintln!("error: {e}");
                return ExitCode::from(2);
            }
        }
    }
    let first = &sheets[0];
    let details: usize = sheets.iter().map(|s| s.details.len()).sum();
    let summary = format!(
        "{}: {} {} at 1:{}{}, {} nozzles scheduled, {} dimensions; built {} vessel(s), \
         {} meshes, {} triangles; {:.0} ms",
        if to_stdout {
            "<stdout>".into()
        } else if sheets.len() > 1 && !is_pdf {
            sheets
                .iter()
                .map(|s| sheet_path(&args.output, s).display().to_string())
                .collect::<Vec<_>>()
                .join(", ")
        } else {
            args.output.display().to_string()
        },
        size.name(),
        if sheets.len() == 1 {
            "sheet".to_string()
        } else {
            format!("{} sheets", sheets.len())
        },
        first.scale,
        if details > 0 {
            format!(" with {details} detail views")
        } else {
            String::new()
        },
        first.schedule.len(),
        sheets.iter().map(|s| s.dimensions.len()).sum::<usize>(),
        work.vessels_resolved,
        work.meshes_rebuilt,
        work.triangles_meshed,
        start.elapsed().as_secs_f64() * 1e3
    );
    // On standard error when the sheet itself goes to standard output.
    if to_stdout {
        eprintln!("{summary}");
    } else {
        outln!("{summary}");
    }
    ExitCode::SUCCESS
}

/// Where sheet `s` of a drawing written to `path` goes: `path` itself for
/// sheet 1, `stem-n.ext` beside it for sheet n.
fn sheet_path(path: &Path, s: &Sheet) -> PathBuf {
    if s.number <= 1 {
        return path.to_path_buf();
    }
    let stem = path
        .file_stem()
        .map_or_else(String::new, |f| f.to_string_lossy().into_owned());
    let name = match path.extension() {
        Some(ext) => format!("{stem}-{}.{}", s.number, ext.to_string_lossy()),
        None => format!("{stem}-{}", s.number),
    };
    path.with_file_name(name)
}

/// Prints the sheets' `svgs` to `out` as a PDF of one page per sheet, each of
/// the sheets' `size`, with headless Chromium.
fn print_pdf(svgs: &[String], size: SheetSize, out: &Path) -> Result<(), String> {
    let paper = size.dimensions();
    let body: String = svgs
        .iter()
        .map(|svg| format!("<div class=\"page\">{svg}</div>"))
        .collect();
    let page = format!(
        "<!doctype html><html><head><meta charset=\"utf-8\"><style>\
         @page{{size:{w}mm {h}mm;margin:0}}html,body{{margin:0;padding:0}}\
         .page{{width:{w}mm;height:{h}mm;overflow:hidden;break-after:page}}\
         .page:last-child{{break-after:auto}}\
         svg{{display:block;width:{w}mm;height:{h}mm}}</style></head><body>{body}</body></html>",
        w = paper.x,
        h = paper.y,
    );
    super::pdf::print_html(&page, out, ".svg")
}
