//! One DXF per plate, at 1:1 in millimetres (`$INSUNITS` = 4), for a cutting
//! table: layer `CUT` holds the outline and the openings (closed polylines;
//! a cone plate's arcs as exact bulges, an eccentric reducer's developed
//! curves as chords within [`super::oblique::OUTLINE_SAG`]), `MARK` the marking lines (nozzle
//! centrelines, the vessel's 0°/90°/180°/270° orientation lines that cross
//! the plate: along the axis on a course, the developed generator on a
//! cone), `TEXT` the plate id, grade, thickness and course.

use std::f64::consts::{FRAC_PI_2, TAU};
use std::path::Path;

use dxf::entities::{Entity, EntityType, Line, LwPolyline, Text};
use dxf::enums::{AcadVersion, Units};
use dxf::tables::Layer;
use dxf::{Color, Drawing, LwPolylineVertex, Point};
use glam::{DVec2, DVec3};

use super::cone_openings::{ConeSurface, develop_point};
use super::develop::{Outline, Rolled};
use super::error::FabError;
use super::plates::Plate;
use super::seams::Course;

pub(super) fn entity(layer: &str, specific: EntityType) -> Entity {
    let mut e = Entity::new(specific);
    e.common.layer = layer.to_string();
    e
}

pub(super) fn vertex(p: DVec2, bulge: f64) -> LwPolylineVertex {
    LwPolylineVertex {
        x: p.x,
        y: p.y,
        bulge,
        ..Default::default()
    }
}

pub(super) fn closed(points: Vec<LwPolylineVertex>) -> EntityType {
    let mut p = LwPolyline {
        vertices: points,
        ..Default::default()
    };
    p.set_is_closed(true);
    EntityType::LwPolyline(p)
}

pub(super) fn line(a: DVec2, b: DVec2) -> EntityType {
    EntityType::Line(Line::new(
        Point::new(a.x, a.y, 0.0),
        Point::new(b.x, b.y, 0.0),
    ))
}

/// The plate's drawing. `grade` is the material; `rolled` and `course` the
/// part and course it is cut from.
pub fn plate_drawing(plate: &Plate, grade: &str, rolled: &Rolled, course: &Course) -> Drawing {
    let mut d = new_drawing();
    let (width, height) = plate.outline.extent();
    match plate.outline {
        Outline::Rectangle { width, height } => {
            let corners = [
                DVec2::ZERO,
                DVec2::new(width, 0.0),
                DVec2::new(width, height),
                DVec2::new(0.0, height),
            ];
            d.add_entity(entity(
                "CUT",
                closed(corners.iter().map(|&p| vertex(p, 0.0)).collect()),
            ));
        }
        Outline::Sector {
            inner,
            outer,
            angle,
        } => {
            // Bisector along +y, apex at the origin; each arc as two exact
            // bulges tan(Δ/4) of half the angle (a bulge spans less than a
            // full turn).
            let at =
                |r: f64, a: f64| DVec2::new(r * (FRAC_PI_2 + a).cos(), r * (FRAC_PI_2 + a).sin());
            let half = 0.5 * angle;
            let bulge = (angle / 8.0).tan();
            let points = vec![
                vertex(at(outer, -half), bulge),
                vertex(at(outer, 0.0), bulge),
                vertex(at(outer, half), 0.0),
                vertex(at(inner, half), -bulge),
                vertex(at(inner, 0.0), -bulge),
                vertex(at(inner, -half), 0.0),
            ];
            d.add_entity(entity("CUT", closed(points)));
        }
        Outline::Oblique(o) => {
            // The developed curves as chords within `OUTLINE_SAG`.
            let points = o.outline().into_iter().map(|p| vertex(p, 0.0)).collect();
            d.add_entity(entity("CUT", closed(points)));
        }
    }
    for o in &plate.openings {
        d.add_entity(entity(
            "CUT",
            closed(o.contour.iter().map(|&p| vertex(p, 0.0)).collect()),
        ));
        let (c, r) = (o.centre, o.reach);
        d.add_entity(entity("MARK", line(c - DVec2::X * r.x, c + DVec2::X * r.x)));
        d.add_entity(entity("MARK", line(c - DVec2::Y * r.y, c + DVec2::Y * r.y)));
        text(&mut d, c + DVec2::new(r.x * 0.2, r.y * 0.6), 25.0, &o.mark);
    }
    // The vessel's orientation lines that cross the plate: on a course a
    // line along the axis, on a cone the generator developed.
    let theta0 = course.seam(plate.seam);
    for quarter in 0..4 {
        let want = f64::from(quarter) * FRAC_PI_2;
        let local = rolled.frame.matrix3.inverse() * DVec3::new(want.cos(), want.sin(), 0.0);
        let rel = (local.y.atan2(local.x) - theta0).rem_euclid(TAU);
        if rel >= course.pitch() {
            continue;
        }
        let (a, b) = match plate.outline {
            Outline::Rectangle { .. } => {
                let x = rolled.radius_at(course.z.0) * rel;
                (DVec2::new(x, 0.0), DVec2::new(x, height))
            }
            Outline::Sector { .. } => {
                let surface = ConeSurface::mid(rolled);
                let mid = theta0 + 0.5 * course.pitch();
                let at = |z: f64| develop_point(&surface, mid, DVec2::new(theta0 + rel, z));
                (at(course.z.0), at(course.z.1))
            }
            Outline::Oblique(o) => (
                o.develop(theta0 + rel, course.z.0),
                o.develop(theta0 + rel, course.z.1),
            ),
        };
        d.add_entity(entity("MARK", line(a, b)));
        let across = -(b - a).perp().normalize_or_zero();
        text(
            &mut d,
            0.5 * (a + b) + across * 10.0,
            25.0,
            &format!("{}°", quarter * 90),
        );
    }
    let label = DVec2::new(0.05 * width, 0.15 * height);
    let size = (0.04 * height).clamp(10.0, 80.0);
    let base = match plate.outline {
        Outline::Rectangle { .. } => label,
        Outline::Sector { inner, outer, .. } => {
            DVec2::new(-0.2 * (outer - inner), 0.5 * (inner + outer))
        }
        Outline::Oblique(o) => {
            o.develop(o.from + 0.5 * o.angle, 0.5 * (o.z.0 + o.z.1)) - DVec2::X * 0.2 * width
        }
    };
    text(&mut d, base, size, &plate.id);
    text(
        &mut d,
        base - DVec2::Y * 1.5 * size,
        size,
        &format!(
            "{grade}  t = {} mm  course {}",
            plate.thickness, plate.course
        ),
    );
    d
}

/// An empty drawing in millimetres with the layers `CUT`, `MARK` and `TEXT`.
pub(super) fn new_drawing() -> Drawing {
    let mut d = Drawing::new();
    d.header.version = AcadVersion::R2000;
    d.header.default_drawing_units = Units::Millimeters;
    for (name, colour) in [("CUT", 7), ("MARK", 1), ("TEXT", 3)] {
        d.add_layer(Layer {
            name: name.into(),
            color: Color::from_index(colour),
            ..Default::default()
        });
    }
    d
}

pub(super) fn text(d: &mut Drawing, at: DVec2, height: f64, value: &str) {
    let t = Text {
        location: Point::new(at.x, at.y, 0.0),
        text_height: height,
        value: value.to_string(),
        ..Default::default()
    };
    d.add_entity(entity("TEXT", EntityType::Text(t)));
}

/// Writes the plate's DXF into `dir` as [`Plate::file_name`].
///
/// # Errors
///
/// [`FabError::Dxf`] when the file cannot be written.
pub fn write_plate(
    dir: &Path,
    plate: &Plate,
    grade: &str,
    rolled: &Rolled,
    course: &Course,
) -> Result<std::path::PathBuf, FabError> {
    let path = dir.join(plate.file_name());
    plate_drawing(plate, grade, rolled, course)
        .save_file(&path)
        .map_err(|e| FabError::Dxf {
            path: path.clone(),
            message: e.to_string(),
        })?;
    Ok(path)
}
