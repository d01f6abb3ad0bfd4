//! DXF writer: a [`Sheet`] as an AutoCAD R2000 drawing a CAD user can measure.
//!
//! Model space holds the views at 1:1 in millimetres (`$INSUNITS` = 4): every
//! item of the drawing area is scaled up by the sheet's scale, so a view's lines
//! measure model millimetres; an enlarged plan is drawn at 1:1 too, beside the
//! sheet's extent. Dimensions are `DIMENSION` entities (rotated linear and
//! ordinate) of the `VESSELCAD` dimension style (scale = the sheet's), each with
//! its anonymous block of lines, arrowheads and text. The border and the tables
//! are in paper space at sheet millimetres, and the layout has a viewport on the
//! drawing area at the sheet's scale (and one on the enlarged plan, and on each
//! detail view, at its own: a detail's model space is the elevation at 1:1).
//! Layers carry line types (HIDDEN, CENTER defined in the table) and line
//! weights; ° and ⌀ are written `%%d` and `%%c`. The `dxf` crate writes the
//! drawing; [`super::dxf_fixup`] adds what it leaves out (table handles, layer
//! line weights, viewports).

use dxf::entities::{
    Circle, DimensionBase, Entity, EntityType, LwPolyline, OrdinateDimension, RotatedDimension,
    Solid, Text,
};
use dxf::enums::{AcadVersion, DimensionType, HorizontalTextJustification, Units};
use dxf::tables::{DimStyle, Layer as DxfLayer, LineType};
use dxf::{Block, Color, Drawing, LwPolylineVertex, Point};
use glam::DVec2;

use super::DrawingError;
use super::dimensions::format_mm;
use super::dxf_fixup;
use super::dxf_spaces::{Space, spaces};
use super::labels::item_box;
use super::sheet::{Align, Item, Layer, Measure, Sheet};

/// The dimension style's name.
pub const DIM_STYLE: &str = "VESSELCAD";

/// Line type of a layer and its pattern (dash, gap as negative), mm.
fn line_type(layer: Layer) -> (&'static str, &'static [f64]) {
    match layer {
        Layer::Hidden => ("HIDDEN", &[2.5, -1.2]),
        Layer::Centre => ("CENTER", &[8.0, -1.5, 1.5, -1.5]),
        _ => ("CONTINUOUS", &[]),
    }
}

/// ACI colour of a layer.
fn colour(layer: Layer) -> u8 {
    match layer {
        Layer::Border | Layer::Outline | Layer::Text => 7,
        Layer::Hidden => 8,
        Layer::Centre => 1,
        Layer::Dimension => 3,
    }
}

/// A text as every CAD reader shows it: ° and ⌀ (and ±) as `%%d`, `%%c`,
/// `%%p`; the few other non-ASCII characters the sheets use spelt in ASCII.
pub fn cad_text(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    for c in text.chars() {
        match c {
            '°' => out.push_str("%%d"),
            '⌀' => out.push_str("%%c"),
            '±' => out.push_str("%%p"),
            '³' => out.push('3'),
            '²' => out.push('2'),
            '—' | '–' => out.push('-'),
            '…' => out.push_str("..."),
            '×' => out.push('x'),
            c if c.is_ascii() => out.push(c),
            _ => out.push('?'),
        }
    }
    out
}

/// The space an item belongs to.
fn space_of(sheet: &Sheet, item: &Item, spaces: &[Space]) -> Space {
    let first = match item {
        Item::Line { layer, points, .. } | Item::Fill { layer, points } => {
            if *layer == Layer::Border {
                return spaces[0];
            }
            points.first().copied().unwrap_or_default()
        }
        Item::Circle { centre, .. } => *centre,
        Item::Text { .. } => item_box(item).map_or(DVec2::ZERO, |b| 0.5 * (b.min + b.max)),
    };
    space_at(sheet, first, spaces)
}

/// The space of the sheet point `first`.
fn space_at(sheet: &Sheet, first: DVec2, spaces: &[Space]) -> Space {
    if let Some(k) = sheet.details.iter().position(|d| d.region.contains(first)) {
        spaces[3 + k]
    } else if sheet.tables.contains(first) {
        spaces[0]
    } else if sheet.factors[1] > 1.0 && sheet.plan_region.contains(first) {
        spaces[2]
    } else {
        spaces[1]
    }
}

/// The DXF entity of one item in `space`, if it draws anything.
fn item_entity(item: &Item, space: &Space) -> Option<Entity> {
    let (layer, specific) = match item {
        Item::Line {
            layer,
            points,
            closed,
        } if points.len() >= 2 => {
            let mut p = LwPolyline {
                vertices: points
                    .iter()
                    .map(|&q| {
                        let m = space.map(q);
                        LwPolylineVertex {
                            x: m.x,
                            y: m.y,
                            ..Default::default()
                        }
                    })
                    .collect(),
                ..Default::default()
            };
            p.set_is_closed(*closed);
            (*layer, EntityType::LwPolyline(p))
        }
        Item::Fill { layer, points } if points.len() >= 3 => {
            let at = |i: usize| space.point(points[i.min(points.len() - 1)]);
            // SOLID corners go 1, 2, 4, 3; a triangle repeats its last corner.
            (
                *layer,
                EntityType::Solid(Solid::new(at(0), at(1), at(3), at(2))),
            )
        }
        Item::Circle {
            layer,
            centre,
            radius,
        } => (
            *layer,
            EntityType::Circle(Circle::new(space.point(*centre), radius * space.factor)),
        ),
        Item::Text {
            at,
            height,
            align,
            rotation,
            text,
        } => {
            let mut t = Text {
                location: space.point(*at),
                text_height: height * space.factor,
                value: cad_text(text),
                rotation: *rotation,
                ..Default::default()
            };
            t.horizontal_text_justification = match align {
                Align::Start => HorizontalTextJustification::Left,
                Align::Middle => HorizontalTextJustification::Center,
                Align::End => HorizontalTextJustification::Right,
            };
            if *align != Align::Start {
                t.second_alignment_point = t.location.clone();
            }
            (Layer::Text, EntityType::Text(t))
        }
        _ => return None,
    };
    let mut e = Entity::new(specific);
    e.common.layer = layer.name().to_string();
    e.common.is_in_paper_space = space.paper;
    Some(e)
}

/// A dimension's text for the DIMENSION entity: the measured value's place
/// taken by `<>` (the reader writes the measurement there) when the text shows
/// the whole-millimetre value, the text as drawn otherwise.
fn dimension_text(text: &str, value: f64) -> String {
    let shown = format_mm(value);
    if (value - value.round()).abs() < 1e-6
        && value >= 0.0
        && let Some(i) = text.find(&shown)
    {
        let end = i + shown.len();
        let bounded = !text[end..].starts_with(|c: char| c.is_ascii_digit())
            && !text[..i].ends_with(|c: char| c.is_ascii_digit());
        if bounded {
            return cad_text(&format!("{}<>{}", &text[..i], &text[end..]));
        }
    }
    cad_text(text)
}

/// The sheet as a DXF drawing (without the additions of [`to_dxf_bytes`]).
pub fn to_dxf(sheet: &Sheet) -> Drawing {
    let mut drawing = Drawing::new();
    drawing.header.version = AcadVersion::R2000;
    drawing.header.default_drawing_units = Units::Millimeters;
    for name in ["HIDDEN", "CENTER"] {
        let (_, pattern) = if name == "HIDDEN" {
            line_type(Layer::Hidden)
        } else {
            line_type(Layer::Centre)
        };
        drawing.add_line_type(LineType {
            name: name.to_string(),
            description: format!("{name} __ __ __"),
            alignment_code: 65,
            element_count: pattern.len() as i32,
            total_pattern_length: pattern.iter().map(|d| d.abs()).sum(),
            dash_dot_space_lengths: pattern.to_vec(),
            complex_line_type_element_types: vec![0; pattern.len()],
            shape_numbers: vec![0; pattern.len()],
            scale_values: vec![1.0; pattern.len()],
            rotation_angles: vec![0.0; pattern.len()],
            x_offsets: vec![0.0; pattern.len()],
            y_offsets: vec![0.0; pattern.len()],
            text_strings: vec![String::new(); pattern.len()],
            ..Default::default()
        });
    }
    for layer in Layer::ALL {
        drawing.add_layer(DxfLayer {
            name: layer.name().to_string(),
            color: Color::from_index(colour(layer)),
            line_type_name: line_type(layer).0.to_string(),
            ..Default::default()
        });
    }
    drawing.add_layer(DxfLayer {
        name: dxf_fixup::VIEWPORT_LAYER.to_string(),
        color: Color::from_index(8),
        is_layer_plotted: false,
        ..Default::default()
    });
    let h = sheet.size.text_height();
    drawing.add_dim_style(DimStyle {
        name: DIM_STYLE.to_string(),
        dimensioning_scale_factor: sheet.scale,
        dimensioning_text_height: h,
        dimensioning_arrow_size: 0.9 * h,
        dimension_extension_line_offset: 1.5,
        dimension_extension_line_extension: 1.5,
        dimension_line_gap: 1.0,
        ..Default::default()
    });
    let spaces = spaces(sheet);
    let mut in_dimension = vec![false; sheet.items.len()];
    for d in &sheet.dimensions {
        for i in d.items.clone() {
            if let Some(flag) = in_dimension.get_mut(i) {
                *flag = true;
            }
        }
    }
    for (item, _) in sheet
        .items
        .iter()
        .zip(&in_dimension)
        .filter(|(_, dimensioned)| !**dimensioned)
    {
        let space = space_of(sheet, item, &spaces);
        if let Some(e) = item_entity(item, &space) {
            drawing.add_entity(e);
        }
    }
    // Dimensions: an anonymous block of what the sheet draws, and the entity,
    // in the space of the view they belong to.
    for (n, d) in sheet.dimensions.iter().enumerate() {
        let at = match d.measure {
            Measure::Linear { a, .. } => a,
            Measure::Ordinate { feature, .. } => feature,
        };
        let main = space_at(sheet, at, &spaces);
        let name = format!("*D{}", n + 1);
        let entities: Vec<Entity> = d
            .items
            .clone()
            .filter_map(|i| sheet.items.get(i))
            .filter_map(|item| item_entity(item, &main))
            .collect();
        let text_mid = d
            .items
            .clone()
            .filter_map(|i| sheet.items.get(i))
            .find_map(item_box)
            .map_or(d.text_box.min, |b| 0.5 * (b.min + b.max));
        let mut block = Block {
            name: name.clone(),
            flags: 1,
            ..Default::default()
        };
        block.entities = entities;
        drawing.add_block(block);
        let base = |text: String| DimensionBase {
            block_name: name.clone(),
            text_mid_point: main.point(text_mid),
            text,
            dimension_style_name: DIM_STYLE.to_string(),
            is_at_user_defined_location: true,
            ..Default::default()
        };
        let specific = match d.measure {
            Measure::Linear {
                a,
                b,
                line,
                vertical,
                value,
            } => {
                let mut base = base(dimension_text(&d.text, value));
                base.dimension_type = DimensionType::RotatedHorizontalOrVertical;
                base.definition_point_1 = main.point(line);
                EntityType::RotatedDimension(RotatedDimension {
                    dimension_base: base,
                    definition_point_2: main.point(a),
                    definition_point_3: main.point(b),
                    rotation_angle: if vertical { 90.0 } else { 0.0 },
                    ..Default::default()
                })
            }
            Measure::Ordinate {
                feature,
                leader_end,
                vertical,
                value,
            } => {
                let mut base = base(dimension_text(&d.text, value));
                base.dimension_type = DimensionType::Ordinate;
                base.is_ordinate_x_type = !vertical;
                // The datum: the feature less its value along the measured axis.
                let f = main.map(feature);
                let datum = if vertical {
                    DVec2::new(f.x, f.y - value)
                } else {
                    DVec2::new(f.x - value, f.y)
                };
                base.definition_point_1 = Point::new(datum.x, datum.y, 0.0);
                EntityType::OrdinateDimension(OrdinateDimension {
                    dimension_base: base,
                    definition_point_2: main.point(feature),
                    definition_point_3: main.point(leader_end),
                })
            }
        };
        let mut e = Entity::new(specific);
        e.common.layer = Layer::Dimension.name().to_string();
        drawing.add_entity(e);
    }
    drawing
}

/// The sheet as DXF text: [`to_dxf`] with the table handles, layer line weights
/// and paper-space viewports the `dxf` crate does not write.
pub fn to_dxf_bytes(sheet: &Sheet) -> Result<Vec<u8>, DrawingError> {
    let mut out = Vec::new();
    to_dxf(sheet)
        .save(&mut out)
        .map_err(|e| DrawingError::Dxf(e.to_string()))?;
    let text = String::from_utf8(out).map_err(|e| DrawingError::Dxf(e.to_string()))?;
    dxf_fixup::fix_up(&text, sheet).map(String::into_bytes)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn special_characters_are_cad_codes() {
        assert_eq!(cad_text("N1 90°"), "N1 90%%d");
        assert_eq!(cad_text("⌀610 × 12"), "%%c610 x 12");
        assert_eq!(cad_text("35.71 m³"), "35.71 m3");
    }

    #[test]
    fn dimension_texts_let_the_reader_write_whole_values() {
        assert_eq!(dimension_text("T/T 7300", 7300.0), "T/T <>");
        assert_eq!(dimension_text("OD 2400 (S1)", 2400.0), "OD <> (S1)");
        assert_eq!(dimension_text("N1 EL 10000", 1000.0), "N1 EL 10000");
        assert_eq!(dimension_text("HEAD 612.5", 612.5), "HEAD 612.5");
        assert_eq!(dimension_text("BASE EL -3000", -3000.0), "BASE EL -3000");
    }
}
