//! One DXF per head blank (`V-101-H1-BLANK.dxf`, a boot's head
//! `V-101-B1-HEAD-BLANK.dxf`), 1:1 in millimetres with the plates' layers:
//! `CUT` the blank's circle (two exact half-circle bulges), `MARK` the
//! centre cross (the pole; +x along the head's local +X, labelled `0`) and
//! each opening of the head mapped by the forming rule of
//! [`super::head_map`] — its outline, its pad's, and its centre mark,
//! labelled "cut after forming" — and `TEXT` the blank id, grade, thickness
//! and rule.

use std::path::{Path, PathBuf};

use dxf::Drawing;
use glam::DVec2;

use super::develop::{BLANK_RULE, HeadBlank};
use super::error::FabError;
use super::openings::{FormedOpening, polygon_area};
use super::plate_dxf::{closed, entity, line, new_drawing, text, vertex};

/// The blank's id, `V-101-H1-BLANK`.
pub fn blank_id(tag: &str, blank: &HeadBlank) -> String {
    format!("{tag}-{}-BLANK", blank.id)
}

/// The blank's drawing with the openings `formed` on its head.
pub fn blank_drawing(
    tag: &str,
    blank: &HeadBlank,
    grade: &str,
    formed: &[&FormedOpening],
) -> Drawing {
    let mut d = new_drawing();
    let r = 0.5 * blank.diameter;
    // A circle as two half-circle arcs: bulge 1 = 180° counter-clockwise.
    let circle = vec![
        vertex(DVec2::new(r, 0.0), 1.0),
        vertex(DVec2::new(-r, 0.0), 1.0),
    ];
    d.add_entity(entity("CUT", closed(circle)));
    let size = (0.02 * blank.diameter).clamp(8.0, 40.0);
    let reach = 0.1 * r;
    d.add_entity(entity(
        "MARK",
        line(DVec2::new(-reach, 0.0), DVec2::new(reach, 0.0)),
    ));
    d.add_entity(entity(
        "MARK",
        line(DVec2::new(0.0, -reach), DVec2::new(0.0, reach)),
    ));
    d.add_entity(entity(
        "MARK",
        line(DVec2::new(r - 3.0 * size, 0.0), DVec2::new(r, 0.0)),
    ));
    text(&mut d, DVec2::new(r - 3.0 * size, 0.3 * size), size, "0");
    for f in formed {
        let Some(mark) = &f.blank else { continue };
        let contours = std::iter::once(&mark.outline).chain(mark.pad.as_ref());
        for contour in contours {
            let points = contour.iter().map(|&p| vertex(p, 0.0)).collect();
            d.add_entity(entity("MARK", closed(points)));
        }
        let c = mark.centre;
        let arm = (polygon_area(&mark.outline).abs() / std::f64::consts::PI).sqrt() + 25.0;
        d.add_entity(entity("MARK", line(c - DVec2::X * arm, c + DVec2::X * arm)));
        d.add_entity(entity("MARK", line(c - DVec2::Y * arm, c + DVec2::Y * arm)));
        text(
            &mut d,
            c + DVec2::new(0.3 * arm, 0.3 * arm),
            size,
            &format!("{}: cut after forming", f.mark),
        );
    }
    text(
        &mut d,
        DVec2::new(-r, -r - 2.0 * size),
        size,
        &blank_id(tag, blank),
    );
    text(
        &mut d,
        DVec2::new(-r, -r - 3.5 * size),
        size,
        &format!(
            "{grade}  t = {} mm  blank Ø{:.1}  openings marked, cut after forming  ({BLANK_RULE})",
            blank.thickness, blank.diameter
        ),
    );
    d
}

/// Writes the blank's DXF into `dir`; returns its path.
///
/// # Errors
///
/// [`FabError::Dxf`] when the file cannot be written.
pub fn write_blank(
    dir: &Path,
    tag: &str,
    blank: &HeadBlank,
    grade: &str,
    formed: &[&FormedOpening],
) -> Result<PathBuf, FabError> {
    let path = dir.join(format!("{}.dxf", blank_id(tag, blank)));
    blank_drawing(tag, blank, grade, formed)
        .save_file(&path)
        .map_err(|e| FabError::Dxf {
            path: path.clone(),
            message: e.to_string(),
        })?;
    Ok(path)
}
