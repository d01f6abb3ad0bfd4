//! Cutting files of a nozzle's pieces besides the plates, 1:1 in
//! millimetres with the plates' layers (`CUT`, `MARK`, `TEXT`):
//!
//! - **Pad** (`V-101-N1-PAD.dxf`): the pad's outline and the neck's hole as
//!   developed on the pad's mid-surface ([`super::openings`]: `x` along the
//!   shell's circumference, `y` along its axis, the nozzle axis at the
//!   origin), the nozzle centrelines marked; rolled to the radius printed.
//!   A pad on a cone (concentric or an eccentric reducer's oblique one,
//!   [`super::cone_openings`]) is developed on its own conical mid-surface,
//!   `y` along the generator through the nozzle axis: it is rolled as a
//!   cone about its apex, whose developed point is printed and marked
//!   (`MARK`, the generator from the axis towards it).
//! - **Neck template** (`V-101-N1-NECK.dxf`): the saddle cut of the neck as
//!   a wrap-around template developed on the neck's mid-surface: `x = r·φ`
//!   about the neck, `y` the length from the cut to the flange's back (the
//!   template's straight edge). Marks every 90° from the side facing the
//!   course's +Z (`0°`), so the template is wrapped the right way round.
//!
//! Every vertex is a point of the exact intersection curve (to rounding), so
//! wrapping a template back onto its cylinder gives that curve.

use std::f64::consts::{FRAC_PI_2, TAU};
use std::path::{Path, PathBuf};

use dxf::Drawing;
use glam::DVec2;

use super::error::FabError;
use super::openings::NozzleCut;
use super::plate_dxf::{closed, entity, line, new_drawing, text, vertex};

/// The pad's file name, `V-101-N1-PAD.dxf`.
pub fn pad_file_name(tag: &str, cut: &NozzleCut) -> String {
    format!("{tag}-{}-PAD.dxf", cut.mark)
}

/// The neck template's file name, `V-101-N1-NECK.dxf`.
pub fn neck_file_name(tag: &str, cut: &NozzleCut) -> String {
    format!("{tag}-{}-NECK.dxf", cut.mark)
}

/// The pad's drawing, or `None` when the nozzle has no pad. `grade` is the
/// material, `shell_outside` the outside radius of the course it sits on
/// (unused for a pad on a cone, rolled about its apex).
pub fn pad_drawing(tag: &str, cut: &NozzleCut, grade: &str, shell_outside: f64) -> Option<Drawing> {
    let pad = cut.pad.as_ref()?;
    let mut d = new_drawing();
    for contour in [&pad.outline, &pad.hole] {
        let points = contour.iter().map(|&p| vertex(p, 0.0)).collect();
        d.add_entity(entity("CUT", closed(points)));
    }
    let reach = 0.5 * pad.od + 25.0;
    d.add_entity(entity(
        "MARK",
        line(DVec2::new(-reach, 0.0), DVec2::new(reach, 0.0)),
    ));
    d.add_entity(entity(
        "MARK",
        line(DVec2::new(0.0, -reach), DVec2::new(0.0, reach)),
    ));
    let size = (0.05 * pad.od).clamp(8.0, 40.0);
    let at = DVec2::new(-0.3 * pad.od, 0.5 * pad.od + 2.0 * size);
    text(&mut d, at, size, &format!("{tag}-{}-PAD", cut.mark));
    let rolling = match pad.apex {
        None => format!(
            "roll to R {:.1} (mid)  y along the shell axis",
            shell_outside + 0.5 * pad.thickness
        ),
        Some(apex) => {
            // The generator through the axis, from the pad's edge towards
            // the apex.
            let towards = apex.normalize_or_zero();
            d.add_entity(entity("MARK", line(DVec2::ZERO, towards * reach)));
            format!(
                "roll as a cone (mid) about its apex at x {:.1}, y {:.1} ({:.1} from the axis)  y along the generator",
                apex.x,
                apex.y,
                apex.length()
            )
        }
    };
    text(
        &mut d,
        at + DVec2::Y * 1.5 * size,
        size,
        &format!("{grade}  t = {} mm  {rolling}", pad.thickness),
    );
    Some(d)
}

/// The neck's wrap-around template: the saddle curve, closed by the
/// straight edge at the flange's back (`y = 0`).
pub fn neck_outline(cut: &NozzleCut) -> Vec<DVec2> {
    let mut out = cut.saddle.clone();
    if let (Some(first), Some(last)) = (cut.saddle.first(), cut.saddle.last()) {
        out.push(DVec2::new(last.x, 0.0));
        out.push(DVec2::new(first.x, 0.0));
    }
    out
}

/// The neck's angle φ (from its local +x) that faces the course's +Z.
fn top(cut: &NozzleCut) -> f64 {
    let n = &cut.neck;
    n.e2.z.atan2(n.e1.z)
}

/// The radius of the neck's mid-surface the saddle is developed on (its
/// last point is at φ = 2π).
pub fn neck_mid_radius(cut: &NozzleCut) -> f64 {
    cut.saddle.last().map_or(0.0, |p| p.x / TAU)
}

/// The neck template's drawing.
pub fn neck_drawing(tag: &str, cut: &NozzleCut) -> Drawing {
    let mid_radius = neck_mid_radius(cut);
    let mut d = new_drawing();
    let outline = neck_outline(cut);
    let points = outline.iter().map(|&p| vertex(p, 0.0)).collect();
    d.add_entity(entity("CUT", closed(points)));
    let high = cut.saddle.iter().fold(0.0f64, |m, p| m.max(p.y));
    let size = (0.04 * TAU * mid_radius).clamp(5.0, 30.0);
    for quarter in 0..4 {
        let phi = (top(cut) + f64::from(quarter) * FRAC_PI_2).rem_euclid(TAU);
        let x = mid_radius * phi;
        d.add_entity(entity(
            "MARK",
            line(DVec2::new(x, 0.0), DVec2::new(x, high)),
        ));
        text(
            &mut d,
            DVec2::new(x + 0.2 * size, 0.3 * high),
            size,
            &format!("{}°", quarter * 90),
        );
    }
    text(
        &mut d,
        DVec2::new(0.0, -2.0 * size),
        size,
        &format!("{tag}-{}-NECK", cut.mark),
    );
    text(
        &mut d,
        DVec2::new(0.0, -3.5 * size),
        size,
        &format!(
            "wrap on the neck (mid R {mid_radius:.2}); straight edge at the flange's back; 0° faces the course's +Z"
        ),
    );
    d
}

fn save(d: &Drawing, path: PathBuf) -> Result<PathBuf, FabError> {
    d.save_file(&path).map_err(|e| FabError::Dxf {
        path: path.clone(),
        message: e.to_string(),
    })?;
    Ok(path)
}

/// Writes the pad's DXF (when the nozzle has one) and the neck template's
/// into `dir`; returns the paths written.
///
/// # Errors
///
/// [`FabError::Dxf`] when a file cannot be written.
pub fn write_templates(
    dir: &Path,
    tag: &str,
    cut: &NozzleCut,
    grade: &str,
    shell_outside: f64,
) -> Result<Vec<PathBuf>, FabError> {
    let mut out = Vec::new();
    if let Some(d) = pad_drawing(tag, cut, grade, shell_outside) {
        out.push(save(&d, dir.join(pad_file_name(tag, cut)))?);
    }
    let d = neck_drawing(tag, cut);
    out.push(save(&d, dir.join(neck_file_name(tag, cut)))?);
    Ok(out)
}
