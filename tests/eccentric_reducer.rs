//! An eccentric reducer moves the axis: the courses, heads, nozzles and supports
//! beyond it stand on the axis of its far end, offset (D − d)/2 towards its flat
//! side, and the figures that depend on where they stand (frames, dimensions,
//! volumes) follow. The envelope's closure is checked in `mesh_watertight.rs`.

mod common;

use common::eccentric::eccentric_vessel;
use glam::DVec3;
use vesselcad::design::{Design, resolve};
use vesselcad::mesh::TessellationOptions;
use vesselcad::model::{Edit, Model};

/// The test vessel, tagged `X`, without a nozzle on the reducer.
fn design(kind: &str, below: f64, above: f64, flat_side: f64) -> Design {
    eccentric_vessel("X", kind, below, above, flat_side, false)
}

fn close(a: DVec3, b: DVec3) -> bool {
    (a - b).length() < 1e-9
}

/// The parts above a reducer with its flat side east (90° on a vertical vessel
/// turned 0°) stand 300 mm east: (2000 − 1400) / 2. Turned over (small end
/// below), they stand 300 mm west. The datum stays on the bottom course's axis.
#[test]
fn parts_beyond_an_eccentric_reducer_stand_on_the_offset_axis() {
    for (below, above, east) in [(2000.0, 1400.0, 300.0), (1400.0, 2000.0, -300.0)] {
        let vessel = &resolve(&design("vertical", below, above, 90.0)).unwrap()[0];
        let part = |id: &str| vessel.parts.iter().find(|p| p.id == id).unwrap();
        let shift = DVec3::new(east, 0.0, 0.0);
        assert!(close(part("S1").frame.translation, DVec3::ZERO));
        assert!(close(
            part("S2").frame.translation,
            shift + DVec3::Z * 2800.0
        ));
        assert!(close(
            part("H2").frame.translation,
            shift + DVec3::Z * 4800.0
        ));
        // The shell nozzle is radial from S2's own axis.
        let n1 = &vessel.nozzles[0];
        assert!(close(n1.frame.translation, shift + DVec3::Z * 3800.0));
        // The head nozzle stands 200 mm from H2's centreline.
        let n3 = &vessel.nozzles[1];
        let from_axis = n3.frame.translation - (shift + DVec3::Z * 4800.0);
        assert!((from_axis.truncate().length() - 200.0).abs() < 1e-9);
    }
}

/// Every point of the reducer's far end lies on the next course's end circle,
/// and the course's far end on the head's open end (the crescent of the repro
/// closed at the source: the surfaces meet exactly).
#[test]
fn the_reducer_meets_the_course_beyond_it_exactly() {
    for (kind, below, above, flat_side) in [
        ("vertical", 2000.0, 1400.0, 90.0),
        ("vertical", 1400.0, 2000.0, 217.5),
        ("horizontal", 2000.0, 1400.0, 180.0),
    ] {
        let vessel = &resolve(&design(kind, below, above, flat_side)).unwrap()[0];
        let part = |id: &str| vessel.parts.iter().find(|p| p.id == id).unwrap();
        let end_points = |id: &str, top: bool| -> Vec<DVec3> {
            let p = part(id);
            let patches = p.geometry.patches().unwrap();
            let surface = &patches[0].surface;
            let ((u0, u1), (v0, v1)) = surface.domain();
            (0..64)
                .map(|k| {
                    let u = u0 + (u1 - u0) * f64::from(k) / 64.0;
                    p.frame
                        .transform_point3(surface.point(u, if top { v1 } else { v0 }))
                })
                .collect()
        };
        let s2 = part("S2");
        let centre = s2.frame.translation;
        // The reducer's end towards S2: its v1 when its large end is below.
        for q in end_points("R1", below > above) {
            assert!((q.z - centre.z).abs() < 1e-9, "{kind} {q}");
            let r = (q - centre).truncate().length();
            assert!((r - above / 2.0).abs() < 1e-9, "{kind}: {r}");
        }
    }
}

/// An edit to the reducer's flat side moves everything above it in the
/// incremental model exactly as a full build places it.
#[test]
fn turning_the_flat_side_equals_a_full_build() {
    let start = design("vertical", 2000.0, 1400.0, 90.0);
    let mut model = Model::from_design(&start, TessellationOptions::chord(2.0)).unwrap();
    let turned = design("vertical", 2000.0, 1400.0, 300.0);
    model.edit(Edit::ReplaceDesign(turned.clone())).unwrap();
    let full = Model::from_design(&turned, TessellationOptions::chord(2.0)).unwrap();
    let glb = |m: &Model| vesselcad::export::write_glb(&m.scene()).unwrap();
    assert!(glb(&model) == glb(&full));
}

/// The interior volume and its report are the same whichever way the flat side
/// faces (Cavalieri: the sections are the same circles, moved).
#[test]
fn volumes_do_not_depend_on_the_flat_side() {
    let volume = |flat_side: f64| {
        let d = design("vertical", 2000.0, 1400.0, flat_side);
        vesselcad::report::report(&d).unwrap()[0].volume
    };
    let (a, b) = (volume(0.0), volume(135.0));
    assert!((a - b).abs() <= 1e-9 * a, "{a} vs {b}");
}
