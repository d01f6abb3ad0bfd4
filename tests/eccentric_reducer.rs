//! An eccentric reducer moves the axis: the courses, heads, nozzles and supports
//! beyond it stand on the axis of its far end, offset (D − d)/2 towards its flat
//! side, and the figures that depend on where they stand (frames, dimensions,
//! volumes) follow. The envelope's closure is checked in `mesh_watertight.rs`.

mod common;

use common::eccentric::eccentric_vessel;
use common::triangle::largest_distance;
use glam::DVec3;
use vesselcad::design::{Design, resolve};
use vesselcad::mesh::cdt::mesh_patch_region;
use vesselcad::mesh::{TessellationOptions, patch_region};
use vesselcad::model::{Edit, Model};
use vesselcad::parts::{Reducer, ReducerAlignment};

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

/// The mesh of an eccentric reducer's cone alone at `tolerance`: every point of
/// every triangle within the tolerance of the exact oblique cone (45 barycentric
/// samples and a climb per triangle), and closed but for its two end rings
/// (every other edge shared by exactly two triangles). Returns the triangle count.
fn cone_meshes_within(reducer: &Reducer, tolerance: f64) -> Result<usize, String> {
    let patch = &reducer.patches().map_err(|e| e.to_string())?[0];
    let options = TessellationOptions::chord(tolerance);
    let region = patch_region(&patch.surface, &options, &[], None).map_err(|e| e.to_string())?;
    let out = mesh_patch_region(patch, &region, &options)
        .map_err(|e| format!("{reducer:?} at {tolerance} mm: {e}"))?;
    let (positions, indices) = (&out.mesh.positions, &out.mesh.indices);
    let mut edges: std::collections::HashMap<(u32, u32), usize> = Default::default();
    for t in indices.chunks_exact(3) {
        let p = [t[0], t[1], t[2]].map(|i| positions[i as usize]);
        let d = largest_distance(&patch.analytic, p);
        if d > tolerance * (1.0 + 1e-9) {
            return Err(format!(
                "{reducer:?} at {tolerance} mm: a triangle deviates {d} mm"
            ));
        }
        for i in 0..3 {
            let (a, b) = (t[i], t[(i + 1) % 3]);
            *edges.entry((a.min(b), a.max(b))).or_default() += 1;
        }
    }
    let length = reducer.length;
    for ((a, b), n) in edges {
        let (pa, pb) = (positions[a as usize], positions[b as usize]);
        let on_end = |z: f64| (pa.z - z).abs() < 1e-9 * length && (pb.z - z).abs() < 1e-9 * length;
        let open = n == 1 && (on_end(0.0) || on_end(length));
        if !(n == 2 || open) {
            return Err(format!(
                "{reducer:?} at {tolerance} mm: edge {pa} – {pb} has {n} triangles"
            ));
        }
    }
    Ok(indices.len() / 3)
}

/// The plant's eccentric cone: C-00515/R1 of `vesselcad plant generate
/// --vessels 1000 --seed 1`, 3000 → 2500 over 600 mm, flat side 90°.
fn plant_cone() -> Reducer {
    Reducer {
        large_diameter: 3000.0,
        small_diameter: 2500.0,
        length: 600.0,
        alignment: ReducerAlignment::Eccentric { flat_side: 90.0 },
    }
}

/// The plant's eccentric cone failed to mesh at every tolerance from 0.492 to
/// 0.498 mm ("refinement did not converge", "triangle … is inverted or flat")
/// and at 0.3 mm (`tests/repros/plant1000-seed1-eccentric-reducer-cones-0.5mm.json`):
/// the probes measured points off its end rings to the ring (the NURBS
/// inversion clamped to the domain) rather than along the normal, and the one
/// strip between its rings crossed the generators; see `cdt::structured::ruled`.
#[test]
fn the_plants_eccentric_cone_meshes_where_it_failed() {
    let reducer = plant_cone();
    let fine = (0..=40).map(|k| 0.490 + 0.00025 * f64::from(k));
    let failures: Vec<String> = fine
        .chain([0.3, 0.5])
        .filter_map(|t| cone_meshes_within(&reducer, t).err())
        .collect();
    assert!(failures.is_empty(), "{failures:#?}");
}

/// The whole sweep, 0.2 to 2 mm in steps of 0.005 (it failed at 16
/// tolerances).
#[test]
fn the_plants_eccentric_cone_meshes_at_every_tolerance() {
    let reducer = plant_cone();
    let failures: Vec<String> = (0..=360)
        .map(|k| 0.2 + 0.005 * f64::from(k))
        .filter_map(|t| cone_meshes_within(&reducer, t).err())
        .collect();
    assert!(failures.is_empty(), "{failures:#?}");
}

proptest::proptest! {
    #![proptest_config(proptest::prelude::ProptestConfig::with_cases(48))]

    /// Random eccentric reducers (diameters 300–6000 mm, the small end 30–97 %
    /// of the large, lengths from a tenth to twice the large diameter, any flat
    /// side) mesh at any tolerance from 0.05 to 5 mm, within the bound and
    /// closed (a counterexample before: 3189 → 1007 over 319 mm at 0.064 mm, a
    /// triangle left turned over by refinement).
    #[test]
    fn random_eccentric_cones_mesh_within_the_bound(
        large in 300.0f64..6000.0,
        share in 0.3f64..0.97,
        length in 0.1f64..2.0,
        flat_side in -360.0f64..360.0,
        tolerance in 0.05f64..5.0,
    ) {
        let reducer = Reducer {
            large_diameter: large,
            small_diameter: share * large,
            length: length * large,
            alignment: ReducerAlignment::Eccentric { flat_side },
        };
        // At least a few hundred triangles and at most a few hundred thousand:
        // the tolerance as a share of the diameter.
        let tolerance = tolerance.clamp(large * 2e-5, large * 2e-3);
        let result = cone_meshes_within(&reducer, tolerance);
        proptest::prop_assert!(result.is_ok(), "{}", result.unwrap_err());
    }
}

proptest::proptest! {
    /// The oblique cone's distance is exact near the surface (where the chordal
    /// checks measure): a point `h` along the normal from a point of an
    /// eccentric reducer is at distance |h| (the former section-plane measure
    /// overstated it by up to 1 / cos of the generatrix's slope, 30 % on the
    /// plant's cone).
    #[test]
    fn the_oblique_cones_distance_is_exact_near_it(
        u in 0.0f64..1.0,
        v in 0.0f64..1.0,
        h in -5.0f64..5.0,
        flat_side in 0.0f64..360.0,
        share in 0.3f64..0.95,
    ) {
        use vesselcad::parts::Analytic;
        let reducer = Reducer {
            large_diameter: 3000.0,
            small_diameter: share * 3000.0,
            length: 600.0,
            alignment: ReducerAlignment::Eccentric { flat_side },
        };
        let patch = &reducer.patches().unwrap()[0];
        proptest::prop_assert!(matches!(patch.analytic, Analytic::ObliqueCone { .. }), "an oblique cone");
        let ((u0, u1), (v0, v1)) = patch.surface.domain();
        let (u, v) = (u0 + (u1 - u0) * u, v0 + (v1 - v0) * v);
        let foot = patch.surface.point(u, v);
        let normal = patch.surface.normal(u, v);
        let d = patch.analytic.distance(foot + normal * h);
        proptest::prop_assert!((d - h.abs()).abs() <= 1e-9, "{d} vs {h}");
    }
}
