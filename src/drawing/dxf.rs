//! DXF writer: a [`Sheet`] as an AutoCAD R2000 DXF drawing (the `dxf` crate writes
//! it), in paper millimetres in model space, with one layer per [`Layer`] and the
//! HIDDEN and CENTER line types defined.

use dxf::entities::{Circle, Entity, EntityType, LwPolyline, Solid, Text};
use dxf::enums::{AcadVersion, HorizontalTextJustification, Units};
use dxf::tables::{Layer as DxfLayer, LineType};
use dxf::{Color, Drawing, LwPolylineVertex, Point};

use super::DrawingError;
use super::sheet::{Align, Item, Layer, Sheet};

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

fn entity(layer: Layer, specific: EntityType) -> Entity {
    let mut e = Entity::new(specific);
    e.common.layer = layer.name().to_string();
    e
}

/// The sheet as a DXF drawing.
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
    for item in &sheet.items {
        match item {
            Item::Line {
                layer,
                points,
                closed,
            } if points.len() >= 2 => {
                let mut p = LwPolyline {
                    vertices: points
                        .iter()
                        .map(|q| LwPolylineVertex {
                            x: q.x,
                            y: q.y,
                            ..Default::default()
                        })
                        .collect(),
                    ..Default::default()
                };
                p.set_is_closed(*closed);
                drawing.add_entity(entity(*layer, EntityType::LwPolyline(p)));
            }
            Item::Fill { layer, points } if points.len() >= 3 => {
                let at = |i: usize| {
                    let q = points[i.min(points.len() - 1)];
                    Point::new(q.x, q.y, 0.0)
                };
                // SOLID corners go 1, 2, 4, 3; a triangle repeats its last corner.
                let solid = Solid::new(at(0), at(1), at(3), at(2));
                drawing.add_entity(entity(*layer, EntityType::Solid(solid)));
            }
            Item::Circle {
                layer,
                centre,
                radius,
            } => {
                let c = Circle::new(Point::new(centre.x, centre.y, 0.0), *radius);
                drawing.add_entity(entity(*layer, EntityType::Circle(c)));
            }
            Item::Text {
                at,
                height,
                align,
                rotation,
                text,
            } => {
                let mut t = Text {
                    location: Point::new(at.x, at.y, 0.0),
                    text_height: *height,
                    value: text.clone(),
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
                drawing.add_entity(entity(Layer::Text, EntityType::Text(t)));
            }
            _ => {}
        }
    }
    drawing
}

/// The sheet as DXF text.
pub fn to_dxf_bytes(sheet: &Sheet) -> Result<Vec<u8>, DrawingError> {
    let mut out = Vec::new();
    to_dxf(sheet)
        .save(&mut out)
        .map_err(|e| DrawingError::Dxf(e.to_string()))?;
    Ok(out)
}
