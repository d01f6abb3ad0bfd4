//! Each vessel's pressure envelope — heads, courses, reducers, the boot and the
//! nozzles with their openings — meshes into a closed, consistently oriented
//! 2-manifold, apart from the intended open ends (the bores of open nozzles): every
//! other edge is shared by exactly two triangles, once in each direction, and the
//! enclosed volume is positive (normals outward). Checked on every example design,
//! on randomized nozzle layouts and on randomized boots.

mod common;

use common::eccentric::eccentric_vessel;
use common::examples::example;
use std::collections::HashMap;

use glam::{DAffine3, DVec3};
use proptest::prelude::*;
use vesselcad::design::{Design, HeadShape, NozzleDesign, PadDesign, PartDesign, load};
use vesselcad::export::{Scene, SceneNodeKind};
use vesselcad::mesh::TessellationOptions;
use vesselcad::model::Model;

/// Welds positions on a fine grid (1e-6 mm cells, neighbours checked) into ids.
struct Welder {
    cells: HashMap<[i64; 3], Vec<(DVec3, usize)>>,
    count: usize,
}

const WELD: f64 = 1e-6;

impl Welder {
    fn id(&mut self, p: DVec3) -> usize {
        let key = (p / WELD).round().as_i64vec3().to_array();
        for dx in -1..=1 {
            for dy in -1..=1 {
                for dz in -1..=1 {
                    if let Some(list) = self.cells.get(&[key[0] + dx, key[1] + dy, key[2] + dz]) {
                        for &(q, id) in list {
                            if (q - p).length() <= WELD {
                                return id;
                            }
                        }
                    }
                }
            }
        }
        let id = self.count;
        self.count += 1;
        self.cells.entry(key).or_default().push((p, id));
        id
    }
}

/// Is the point on the bore rim of an open nozzle (the intended open end)?
fn on_a_bore(p: DVec3, bores: &[(DAffine3, f64, f64)]) -> bool {
    bores.iter().any(|(frame, projection, radius)| {
        let q = frame.inverse().transform_point3(p);
        (q.z - projection).abs() < 1e-6
            && (q.truncate().length() - radius).abs() < 1e-6 * radius.max(1.0)
    })
}

/// Checks one vessel of the scene; `bores` are (nozzle frame in vessel, face z, bore radius).
fn check_vessel(scene: &Scene, tag: &str, bores: &[(DAffine3, f64, f64)]) {
    let vessel = scene.vessels.iter().find(|v| v.tag == tag).unwrap();
    let envelope = ["shell", "head", "reducer", "boot"];
    let mut welder = Welder {
        cells: HashMap::new(),
        count: 0,
    };
    let mut edges: HashMap<(usize, usize), i32> = HashMap::new();
    let mut positions: Vec<DVec3> = Vec::new();
    let mut volume = 0.0;
    for node in &vessel.nodes {
        let kind = node.extras["kind"].as_str().unwrap_or("");
        if node.kind == SceneNodeKind::Part && !envelope.contains(&kind) {
            continue;
        }
        for patch in &node.patches {
            let ids: Vec<usize> = patch
                .mesh
                .positions()
                .map(|p| {
                    let q = node.frame.transform_point3(p);
                    let id = welder.id(q);
                    if id == positions.len() {
                        positions.push(q);
                    }
                    id
                })
                .collect();
            for t in patch.mesh.triangles() {
                let [a, b, c] = [ids[t[0] as usize], ids[t[1] as usize], ids[t[2] as usize]];
                assert!(
                    a != b && b != c && a != c,
                    "{tag}/{}/{}: degenerate triangle after welding",
                    node.id,
                    patch.name
                );
                let (pa, pb, pc) = (positions[a], positions[b], positions[c]);
                volume += pa.dot(pb.cross(pc)) / 6.0;
                for (x, y) in [(a, b), (b, c), (c, a)] {
                    *edges.entry((x.min(y), x.max(y))).or_insert(0) +=
                        if x < y { 1 } else { -1 } * 1000 + 1;
                }
            }
        }
    }
    let mut open = 0;
    for (&(a, b), &code) in &edges {
        let uses = code.rem_euclid(1000);
        let balance = (code - uses) / 1000;
        match uses {
            2 => assert_eq!(
                balance, 0,
                "{tag}: edge {:?}–{:?} is used twice in one direction (inconsistent orientation)",
                positions[a], positions[b]
            ),
            1 => {
                assert!(
                    on_a_bore(positions[a], bores) && on_a_bore(positions[b], bores),
                    "{tag}: open edge {:?}–{:?} is not on a nozzle bore",
                    positions[a],
                    positions[b]
                );
                open += 1;
            }
            n => panic!(
                "{tag}: edge {:?}–{:?} is shared by {n} triangles",
                positions[a], positions[b]
            ),
        }
    }
    assert!(
        volume > 0.0,
        "{tag}: normals point inward (volume {volume})"
    );
    let _ = open;
}

/// The bores of a vessel's open nozzles from the resolved design.
fn bores(design: &Design, tag: &str) -> Vec<(DAffine3, f64, f64)> {
    let resolved = vesselcad::design::resolve(design).unwrap();
    let (i, _) = design
        .vessels
        .iter()
        .enumerate()
        .find(|(_, v)| v.tag == tag)
        .unwrap();
    resolved[i]
        .nozzles
        .iter()
        .zip(&design.vessels[i].nozzles)
        .filter(|(_, d)| d.flange != vesselcad::design::FlangeDesign::Blind)
        .map(|(n, _)| {
            let pipe = vesselcad::parts::tables::pipe(n.geometry.nps);
            let wall = pipe.wall(n.geometry.schedule).unwrap();
            (
                n.frame,
                n.geometry.projection,
                pipe.outside_diameter / 2.0 - wall,
            )
        })
        .collect()
}

/// Builds the design's model and checks every vessel; returns the model.
fn check_design(design: &Design, tolerance: f64) -> Model {
    check_design_with(design, TessellationOptions::chord(tolerance))
}

/// [`check_design`] with any tessellation options.
fn check_design_with(design: &Design, options: TessellationOptions) -> Model {
    let model = Model::from_design(design, options).unwrap();
    assert!(model.errors().0.is_empty(), "{:?}", model.errors());
    let scene = model.scene();
    for v in &design.vessels {
        check_vessel(&scene, &v.tag, &bores(design, &v.tag));
    }
    model
}

#[test]
fn every_example_is_watertight() {
    for name in [
        "horizontal-drum",
        "vertical-column",
        "storage-tank",
        "small-plant",
    ] {
        check_design(&example(name), 1.0);
    }
}

/// A manway round the pole of the drum's head whose intersection loop starts a
/// hair past the host's seam angle (projections 900 and 1100 of M1 did, at the
/// default tolerance) is cut like any other, and the envelope stays closed.
#[test]
fn a_pole_opening_whose_loop_starts_on_the_seam_is_cut() {
    for projection in [900.0, 1000.0, 1100.0] {
        let mut design = example("horizontal-drum");
        let manway = design.vessels[0]
            .nozzles
            .iter_mut()
            .find(|n| n.mark == "M1")
            .unwrap();
        manway.projection = projection;
        check_design_with(&design, TessellationOptions::DEFAULT);
    }
}

/// A stretch limit samples the seams of closed patches more finely (inside the
/// patch only): the envelopes stay closed.
#[test]
fn examples_with_a_stretch_limit_are_watertight() {
    for name in ["horizontal-drum", "vertical-column"] {
        check_design_with(
            &example(name),
            TessellationOptions::chord(1.0).with_max_stretch(Some(3.0)),
        );
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 12, failure_persistence: None, ..ProptestConfig::default() })]

    /// Random nozzle layouts on the drum's shell: sizes, orientations, positions.
    #[test]
    fn random_nozzle_layouts_are_watertight(
        nozzles in proptest::collection::vec((prop_oneof![Just(2.0), Just(3.0), Just(4.0), Just(6.0), Just(8.0), Just(12.0)], 0.0..360.0f64), 1..5)
    ) {
        let mut design = example("horizontal-drum");
        let v = &mut design.vessels[0];
        v.parts.retain(|p| !matches!(p, PartDesign::Boot(_)));
        v.notes.clear();
        let template: NozzleDesign = v.nozzles[0].clone();
        v.nozzles.clear();
        for (k, (size, orientation)) in nozzles.into_iter().enumerate() {
            let mut n = template.clone();
            n.mark = format!("N{k}");
            n.size = size;
            // Every other nozzle gets a reinforcing pad.
            n.pad = (k % 2 == 0).then_some(PadDesign { od: size * 25.4 * 2.0 + 50.0, thickness: 12.0 });
            n.orientation = orientation;
            // One axial slot per nozzle so openings never overlap.
            n.elevation = Some(700.0 + 1300.0 * k as f64);
            v.nozzles.push(n);
        }
        if vesselcad::design::validate(&design).is_ok() {
            check_design(&design, 1.0);
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 8, failure_persistence: None, ..ProptestConfig::default() })]

    /// Random boots under the drum: position, diameter (up to 0.8 of the shell's),
    /// length and head shape. The boot's shell is cut at its intersection with the
    /// drum's shell, which gets the matching hole.
    #[test]
    fn random_boots_are_watertight(
        at in 0.0..1.0f64,
        fraction in 0.1..0.8f64,
        length in 200.0..1500.0f64,
        head in prop_oneof![
            Just(HeadShape::Ellipsoidal),
            Just(HeadShape::Hemispherical),
            Just(HeadShape::Torispherical),
            Just(HeadShape::Flat),
        ],
    ) {
        let mut design = example("horizontal-drum");
        let v = &mut design.vessels[0];
        v.nozzles.clear();
        v.notes.clear();
        let shell_od = v.parts.iter().find_map(|p| match p {
            PartDesign::Shell(s) => Some(s.od),
            _ => None,
        }).unwrap();
        // The course's span from the datum (the left head's tangent line: the
        // course starts after the head's straight flange).
        let resolved = vesselcad::design::resolve(&design).unwrap();
        let (start, end) = resolved[0].parts.iter().find(|p| p.id == "S1").unwrap().span;
        let v = &mut design.vessels[0];
        let od = (fraction * shell_od).round();
        for p in &mut v.parts {
            if let PartDesign::Boot(b) = p {
                // Anywhere wholly under the course.
                b.position = start + od / 2.0 + 1.0 + at * (end - start - od - 2.0);
                b.od = od;
                b.length = length;
                b.head = head;
            }
        }
        vesselcad::design::validate(&design).unwrap();
        check_design(&design, 1.0);
    }
}

/// Radius of the knuckle–crown seam of a vessel's torispherical head `id`.
fn crown_seam_radius(design: &Design, id: &str) -> f64 {
    let resolved = vesselcad::design::resolve(design).unwrap();
    let part = resolved[0].parts.iter().find(|p| p.id == id).unwrap();
    let patches = part.geometry.patches().unwrap();
    let crown = patches.iter().find(|p| p.name == "crown").unwrap();
    let p = crown
        .surface
        .boundary(vesselcad::nurbs::Side::VMin)
        .control_points()[0];
    p.truncate().length()
}

/// The column with `nozzles` `(size, orientation, t)` on its torispherical top head
/// H2 in place of N3, each centred at the knuckle–crown seam radius plus `t` times
/// its neck radius, so its opening crosses the seam.
fn column_with_seam_nozzles(nozzles: &[(f64, f64, f64)]) -> Design {
    let mut design = example("vertical-column");
    let seam = crown_seam_radius(&design, "H2");
    let v = &mut design.vessels[0];
    v.notes.clear();
    let template = v.nozzles.iter().find(|n| n.mark == "N3").unwrap().clone();
    v.nozzles.retain(|n| n.host != "H2");
    for (k, &(size, orientation, t)) in nozzles.iter().enumerate() {
        let mut n = template.clone();
        n.mark = format!("X{k}");
        n.size = size;
        n.orientation = orientation;
        let r =
            vesselcad::parts::tables::pipe(vesselcad::parts::tables::Nps::try_new(size).unwrap())
                .outside_diameter
                / 2.0;
        n.offset = Some(seam + t * r);
        v.nozzles.push(n);
    }
    design
}

/// How many openings of the model's nozzles cross a seam between two host patches.
fn openings_across_seams(mut model: Model) -> usize {
    let mut query = model.query::<&vesselcad::components::Opening>();
    let world = model.world();
    query.iter(world).filter(|o| o.hosts.len() == 2).count()
}

#[test]
fn a_head_nozzle_across_the_knuckle_crown_seam_is_watertight() {
    let design = column_with_seam_nozzles(&[(4.0, 30.0, -0.5)]);
    vesselcad::design::validate(&design).unwrap();
    assert_eq!(openings_across_seams(check_design(&design, 1.0)), 1);
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 10, failure_persistence: None, ..ProptestConfig::default() })]

    /// Random nozzles across the knuckle–crown seam of the column's top head: one
    /// or two (opposite each other), of random size, orientation and position
    /// across the seam.
    #[test]
    fn random_openings_across_a_head_seam_are_watertight(
        size in prop_oneof![Just(2.0), Just(3.0), Just(4.0), Just(6.0)],
        orientation in 0.0..360.0f64,
        along in 0.0..1.0f64,
        second in proptest::option::of((prop_oneof![Just(2.0), Just(3.0), Just(4.0)], 0.0..1.0f64)),
    ) {
        // t from −0.9 to as far out as the head radius allows.
        let design = example("vertical-column");
        let (seam, radius) = (crown_seam_radius(&design, "H2"), 700.0);
        let t = |size: f64, along: f64| {
            let r = vesselcad::parts::tables::pipe(vesselcad::parts::tables::Nps::try_new(size).unwrap())
                .outside_diameter / 2.0;
            let hi = ((radius - 1.0 - r - seam) / r).min(0.9);
            -0.9 + along * (hi + 0.9)
        };
        let mut nozzles = vec![(size, orientation, t(size, along))];
        if let Some((s2, a2)) = second {
            nozzles.push((s2, (orientation + 180.0) % 360.0, t(s2, a2)));
        }
        let design = column_with_seam_nozzles(&nozzles);
        vesselcad::design::validate(&design).unwrap();
        prop_assert_eq!(openings_across_seams(check_design(&design, 1.0)), nozzles.len());
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 6, failure_persistence: None, ..ProptestConfig::default() })]

    /// Random padded nozzles across the knuckle–crown seam of the column's top
    /// head: of random size, orientation, pad OD (1.5 to 2.5 times the neck's)
    /// and position, the pad's edges at least its end gap beyond the seam on
    /// both sides (the rule's range): `check` accepts each and it builds closed.
    #[test]
    fn random_pads_across_a_head_seam_are_watertight(
        size in prop_oneof![Just(2.0), Just(3.0), Just(4.0), Just(6.0)],
        orientation in 0.0..360.0f64,
        ratio in 1.5..2.5f64,
        along in 0.0..1.0f64,
    ) {
        let design = example("vertical-column");
        let (seam, radius) = (crown_seam_radius(&design, "H2"), 700.0);
        let r = vesselcad::parts::tables::pipe(vesselcad::parts::tables::Nps::try_new(size).unwrap())
            .outside_diameter / 2.0;
        let od = (2.0 * r * ratio).round();
        let gap = (0.05 * od).max(5.0) + 1.0;
        // The pad's centre from seam − od/2 + gap to the lesser of seam + od/2
        // − gap and the head's radius less od/2 and 1 mm.
        let (lo, hi) = (seam - od / 2.0 + gap, (seam + od / 2.0 - gap).min(radius - od / 2.0 - 1.0));
        prop_assume!(hi > lo);
        let offset = lo + along * (hi - lo);
        let mut design = column_with_seam_nozzles(&[(size, orientation, (offset - seam) / r)]);
        design.vessels[0].nozzles.last_mut().unwrap().pad = Some(PadDesign { od, thickness: 10.0 });
        vesselcad::design::validate(&design).unwrap();
        prop_assert_eq!(openings_across_seams(check_design(&design, 1.0)), 1);
    }
}

/// A pad reaching across a head's knuckle–crown seam was refused by `check`
/// (issue 30 §1: it passed `check` and failed to cut before that): it now
/// builds closed, its opening notching both patches. A pad whose edge comes
/// within the end gap of the seam without crossing it by more is refused,
/// naming the nozzle's offset; without the pad the same nozzle builds.
#[test]
fn a_pad_across_a_head_seam_builds_and_one_at_the_seam_is_refused_clearly() {
    let pad = PadDesign {
        od: 120.0,
        thickness: 10.0,
    };
    let mut design = column_with_seam_nozzles(&[(3.0, 30.0, -0.5)]);
    design.vessels[0].nozzles.last_mut().unwrap().pad = Some(pad);
    vesselcad::design::validate(&design).unwrap();
    assert_eq!(openings_across_seams(check_design(&design, 1.0)), 1);

    // Centred 63 mm inside the seam: the pad's edge stops 3 mm short of it
    // (its end gap is 6 mm).
    let mut design = column_with_seam_nozzles(&[(3.0, 30.0, -63.0 / 44.45)]);
    design.vessels[0].nozzles.last_mut().unwrap().pad = Some(pad);
    let refused = vesselcad::design::validate(&design).unwrap_err();
    let violations = refused.violations();
    assert_eq!(violations.len(), 1, "{violations:?}");
    let v = &violations[0];
    assert_eq!(
        (v.path.as_str(), v.entity.as_str(), v.field.as_str()),
        ("vessels[0].nozzles[9].offset", "C-201/X0", "offset")
    );
    assert!(
        v.rule.contains("pad") && v.rule.contains("seam") && v.rule.contains("H2"),
        "{v}"
    );
    design.vessels[0].nozzles.last_mut().unwrap().pad = None;
    vesselcad::design::validate(&design).unwrap();
    let model = Model::from_design(&design, TessellationOptions::chord(1.0)).unwrap();
    assert!(model.errors().0.is_empty(), "{:?}", model.errors());
}

/// A reinforcing pad across the seam between a head's knuckle and the crown
/// (D7, torispherical), the cone (D7b, toriconical) or the plate (D7c, flat)
/// was refused ("a pad must lie on one patch"; issue 30): its loop now
/// notches both host patches and the pad lies on the two joined, whose exact
/// surface is the torus up to the seam and the sphere, cone or plane beyond
/// (`Analytic::Knuckled`). Each builds closed, with the pad's triangles on
/// both sides of the seam, every point of every triangle within the
/// tolerance of its exact surface at 1 and 0.5 mm, and the incremental model
/// equal to the full build; so does D7 with a smaller pad whose neck crosses
/// the seam too.
#[test]
fn pads_across_a_knuckle_seam_build_closed_within_the_bound() {
    use vesselcad::components::{PatchMesh, PatchSurface};
    use vesselcad::parts::Analytic;
    let repro = |name: &str| {
        let path = format!("{}/tests/repros/{name}.json", env!("CARGO_MANIFEST_DIR"));
        load(&path).unwrap_or_else(|e| panic!("{name} is refused: {e}"))
    };
    let mut neck_across = repro("D7-pad-across-knuckle-crown-seam");
    {
        let n = &mut neck_across.vessels[0].nozzles[0];
        n.offset = Some(1100.0);
        n.pad = Some(PadDesign {
            od: 180.0,
            thickness: 10.0,
        });
    }
    vesselcad::design::validate(&neck_across).unwrap();
    for (name, design) in [
        ("D7", repro("D7-pad-across-knuckle-crown-seam")),
        ("D7b", repro("D7b-pad-across-toriconical-knuckle-cone")),
        ("D7c", repro("D7c-pad-across-flat-head-knuckle-plate")),
        ("D7 neck across", neck_across),
    ] {
        closed_within_the_bound(name, &design);
        let options = TessellationOptions::chord(1.0);
        let mut model = check_design_with(&design, options);
        common::full_build::assert_matches_full_build(&model, &options);
        assert_eq!(
            openings_across_seams(check_design(&design, 1.0)),
            1,
            "{name}"
        );
        let mut query = model.query::<(&PatchSurface, &PatchMesh)>();
        let world = model.world();
        let (surface, mesh) = query
            .iter(world)
            .find(|(s, _)| s.0.name == vesselcad::mesh::PAD_PATCH)
            .expect("a pad patch");
        let Analytic::Knuckled {
            center,
            axis,
            major,
            seam,
            ..
        } = surface.0.analytic
        else {
            panic!("{name}: the pad lies on {:?}", surface.0.analytic);
        };
        // Which side of the seam each vertex lies on, in the meridian plane.
        let normal = glam::DVec2::from_angle(seam);
        let (mut knuckle, mut beyond) = (0, 0);
        for p in mesh.0.unpack().positions {
            let d = p - center;
            let h = d.dot(axis);
            let q = glam::DVec2::new((d - axis * h).length() - major, h);
            if normal.perp_dot(q) < 0.0 {
                knuckle += 1;
            } else {
                beyond += 1;
            }
        }
        assert!(
            knuckle > 10 && beyond > 10,
            "{name}: the pad has {knuckle} vertices on the knuckle, {beyond} beyond"
        );
    }
}

/// Openings on a course that cover every one of its eight standard seam-cut
/// angles (one small nozzle on each, at different elevations, gaps between them)
/// still leave the layout a cut: any angle where both end circles have a vertex
/// and no opening reaches will do. The vessel meshes without errors and stays
/// closed. The drum's boot stays: it hangs at 180° round 4000 mm, so the nozzle
/// at 180° sits at 2400 mm, clear of the boot's opening (one inside it is refused,
/// see [`a_nozzle_inside_the_boot_opening_is_refused_clearly`]); the nozzles
/// below the horns (135°, 180°, 225°) stand clear of the saddles' wear plates
/// (0.2 L and 0.8 L, 300 mm wide), which they may not reach.
#[test]
fn a_course_with_openings_on_every_standard_cut_angle_is_meshed() {
    let mut design = example("horizontal-drum");
    let v = &mut design.vessels[0];
    let template = v.nozzles.iter().find(|n| n.mark == "N6").unwrap().clone();
    v.nozzles.retain(|n| n.host != "S1" || n.mark == "N1");
    v.notes.retain(|n| n.target != "N6");
    for k in 0..8 {
        let mut n = template.clone();
        n.mark = format!("X{k}");
        n.orientation = 45.0 * k as f64;
        n.elevation = Some(1800.0 + 600.0 * ((k + 5) % 8) as f64);
        v.nozzles.push(n);
    }
    check_design(&design, 1.0);
}

/// The drum of [`a_course_with_openings_on_every_standard_cut_angle_is_meshed`]
/// with its boot (hanging at 180° round 4000 mm, OD 610) and its shell nozzles
/// on S1 other than N1 replaced by copies of N6 at `(mark, orientation, elevation)`.
fn drum_with_shell_nozzles(nozzles: &[(&str, f64, f64)]) -> Design {
    let mut design = example("horizontal-drum");
    let v = &mut design.vessels[0];
    let template = v.nozzles.iter().find(|n| n.mark == "N6").unwrap().clone();
    v.nozzles.retain(|n| n.host != "S1" || n.mark == "N1");
    v.notes.retain(|n| n.target != "N6");
    for &(mark, orientation, elevation) in nozzles {
        let mut n = template.clone();
        n.mark = mark.into();
        n.orientation = orientation;
        n.elevation = Some(elevation);
        v.nozzles.push(n);
    }
    design
}

/// A 2-inch nozzle at 180° and 4200 mm lies inside the boot's opening in S1 (the
/// boot hangs at 180° too, its opening reaching 305 mm either side of 4000 mm):
/// there is no shell there to cut it into. It used to pass every rule and mesh
/// silently with an open edge along the boot's opening (the course's region had
/// the nozzle's hole inside the boot's, and its mesh covered the boot's hole);
/// the design is now refused, naming both openings.
#[test]
fn a_nozzle_inside_the_boot_opening_is_refused_clearly() {
    let design = drum_with_shell_nozzles(&[("X4", 180.0, 4200.0)]);
    let Err(vesselcad::model::ModelError::Design(error)) =
        Model::from_design(&design, TessellationOptions::chord(1.0))
    else {
        panic!("a nozzle inside the boot's opening must be refused");
    };
    let violations = error.violations();
    assert_eq!(violations.len(), 1, "{violations:?}");
    let v = &violations[0];
    assert_eq!(
        (v.entity.as_str(), v.field.as_str()),
        ("V-101/X4", "mark"),
        "{v}"
    );
    assert!(v.rule.contains("overlaps the opening of boot B1"), "{v}");
}

/// Nozzles level with the boot but clear of its opening — 90° away on either
/// side, and at 180° just past its axial reach — are cut beside it, and the
/// envelope stays closed along the boot's opening.
#[test]
fn shell_nozzles_beside_the_boot_are_watertight() {
    let design = drum_with_shell_nozzles(&[
        ("X2", 90.0, 4200.0),
        ("X6", 270.0, 4200.0),
        ("X4", 180.0, 4400.0),
        ("X5", 180.0, 3600.0),
    ]);
    check_design(&design, 1.0);
}

/// Every course and head beyond an eccentric reducer sits on the axis its small
/// (or large) end leaves: the envelope is closed, whichever way the flat side
/// faces, whichever end is the larger, on vertical and horizontal vessels. The
/// courses above used to stay on the first axis, leaving a crescent-shaped hole
/// (176 open edges in the repro).
#[test]
fn vessels_with_an_eccentric_reducer_are_watertight() {
    for (kind, below, above, flat_side) in [
        ("vertical", 2000.0, 1400.0, 90.0),
        ("vertical", 2000.0, 1400.0, 0.0),
        ("vertical", 2000.0, 1400.0, 217.5),
        ("vertical", 1400.0, 2000.0, 300.0),
        ("horizontal", 2000.0, 1400.0, 180.0),
        ("horizontal", 1400.0, 2000.0, 45.0),
    ] {
        let design = eccentric_vessel(
            &format!("{kind}-{below}-{above}-{flat_side}"),
            kind,
            below,
            above,
            flat_side,
            true,
        );
        check_design(&design, 1.0);
    }
}

/// A generated plant holds columns with eccentric reducers (every other column):
/// every vessel of it is closed.
#[test]
fn a_generated_plant_with_eccentric_reducers_is_watertight() {
    let design = vesselcad::plant::generate_plant(12, 3).unwrap();
    let eccentric = design
        .vessels
        .iter()
        .flat_map(|v| &v.parts)
        .filter(|p| matches!(p, PartDesign::Reducer(r) if r.eccentric.is_some()))
        .count();
    assert!(eccentric > 0);
    check_design(&design, 5.0);
}

/// Hillside, near-tangential and inclined nozzles (with and without pads) on the
/// drum's shell and on a column's courses leave the envelope closed.
#[test]
fn hillside_tangential_and_inclined_shell_nozzles_are_watertight() {
    let mut design = example("horizontal-drum");
    let v = &mut design.vessels[0];
    let od = v
        .parts
        .iter()
        .find_map(|p| match p {
            PartDesign::Shell(s) => Some(s.od),
            _ => None,
        })
        .unwrap();
    let template = v.nozzles.iter().find(|n| n.mark == "N6").unwrap().clone();
    v.nozzles.retain(|n| n.host != "S1" || n.mark == "N1");
    v.notes.retain(|n| n.target != "N6");
    let neck = |size: f64| {
        vesselcad::parts::tables::pipe(vesselcad::parts::tables::Nps::try_new(size).unwrap())
            .outside_diameter
            / 2.0
    };
    // (mark, size, orientation, elevation, offset, inclination, pad OD)
    let tangential = 0.98 * od / 2.0 - neck(4.0);
    for (mark, size, orientation, elevation, offset, inclination, pad) in [
        ("X1", 6.0, 60.0, 1500.0, 400.0, 0.0, None),
        ("X2", 4.0, 300.0, 2200.0, -tangential, 0.0, None),
        ("X3", 8.0, 90.0, 3000.0, 0.0, 30.0, Some(450.0)),
        ("X4", 6.0, 270.0, 5200.0, 300.0, -45.0, None),
        ("X5", 6.0, 20.0, 5600.0, -250.0, 20.0, Some(350.0)),
    ] {
        let mut n = template.clone();
        n.mark = mark.into();
        n.size = size;
        n.orientation = orientation;
        n.elevation = Some(elevation);
        n.offset = Some(offset);
        n.inclination = Some(inclination);
        n.projection = od + 500.0;
        n.pad = pad.map(|od| PadDesign {
            od,
            thickness: 12.0,
        });
        v.nozzles.push(n);
    }
    vesselcad::design::validate(&design).unwrap();
    check_design(&design, 1.0);
}

/// The fuzz plant's storage tank (issue 30 §1): its conical roof (half-angle
/// 79°, two 4″ nozzles at offset 1500 mm) leaves a hole-loop segment nearly
/// along a cone generator, and refinement ran away (past 50 000 vertices) at 1
/// and 0.7 mm while 0.5, 1.5 and 2 mm built: the apex, fanned straight to that
/// segment, made triangles turned over on the cone that no split could mend. It
/// builds closed at both, with a bounded roof.
#[test]
fn the_fuzz_plants_conical_roof_builds_closed_at_1_and_0_7_mm() {
    let mut design = load(format!(
        "{}/tests/repros/fuzz-seed1-accepted-edit-roof-4M-vertices.json",
        env!("CARGO_MANIFEST_DIR")
    ))
    .unwrap();
    design.vessels.retain(|v| v.tag == "TK-301");
    for tolerance in [1.0, 0.7] {
        let model = check_design(&design, tolerance);
        let scene = model.scene();
        let roof = scene.vessels[0]
            .nodes
            .iter()
            .find(|n| n.id == "ROOF")
            .unwrap();
        let vertices: usize = roof
            .patches
            .iter()
            .map(|p| p.mesh.positions().count())
            .sum();
        assert!(
            vertices < 5_000,
            "the roof at {tolerance} mm has {vertices} vertices"
        );
    }
}

/// Designs that `check` once accepted but `build` could not mesh (issue 30 §1;
/// `tests/repros/`, from `shared/repros/`): each is now either refused by the
/// rules, with a violation naming path, entity, field and rule, or builds with
/// no failure into closed envelopes.
#[test]
fn every_repro_is_refused_clearly_or_builds_closed() {
    let dir = format!("{}/tests/repros", env!("CARGO_MANIFEST_DIR"));
    let mut names: Vec<_> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|x| x == "json"))
        .collect();
    names.sort();
    assert!(names.len() >= 18, "repros missing from {dir}");
    let mut broken = Vec::new();
    for path in names {
        let name = path.file_name().unwrap().to_string_lossy().to_string();
        let start = std::time::Instant::now();
        let outcome = std::panic::catch_unwind(|| repro_outcome(&path));
        let took = start.elapsed().as_secs_f64();
        match outcome {
            Ok(Ok(what)) => eprintln!("{name}: {what} ({took:.2} s)"),
            Ok(Err(problem)) => broken.push(format!("{name}: {problem} ({took:.2} s)")),
            Err(_) => broken.push(format!("{name}: not closed ({took:.2} s)")),
        }
    }
    assert!(broken.is_empty(), "\n{}", broken.join("\n"));
}

/// What one repro does: refused clearly or built closed (panics when not closed).
fn repro_outcome(path: &std::path::Path) -> Result<String, String> {
    match load(path) {
        Err(e) => {
            let violations = e.violations();
            if violations.is_empty() {
                return Err(format!("refused without a rule: {e}"));
            }
            for v in violations {
                if !(v.path.starts_with("vessels[")
                    && !v.entity.is_empty()
                    && !v.field.is_empty()
                    && !v.rule.is_empty())
                {
                    return Err(format!("unclear violation {v:?}"));
                }
            }
            Ok(format!("refused: {}", violations[0]))
        }
        Ok(design) => {
            let model =
                Model::from_design(&design, TessellationOptions::DEFAULT).map_err(|e| match e {
                    vesselcad::model::ModelError::Geometry(v) => {
                        format!("accepted but fails to build: {v:?}")
                    }
                    e => e.to_string(),
                })?;
            let scene = model.scene();
            for v in &design.vessels {
                check_vessel(&scene, &v.tag, &bores(&design, &v.tag));
            }
            Ok("builds closed".into())
        }
    }
}

/// Off-centre nozzles on a head at its default seam angle (the ellipsoidal
/// heads of D2, D2b, D2c), a ring of four with a centre nozzle on an
/// ellipsoidal top head (D5), and a centre nozzle with an opening across a
/// torispherical head's knuckle–crown seam (D4) were refused by rules ("comes
/// within … of the seam", "a head cut round its centre cannot also be cut
/// across a seam"; issue 30 §1). Each head's seam is now chosen in the widest
/// gap between its off-centre openings: every repro builds, closed, with every
/// point of every triangle within the tolerance, at 1 and 0.5 mm; and every
/// head's seam meridian (its local +X) runs clear of its off-centre openings.
#[test]
fn head_seam_layouts_build_closed_within_the_bound() {
    use vesselcad::parts::PartGeometry;
    for name in [
        "D2-ellipsoidal-head-seam-nozzle",
        "D2b-ellipsoidal-head-ring-of-4",
        "D2c-horizontal-drum-head-nozzle-270",
        "D4-seam-crossing-plus-centre-nozzle",
        "D5-ring-of-4-plus-centre",
    ] {
        let path = format!("{}/tests/repros/{name}.json", env!("CARGO_MANIFEST_DIR"));
        let design = load(&path).unwrap_or_else(|e| panic!("{name} is refused: {e}"));
        // The seam of every head is clear of its off-centre openings.
        for vessel in vesselcad::design::resolve(&design).unwrap() {
            for n in &vessel.nozzles {
                let host = &vessel.parts[n.host];
                if !matches!(host.geometry, PartGeometry::Head(_)) {
                    continue;
                }
                let p = host.frame.inverse().transform_point3(n.frame.translation);
                let (d, r) = (p.x.hypot(p.y), n.geometry.outside_diameter() / 2.0);
                if d > r {
                    let away = p.y.atan2(p.x).abs();
                    assert!(
                        away > (r / d).asin(),
                        "{name}: nozzle {} is {:.2}° from the seam of {}",
                        n.mark,
                        away.to_degrees(),
                        host.id
                    );
                }
            }
        }
        closed_within_the_bound(name, &design);
    }
}

/// Builds `design` at 1 and 0.5 mm, closed (`check_design`), and asserts every
/// point of every triangle lies within the tolerance of its exact surface.
fn closed_within_the_bound(name: &str, design: &Design) {
    use common::triangle::largest_distance;
    use vesselcad::components::{PatchMesh, PatchSurface};
    for tolerance in [1.0, 0.5] {
        let start = std::time::Instant::now();
        let mut model = check_design(design, tolerance);
        let took = start.elapsed().as_secs_f64();
        let mut query = model.query::<(&PatchSurface, &PatchMesh)>();
        let world = model.world();
        let (mut triangles, mut worst) = (0usize, 0.0f64);
        for (surface, mesh) in query.iter(world) {
            let m = mesh.0.unpack();
            for t in m.indices.chunks_exact(3) {
                let p = [t[0], t[1], t[2]].map(|i| m.positions[i as usize]);
                let d = largest_distance(&surface.0.analytic, p) / tolerance;
                assert!(
                    d <= 1.0 + 1e-9,
                    "{name} at {tolerance} mm: a triangle of {} is {d:.5}× off",
                    surface.0.name
                );
                worst = worst.max(d);
                triangles += 1;
            }
        }
        eprintln!(
            "{name} at {tolerance} mm: {triangles} triangles, worst {worst:.4}×, built in \
             {took:.2} s"
        );
    }
}

/// A ring of eight nozzles on an ellipsoidal head, one on each of its eight
/// seam steps (D8), was refused ("cover each of the head's 8 seam angles";
/// issue 30). The head now keeps its seam (no step is clear) and the layout
/// cuts its crown at a vertex of its rim between two openings: it builds
/// closed with its course, every point of every triangle within the
/// tolerance, at 1 and 0.5 mm.
#[test]
fn a_ring_of_eight_on_every_seam_step_builds_closed_within_the_bound() {
    let name = "D8-ring-of-8-on-every-seam-angle";
    let path = format!("{}/tests/repros/{name}.json", env!("CARGO_MANIFEST_DIR"));
    let design = load(&path).unwrap_or_else(|e| panic!("{name} is refused: {e}"));
    let head = &design.vessels[0].nozzles;
    assert_eq!(head.len(), 8);
    for (k, n) in head.iter().enumerate() {
        assert_eq!((n.host.as_str(), n.orientation), ("H2", 45.0 * k as f64));
    }
    closed_within_the_bound(name, &design);
}
