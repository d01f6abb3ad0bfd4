//! Renders every example sheet in headless Chromium and checks the screenshot is a
//! drawing: not blank, with drawn content in each view's region; renders the
//! same sheet's DXF (ezdxf's drawing add-on, paper space through its viewports)
//! and PDF (PyMuPDF) and checks that they draw what the SVG draws, where it
//! draws it — on every sheet of a drawing of several, each a page of the PDF. The PNGs are kept in `target/drawings/` for a person to look at.

mod common;

use std::path::{Path, PathBuf};
use std::process::Command;

use vesselcad::drawing::chromium::{CHROMIUM, headless};
use vesselcad::drawing::{Sheet, SheetOptions, SheetSize, sheet, sheets, to_svg};
use vesselcad::mesh::TessellationOptions;
use vesselcad::model::Model;

/// Screenshot width, px; the height follows the sheet's aspect.
const WIDTH: u32 = 1800;

fn out_dir() -> PathBuf {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("target/drawings");
    std::fs::create_dir_all(&dir).expect("target/drawings");
    dir
}

/// Writes the sheet's SVG and an HTML page showing it at the window's width, and
/// screenshots the page; returns the PNG path.
fn render(sheet: &Sheet, name: &str) -> PathBuf {
    let dir = out_dir();
    let svg = dir.join(format!("{name}.svg"));
    std::fs::write(&svg, to_svg(sheet)).unwrap();
    let html = dir.join(format!("{name}.html"));
    std::fs::write(
        &html,
        format!(
            "<!doctype html><html><body style=\"margin:0;background:#fff\">\
             <img src=\"{name}.svg\" style=\"width:100vw;display:block\"></body></html>"
        ),
    )
    .unwrap();
    let size = sheet.size.dimensions();
    let height = (f64::from(WIDTH) * size.y / size.x).ceil() as u32;
    let png = dir.join(format!("{name}.png"));
    std::fs::remove_file(&png).ok();
    let profile =
        std::env::temp_dir().join(format!("vesselcad-chromium-{name}-{}", std::process::id()));
    let status = headless(&profile)
        .arg("--hide-scrollbars")
        .arg(format!("--window-size={WIDTH},{height}"))
        .arg(format!("--screenshot={}", png.display()))
        .arg(format!("file://{}", html.display()))
        .output()
        .expect("run chromium");
    std::fs::remove_dir_all(&profile).ok();
    assert!(
        status.status.success() && png.exists(),
        "chromium failed: {}",
        String::from_utf8_lossy(&status.stderr)
    );
    png
}

/// Decoded RGB(A) pixels: (width, height, bytes per pixel, data).
fn decode(png: &Path) -> (usize, usize, usize, Vec<u8>) {
    let decoder = png::Decoder::new(std::io::BufReader::new(std::fs::File::open(png).unwrap()));
    let mut reader = decoder.read_info().unwrap();
    let mut buf = vec![0; reader.output_buffer_size().unwrap()];
    let info = reader.next_frame(&mut buf).unwrap();
    let bpp = info.color_type.samples();
    assert_eq!(info.bit_depth, png::BitDepth::Eight);
    buf.truncate(info.buffer_size());
    (info.width as usize, info.height as usize, bpp, buf)
}

/// Share of dark pixels in the sheet rectangle (mm) `[lo, hi]`.
fn ink(
    image: &(usize, usize, usize, Vec<u8>),
    sheet: &Sheet,
    lo: glam::DVec2,
    hi: glam::DVec2,
) -> f64 {
    let (w, h, bpp, data) = image;
    let size = sheet.size.dimensions();
    let px = |x: f64| ((x / size.x) * *w as f64).clamp(0.0, *w as f64 - 1.0) as usize;
    let py = |y: f64| (((size.y - y) / size.y) * *h as f64).clamp(0.0, *h as f64 - 1.0) as usize;
    let (x0, x1) = (px(lo.x), px(hi.x));
    let (y0, y1) = (py(hi.y), py(lo.y));
    let mut dark = 0usize;
    let mut total = 0usize;
    for y in y0..=y1 {
        for x in x0..=x1 {
            let i = (y * w + x) * bpp;
            let lum = data[i..i + 3].iter().map(|&c| u32::from(c)).sum::<u32>() / 3;
            dark += usize::from(lum < 160);
            total += 1;
        }
    }
    dark as f64 / total.max(1) as f64
}

#[test]
fn every_example_sheet_renders_as_a_drawing_in_chromium() {
    if !Path::new(CHROMIUM).exists() {
        panic!("{CHROMIUM} is not installed (.ci/run installs Debian's chromium)");
    }
    let cases = [
        ("vertical-column", "C-201", SheetSize::AnsiD),
        ("horizontal-drum", "V-101", SheetSize::AnsiD),
        ("storage-tank", "TK-301", SheetSize::AnsiB),
        ("small-plant", "V-101", SheetSize::IsoA3),
    ];
    for (name, tag, size) in cases {
        let design = common::examples::example(name);
        let model = Model::from_design(&design, TessellationOptions::chord(0.5)).unwrap();
        let s = sheet(&model, tag, &SheetOptions::sized(size)).unwrap();
        let png = render(&s, &format!("{name}-{tag}"));
        let image = decode(&png);
        let paper = size.dimensions();
        let whole = ink(&image, &s, glam::DVec2::ZERO, paper);
        assert!(
            whole > 0.002 && whole < 0.5,
            "{name}: {whole} of the sheet is dark"
        );
        for (k, b) in s.view_boxes.iter().enumerate() {
            let share = ink(&image, &s, b.min, b.max);
            assert!(share > 0.002, "{name}: view {k} region is blank ({share})");
        }
        // The title block corner (lower right) has lettering.
        let corner = ink(
            &image,
            &s,
            glam::DVec2::new(paper.x * 0.8, 0.0),
            glam::DVec2::new(paper.x, paper.y * 0.12),
        );
        assert!(corner > 0.01, "{name}: title block blank ({corner})");
    }
}

/// The Python with ezdxf, matplotlib and PyMuPDF (`.ci/run` makes it).
fn python() -> PathBuf {
    let python = Path::new(env!("CARGO_MANIFEST_DIR")).join("target/occt-venv/bin/python");
    assert!(
        python.exists(),
        "{} is missing (.ci/run makes the venv)",
        python.display()
    );
    python
}

/// Runs `tests/support/render_sheet.py` with `args`.
fn render_with_python(args: &[&str]) {
    let script = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/support/render_sheet.py");
    let out = Command::new(python())
        .arg(script)
        .args(args)
        .output()
        .expect("run python");
    assert!(
        out.status.success(),
        "render_sheet.py {args:?}: {}",
        String::from_utf8_lossy(&out.stderr)
    );
}

/// Size of a comparison cell, paper mm.
const CELL: f64 = 4.0;

/// The paper as a grid of `CELL`-sized cells, each true where any pixel in it
/// is drawn (any channel below 200: coloured layers count).
fn drawn_cells(image: &(usize, usize, usize, Vec<u8>), paper: glam::DVec2) -> Vec<Vec<bool>> {
    let (w, h, bpp, data) = image;
    let nx = (paper.x / CELL) as usize;
    let ny = (paper.y / CELL) as usize;
    let mut cells = vec![vec![false; nx]; ny];
    for y in 0..*h {
        for x in 0..*w {
            let i = (y * w + x) * bpp;
            if data[i..i + 3].iter().any(|&c| c < 200) {
                cells[(y * ny / h).min(ny - 1)][(x * nx / w).min(nx - 1)] = true;
            }
        }
    }
    cells
}

/// Share of the drawn cells of `a` that have a drawn cell of `b` within one
/// cell (the renderers' fonts and line caps differ by a fraction of a cell),
/// leaving out the cells within 8 mm of the paper's edge (in DXF the paper's
/// own outline is the layout itself, not a line).
fn covered(a: &[Vec<bool>], b: &[Vec<bool>]) -> f64 {
    let (ny, nx) = (a.len(), a[0].len());
    let edge = (8.0 / CELL) as usize;
    let near = |j: usize, i: usize| {
        (j.saturating_sub(1)..=(j + 1).min(ny - 1))
            .any(|y| (i.saturating_sub(1)..=(i + 1).min(nx - 1)).any(|x| b[y][x]))
    };
    let mut drawn = 0usize;
    let mut hit = 0usize;
    for (j, row) in a.iter().enumerate().take(ny - edge).skip(edge) {
        for (i, &drawn_here) in row.iter().enumerate().take(nx - edge).skip(edge) {
            if drawn_here {
                drawn += 1;
                hit += usize::from(near(j, i));
            }
        }
    }
    hit as f64 / drawn.max(1) as f64
}

#[test]
fn dxf_and_pdf_draw_what_the_svg_draws_where_it_draws_it() {
    if !Path::new(CHROMIUM).exists() {
        panic!("{CHROMIUM} is not installed (.ci/run installs Debian's chromium)");
    }
    let cases = [
        ("horizontal-drum", "V-101", SheetSize::AnsiD, "ansi-d"),
        ("vertical-column", "C-201", SheetSize::IsoA3, "a3"),
    ];
    let dir = out_dir();
    for (name, tag, size, flag) in cases {
        let design = common::examples::example(name);
        let model = Model::from_design(&design, TessellationOptions::chord(0.5)).unwrap();
        let paper = size.dimensions();
        // The PDF the drawing command prints: a page per sheet.
        let pdf = dir.join(format!("{name}-{tag}-{flag}.pdf"));
        let out = Command::new(env!("CARGO_BIN_EXE_vesselcad"))
            .arg("drawing")
            .arg(common::examples::example_path(name))
            .args(["--vessel", tag, "--sheet", flag, "--tolerance", "0.5", "-o"])
            .arg(&pdf)
            .output()
            .unwrap();
        assert!(
            out.status.success(),
            "{}",
            String::from_utf8_lossy(&out.stderr)
        );
        for s in sheets(&model, tag, &SheetOptions::sized(size)).unwrap() {
            let base = format!("{name}-{tag}-{flag}-{}", s.number);
            let svg = decode(&render(&s, &base));
            // The DXF's paper-space layout, through its viewports.
            let dxf = dir.join(format!("{base}.dxf"));
            std::fs::write(&dxf, vesselcad::drawing::to_dxf_bytes(&s).unwrap()).unwrap();
            let dxf_png = dir.join(format!("{base}-dxf.png"));
            render_with_python(&[
                "dxf",
                dxf.to_str().unwrap(),
                dxf_png.to_str().unwrap(),
                &WIDTH.to_string(),
                &paper.x.to_string(),
                &paper.y.to_string(),
            ]);
            let pdf_png = dir.join(format!("{base}-pdf.png"));
            render_with_python(&[
                "pdf",
                pdf.to_str().unwrap(),
                pdf_png.to_str().unwrap(),
                &WIDTH.to_string(),
                &(s.number - 1).to_string(),
            ]);
            let reference = drawn_cells(&svg, paper);
            for (what, png) in [("DXF", &dxf_png), ("PDF", &pdf_png)] {
                let image = decode(png);
                let regions = s
                    .view_boxes
                    .iter()
                    .zip(s.shown)
                    .filter(|&(_, shown)| shown)
                    .map(|(b, _)| *b)
                    .chain(s.details.iter().map(|d| d.region));
                for (k, b) in regions.enumerate() {
                    let share = ink(&image, &s, b.min, b.max);
                    assert!(
                        share > 0.002,
                        "{name} {what} sheet {}: region {k} is blank ({share})",
                        s.number
                    );
                }
                let cells = drawn_cells(&image, paper);
                let recall = covered(&reference, &cells);
                let precision = covered(&cells, &reference);
                assert!(
                    recall > 0.97 && precision > 0.97,
                    "{name} {what} sheet {}: {recall:.4} of the SVG's drawn cells are drawn, \
                 {precision:.4} of its own are the SVG's ({})",
                    s.number,
                    png.display()
                );
            }
        }
    }
}
