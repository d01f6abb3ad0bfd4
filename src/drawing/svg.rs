//! SVG writer: a [`Sheet`] as one SVG document (the `svg` crate builds and escapes
//! it), sized in millimetres with a matching view box, one group per layer, line
//! styles in a style sheet. Sheet y points up; SVG y points down, so y is flipped.

use glam::DVec2;
use svg::Document;
use svg::node::element::{Circle, Group, Polygon, Polyline, Rectangle, Style, Text};

use super::sheet::{Align, Item, Layer, Sheet};
use super::text::{CAP_HEIGHT_EM, text_width};

/// The style sheet: line weights (mm) and dash patterns per layer.
const STYLE: &str = "\
.BORDER{stroke:#000;stroke-width:0.5;fill:none}\
.OUTLINE{stroke:#000;stroke-width:0.45;fill:none;stroke-linejoin:round;stroke-linecap:round}\
.HIDDEN{stroke:#333;stroke-width:0.25;fill:none;stroke-dasharray:2.5 1.2}\
.CENTER{stroke:#333;stroke-width:0.18;fill:none;stroke-dasharray:8 1.5 1.5 1.5}\
.DIMENSIONS{stroke:#000;stroke-width:0.18;fill:none}\
.DIMENSIONS polygon{fill:#000;stroke:none}\
.TEXT{font-family:'DejaVu Sans',Arial,Helvetica,sans-serif;fill:#000;stroke:none}";

/// Coordinates with 0.01 mm resolution.
fn num(v: f64) -> String {
    let r = (v * 100.0).round() / 100.0;
    if r == 0.0 {
        "0".to_string()
    } else {
        format!("{r}")
    }
}

/// The sheet as an SVG document (UTF-8 text).
pub fn to_svg(sheet: &Sheet) -> String {
    let size = sheet.size.dimensions();
    let flip = |p: DVec2| DVec2::new(p.x, size.y - p.y);
    let points = |ps: &[DVec2]| {
        ps.iter()
            .map(|&p| {
                let q = flip(p);
                format!("{},{}", num(q.x), num(q.y))
            })
            .collect::<Vec<_>>()
            .join(" ")
    };
    let mut document = Document::new()
        .set("width", format!("{}mm", size.x))
        .set("height", format!("{}mm", size.y))
        .set("viewBox", (0, 0, size.x, size.y))
        .add(Style::new(STYLE))
        .add(
            Rectangle::new()
                .set("width", size.x)
                .set("height", size.y)
                .set("fill", "#fff"),
        );
    for layer in Layer::ALL {
        let mut group = Group::new()
            .set("class", layer.name())
            .set("id", layer.name());
        for item in &sheet.items {
            match item {
                Item::Line {
                    layer: l,
                    points: ps,
                    closed,
                } if *l == layer && ps.len() >= 2 => {
                    let mut ps = ps.clone();
                    if *closed {
                        ps.push(ps[0]);
                    }
                    group = group.add(Polyline::new().set("points", points(&ps)));
                }
                Item::Fill {
                    layer: l,
                    points: ps,
                } if *l == layer => {
                    group = group.add(Polygon::new().set("points", points(ps)));
                }
                Item::Circle {
                    layer: l,
                    centre,
                    radius,
                } if *l == layer => {
                    let c = flip(*centre);
                    group = group.add(
                        Circle::new()
                            .set("cx", num(c.x))
                            .set("cy", num(c.y))
                            .set("r", num(*radius)),
                    );
                }
                Item::Text {
                    at,
                    height,
                    align,
                    rotation,
                    text,
                } if layer == Layer::Text => {
                    let p = flip(*at);
                    let anchor = match align {
                        Align::Start => "start",
                        Align::Middle => "middle",
                        Align::End => "end",
                    };
                    // The font size whose cap height is `height`; the stated
                    // length keeps the text in the box the layout reserved.
                    let mut t = Text::new(text.clone())
                        .set("x", num(p.x))
                        .set("y", num(p.y))
                        .set("font-size", num(height / CAP_HEIGHT_EM))
                        .set("text-anchor", anchor)
                        .set("textLength", num(text_width(text, *height)))
                        .set("lengthAdjust", "spacingAndGlyphs");
                    if *rotation != 0.0 {
                        t = t.set(
                            "transform",
                            format!("rotate({} {} {})", num(-rotation), num(p.x), num(p.y)),
                        );
                    }
                    group = group.add(t);
                }
                _ => {}
            }
        }
        document = document.add(group);
    }
    document.to_string()
}
