//! Renders every example sheet in headless Chromium and checks the screenshot is a
//! drawing: not blank, with drawn content in each view's region. The PNGs are kept
//! in `target/drawings/` for a person to look at.

mod common;

use std::path::{Path, PathBuf};
use std::process::Command;

use vesselcad::drawing::{Sheet, SheetOptions, SheetSize, sheet, to_svg};
use vesselcad::mesh::TessellationOptions;
use vesselcad::model::Model;

const CHROMIUM: &str = "/usr/bin/chromium";

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
    let status = Command::new(CHROMIUM)
        .args([
            "--headless",
            "--no-sandbox",
            "--disable-gpu",
            "--disable-quic",
            "--no-first-run",
            "--disable-background-networking",
            "--disable-component-update",
            "--disable-sync",
            "--hide-scrollbars",
        ])
        .arg(format!("--user-data-dir={}", profile.display()))
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
