//! Pad and neck-template DXFs (`fab::template_dxf`): read back at 1:1, and
//! wrapped back onto their cylinders every vertex lies on the exact
//! intersection — a pad's outline on the cylinder of the pad's diameter about
//! the nozzle axis, a neck template's saddle on the shell's inside (set-in)
//! — to 1e-6 mm, on every example's nozzles on shell courses.

mod common;

use std::f64::consts::TAU;

use common::examples::{EXAMPLES, example};
use glam::{DVec2, DVec3};
use vesselcad::fab::openings::NozzleCut;
use vesselcad::fab::template_dxf::{neck_mid_radius, neck_outline, write_templates};
use vesselcad::fab::{Attachment, Shop, plan};
use vesselcad::parts::tables::pipe;

/// The CUT polylines of a DXF file.
fn cut_loops(path: &std::path::Path) -> Vec<Vec<DVec2>> {
    let back = dxf::Drawing::load_file(path).unwrap();
    assert_eq!(
        back.header.default_drawing_units,
        dxf::enums::Units::Millimeters
    );
    back.entities()
        .filter_map(|e| match &e.specific {
            dxf::entities::EntityType::LwPolyline(l) if e.common.layer == "CUT" => {
                Some(l.vertices.iter().map(|v| DVec2::new(v.x, v.y)).collect())
            }
            _ => None,
        })
        .collect()
}

/// Distance of `p` from the axis of `cut`'s neck.
fn from_neck_axis(cut: &NozzleCut, p: DVec3) -> f64 {
    let d = p - cut.neck.origin;
    (d - cut.neck.axis * d.dot(cut.neck.axis)).length()
}

#[test]
fn pad_and_neck_templates_wrap_back_onto_the_exact_intersection() {
    let dir = std::path::Path::new(env!("CARGO_TARGET_TMPDIR")).join("fab_templates");
    std::fs::create_dir_all(&dir).unwrap();
    let shop = Shop::default();
    assert_eq!(shop.attachment, Attachment::SetIn);
    let (mut pads, mut necks) = (0, 0);
    for name in EXAMPLES {
        let design = example(name);
        for v in &design.vessels {
            let p = plan(&design, &v.tag, &shop).unwrap();
            for cut in &p.openings.cuts {
                let course = &p.developments.rolled[cut.rolled];
                let r_out = course.outside.0;
                let written = write_templates(&dir, &p.tag, cut, &p.grade, r_out).unwrap();
                assert_eq!(written.len(), 1 + usize::from(cut.pad.is_some()));
                let neck_file = written.last().unwrap();
                assert_eq!(
                    neck_file.file_name().unwrap().to_str().unwrap(),
                    format!("{}-{}-NECK.dxf", p.tag, cut.mark)
                );
                // The pad: outline and hole read back; the outline wrapped
                // back onto the pad's mid-surface lies on the cylinder of the
                // pad's diameter about the nozzle axis.
                if let Some(pad) = &cut.pad {
                    let loops = cut_loops(&written[0]);
                    assert_eq!(loops.len(), 2);
                    assert_eq!(loops[0].len(), pad.outline.len());
                    let r_pad = r_out + 0.5 * pad.thickness;
                    let (c, _) = cut.neck.crossing(0.0, r_pad, 0.0).unwrap();
                    let tc = c.y.atan2(c.x);
                    for (q, want) in loops[0].iter().zip(&pad.outline) {
                        assert!((*q - *want).length() < 1e-9);
                        let theta = tc + q.x / r_pad;
                        let back = DVec3::new(r_pad * theta.cos(), r_pad * theta.sin(), c.z + q.y);
                        let off = (from_neck_axis(cut, back) - 0.5 * pad.od).abs();
                        assert!(off < 1e-6, "{name} {}: pad off by {off} mm", cut.mark);
                    }
                    pads += 1;
                }
                // The neck: its saddle wrapped back onto the neck's
                // mid-surface lies on the shell's inside.
                let nozzle = &p.resolved.nozzles[cut.nozzle];
                let g = &nozzle.geometry;
                let dims = pipe(g.nps);
                let wall = dims.wall(g.schedule).unwrap();
                let mid = 0.5 * (dims.outside_diameter - wall);
                assert!((neck_mid_radius(cut) - mid).abs() < 1e-9 * mid);
                let back_end = g.projection - g.flange_length().unwrap_or(0.0);
                let loops = cut_loops(neck_file);
                assert_eq!(loops.len(), 1);
                let want = neck_outline(cut);
                assert_eq!(loops[0].len(), want.len());
                for (a, b) in loops[0].iter().zip(&want) {
                    assert!((*a - *b).length() < 1e-9, "{a} vs {b}");
                }
                let saddle = &loops[0][..cut.saddle.len()];
                assert!((saddle.last().unwrap().x - TAU * mid).abs() < 1e-9);
                for q in saddle {
                    let phi = q.x / mid;
                    let n = &cut.neck;
                    let point = n.origin
                        + mid * (phi.cos() * n.e1 + phi.sin() * n.e2)
                        + (back_end - q.y) * n.axis;
                    let off = (point.truncate().length() - (r_out - course.thickness)).abs();
                    assert!(off < 1e-6, "{name} {}: saddle off by {off} mm", cut.mark);
                    assert!(q.y > 0.0);
                }
                necks += 1;
            }
        }
    }
    assert!(pads >= 3 && necks >= 10, "{pads} pads, {necks} necks");
}
