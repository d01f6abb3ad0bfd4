//! Liquid volumes at a level, operating weights and centres of gravity against
//! closed forms: the horizontal cylinder segment, the 2:1 head's partial volume,
//! the spherical cap, full-volume limits against the NURBS divergence integral of
//! the inside head for every head kind, and the model keeping them current.

mod common;

use std::f64::consts::PI;

use vesselcad::components::OperatingState;
use vesselcad::constraints::state_of_design;
use vesselcad::design::{Design, OperatingDesign, VesselDesign, load, parse, resolve, save};
use vesselcad::mesh::TessellationOptions;
use vesselcad::model::{Edit, Model};
use vesselcad::operating::OperatingFigures;
use vesselcad::operating::liquid::circular_segment;
use vesselcad::parts::enclosed_volume;
use vesselcad::parts::heads::{Head, HeadKind};

const T: f64 = 10.0;
const OD: f64 = 2000.0;
const RI: f64 = OD / 2.0 - T;
const L: f64 = 4000.0;

/// A vessel of `kind` with heads given as JSON objects (without id), OD 2000,
/// course 4000, walls 10 mm, filled to `level`.
fn vessel(kind: &str, bottom: &str, top: &str, level: f64) -> Design {
    let text = format!(
        r#"{{"format": "vesselcad/1", "vessels": [{{"tag": "V-1", "kind": "{kind}",
        "parts": [
          {{"head": {{"id": "H1", "thickness": {T}, {bottom}}}}},
          {{"shell": {{"id": "S1", "od": {OD}, "length": {L}, "thickness": {T}}}}},
          {{"head": {{"id": "H2", "thickness": {T}, {top}}}}}
        ],
        "operating": {{"liquid_level": {level}}}}}]}}"#
    );
    parse(&text).unwrap_or_else(|e| panic!("{e}\n{text}"))
}

fn state(design: &Design) -> OperatingFigures {
    let resolved = resolve(design).unwrap();
    state_of_design(&design.vessels[0], &resolved[0]).unwrap()
}

fn close(a: f64, b: f64, rel: f64) -> bool {
    (a - b).abs() <= rel * b.abs().max(1e-300)
}

const FLAT: &str = r#""shape": "flat""#;
const TWO_TO_ONE: &str = r#""shape": "ellipsoidal""#;
const HEMI: &str = r#""shape": "hemispherical""#;

/// mm³ → m³.
const M3: f64 = 1e-9;

#[test]
fn horizontal_cylinder_is_a_circular_segment_times_its_length() {
    for level in [0.0, 1.0, 250.0, RI, 1234.5, 2.0 * RI - 0.5, 2.0 * RI] {
        let s = state(&vessel("horizontal", FLAT, FLAT, level));
        let expected = circular_segment(RI, level - RI).0 * L * M3;
        assert!(
            close(s.liquid_volume, expected, 1e-10) || (expected == 0.0 && s.liquid_volume == 0.0),
            "level {level}: {} vs {expected}",
            s.liquid_volume
        );
    }
    // The segment formula itself: half and full.
    assert!(close(circular_segment(3.0, 0.0).0, PI * 4.5, 1e-15));
    assert!(close(circular_segment(3.0, 3.0).0, PI * 9.0, 1e-15));
}

#[test]
fn vertical_two_to_one_head_partial_volume() {
    let (a, b) = (RI, OD / 4.0 - T);
    for level in [0.0, 17.0, 200.0, b, b + 1000.0, 2.0 * b + L] {
        let s = state(&vessel("vertical", TWO_TO_ONE, TWO_TO_ONE, level));
        let expected = if level <= b {
            PI * a * a / (b * b) * (b * level * level - level.powi(3) / 3.0)
        } else {
            2.0 / 3.0 * PI * a * a * b
                + PI * a * a * (level - b).min(L)
                + if level > b + L {
                    let h = level - b - L;
                    PI * a * a / (b * b) * (b * b * h - h.powi(3) / 3.0)
                } else {
                    0.0
                }
        };
        assert!(
            close(s.liquid_volume, expected * M3, 1e-10) || expected == 0.0,
            "level {level}: {} vs {}",
            s.liquid_volume,
            expected * M3
        );
    }
}

#[test]
fn vertical_hemispherical_bottom_is_a_spherical_cap() {
    for level in [3.0, 100.0, 500.0, RI] {
        let s = state(&vessel("vertical", HEMI, HEMI, level));
        let expected = PI * level * level * (3.0 * RI - level) / 3.0;
        assert!(
            close(s.liquid_volume, expected * M3, 1e-10),
            "level {level}: {} vs {}",
            s.liquid_volume,
            expected * M3
        );
    }
}

#[test]
fn horizontal_dished_heads_add_a_scaled_spherical_cap() {
    // Two 2:1 heads on a horizontal drum make one ellipsoid: a sphere of radius a
    // stretched by b/a along the axis, so their liquid is (b/a) × a spherical cap.
    let (a, b) = (RI, OD / 4.0 - T);
    for (head, axial) in [(TWO_TO_ONE, b), (HEMI, RI)] {
        for level in [5.0, 300.0, RI, 1500.0, 2.0 * RI] {
            let s = state(&vessel("horizontal", head, head, level));
            let cap = PI * level * level * (3.0 * a - level) / 3.0;
            let expected = circular_segment(a, level - a).0 * L + axial / a * cap;
            assert!(
                close(s.liquid_volume, expected * M3, 1e-10),
                "{head} level {level}: {} vs {}",
                s.liquid_volume,
                expected * M3
            );
        }
    }
}

/// Every head kind as (JSON, the inside head as an exact NURBS head).
fn heads() -> Vec<(String, Head)> {
    let ri = RI;
    vec![
        (HEMI.into(), Head::new(2.0 * ri, HeadKind::Hemispherical)),
        (
            r#""shape": "ellipsoidal", "ratio": 1.7"#.into(),
            Head::new(
                2.0 * ri,
                HeadKind::Ellipsoidal {
                    ratio: ri / (OD / 2.0 / 1.7 - T),
                },
            ),
        ),
        (
            r#""shape": "torispherical""#.into(),
            Head::new(
                2.0 * ri,
                HeadKind::Torispherical {
                    crown_radius: OD - T,
                    knuckle_radius: 0.06 * OD - T,
                },
            ),
        ),
        (
            r#""shape": "toriconical", "half_angle": 35, "knuckle_radius": 200"#.into(),
            Head::new(
                2.0 * ri,
                HeadKind::Toriconical {
                    half_angle: 35.0,
                    knuckle_radius: 200.0 - T,
                },
            ),
        ),
        (
            r#""shape": "conical", "half_angle": 50"#.into(),
            Head::new(
                2.0 * ri,
                HeadKind::Conical {
                    half_angle: 50.0,
                    small_diameter: 0.0,
                },
            ),
        ),
        (
            r#""shape": "flat", "knuckle_radius": 120"#.into(),
            Head::new(
                2.0 * ri,
                HeadKind::Flat {
                    knuckle_radius: 120.0 - T,
                },
            ),
        ),
    ]
}

#[test]
fn full_volume_of_every_head_kind_matches_the_nurbs_inside_head() {
    for (json, inside) in heads() {
        let head_volume = enclosed_volume(&inside.patches().unwrap());
        let expected = (2.0 * head_volume + PI * RI * RI * L) * M3;
        for kind in ["vertical", "horizontal"] {
            let empty = state(&vessel(kind, &json, &json, 0.0));
            assert!(
                close(empty.interior_volume, expected, 1e-9),
                "{kind} {json}: interior {} vs NURBS {expected}",
                empty.interior_volume
            );
            assert_eq!(empty.liquid_volume, 0.0, "{kind} {json}: empty");
            let full = state(&vessel(kind, &json, &json, empty.interior_height));
            assert!(
                close(full.liquid_volume, expected, 1e-9),
                "{kind} {json}: full {} vs {expected}",
                full.liquid_volume
            );
        }
    }
}

#[test]
fn horizontal_volumes_are_symmetric_about_the_axis_for_every_head_kind() {
    for (json, _) in heads() {
        let full = state(&vessel("horizontal", &json, &json, 0.0)).interior_volume;
        let half = state(&vessel("horizontal", &json, &json, RI)).liquid_volume;
        assert!(
            close(half, full / 2.0, 1e-11),
            "{json}: half {half} vs {}",
            full / 2.0
        );
        for level in [1.0, 77.0, 420.0, 989.0] {
            let low = state(&vessel("horizontal", &json, &json, level)).liquid_volume;
            let high = state(&vessel("horizontal", &json, &json, 2.0 * RI - level)).liquid_volume;
            assert!(
                close(low + high, full, 1e-11),
                "{json} level {level}: {low} + {high} vs {full}"
            );
            assert!(low > 0.0 && low < half);
        }
    }
}

#[test]
fn operating_mass_and_centre_of_gravity() {
    // Flat plain heads: the walls are a tube and two plates.
    let empty = state(&vessel("horizontal", FLAT, FLAT, 0.0));
    let ro = OD / 2.0;
    let tube = PI * (ro * ro - RI * RI) * L;
    let plates = 2.0 * PI * (ro - T / 2.0).powi(2) * T;
    let metal = (tube + plates) * M3 * 7850.0;
    assert!(
        close(empty.metal_mass, metal, 1e-10),
        "{} vs {metal}",
        empty.metal_mass
    );
    assert_eq!(empty.operating_mass, empty.metal_mass);
    // Centre of gravity: mid-length on the axis, in the plant frame (datum at the
    // origin, axis along plant north for rotation 0).
    let half = state(&vessel("horizontal", FLAT, FLAT, RI));
    assert!(close(half.liquid_mass, half.liquid_volume * 1000.0, 1e-14));
    assert!(close(
        half.operating_mass,
        half.liquid_mass + half.metal_mass,
        1e-14
    ));
    let cog = half.centre_of_gravity;
    let empty_cog = empty.centre_of_gravity;
    // Liquid pulls the centre of gravity down, not along the axis.
    assert!(cog.z < empty_cog.z - 10.0, "{cog} vs {empty_cog}");
    assert!(
        (cog - empty_cog).truncate().length() < 1e-6,
        "{cog} vs {empty_cog}"
    );
    // The half-full liquid's centroid sits 4R/(3π) below the axis.
    let liquid_drop = 4.0 * RI / (3.0 * PI);
    let expected = half.liquid_mass * liquid_drop / half.operating_mass;
    assert!(
        close(empty_cog.z - cog.z, expected, 1e-9),
        "{} vs {expected}",
        empty_cog.z - cog.z
    );
}

#[test]
fn operating_data_is_optional_round_trips_and_is_checked() {
    // Old files (no operating data) still load; new fields round-trip.
    let old = common::examples::example("small-plant");
    assert!(old.vessels.iter().all(|v| v.operating.is_none()));
    let mut d = vessel("vertical", TWO_TO_ONE, TWO_TO_ONE, 1000.0);
    d.vessels[0].operating.as_mut().unwrap().liquid_density = Some(850.0);
    d.vessels[0].design.metal_density = Some(8000.0);
    let path = std::env::temp_dir().join(format!("vesselcad-op-{}.json", std::process::id()));
    save(&d, &path).unwrap();
    let back = load(&path).unwrap();
    std::fs::remove_file(&path).ok();
    assert_eq!(back, d);
    // A level above the top, a negative density: refused with their paths.
    let mut high = d.clone();
    high.vessels[0].operating.as_mut().unwrap().liquid_level = 1e6;
    let e = resolve(&high).unwrap_err().to_string();
    assert!(
        e.contains("operating.liquid_level") && e.contains("interior"),
        "{e}"
    );
    let mut dense = d.clone();
    dense.vessels[0].operating.as_mut().unwrap().liquid_density = Some(-1.0);
    let e = resolve(&dense).unwrap_err().to_string();
    assert!(e.contains("operating.liquid_density"), "{e}");
}

#[test]
fn model_recomputes_only_the_vessel_whose_level_changed() {
    let mut plant = vessel("vertical", TWO_TO_ONE, TWO_TO_ONE, 500.0);
    let mut second: VesselDesign = plant.vessels[0].clone();
    second.tag = "V-2".into();
    second.placement.position = [10_000.0, 0.0, 0.0];
    plant.vessels.push(second);
    let mut model = Model::from_design(&plant, TessellationOptions::chord(5.0)).unwrap();
    let entity = |model: &Model, tag: &str| {
        let world = model.world();
        let mut q = world
            .try_query::<(bevy_ecs::entity::Entity, &vesselcad::components::VesselSpec)>()
            .unwrap();
        q.iter(world).find(|(_, s)| s.tag == tag).unwrap().0
    };
    let e = entity(&model, "V-1");
    let before = *model.world().get::<OperatingState>(e).unwrap();
    let counters = model
        .edit(Edit::SetOperating {
            vessel: "V-1".into(),
            operating: Some(OperatingDesign {
                liquid_level: 2500.0,
                liquid_density: None,
            }),
        })
        .unwrap();
    assert_eq!(counters.operating_updated, 1);
    assert_eq!(counters.vessels_resolved, 0);
    assert_eq!(counters.patches_rebuilt, 0);
    let after = *model.world().get::<OperatingState>(e).unwrap();
    assert!(after.liquid_volume > before.liquid_volume);
    assert_eq!(after.metal_mass, before.metal_mass);
    let expected = state(&{
        let mut d = model.design();
        d.vessels.truncate(1);
        d
    });
    assert_eq!(after.0, expected);
    // A level above the top is refused and changes nothing.
    assert!(
        model
            .edit(Edit::SetOperating {
                vessel: "V-1".into(),
                operating: Some(OperatingDesign {
                    liquid_level: 1e7,
                    liquid_density: None,
                }),
            })
            .is_err()
    );
    assert_eq!(*model.world().get::<OperatingState>(e).unwrap(), after);
}

#[test]
fn a_level_changed_after_a_resolving_edit_in_one_update_counts() {
    // The figures worked out while checking the course edit are for the old
    // level: the level changed after it must be the one the model shows.
    let plant = vessel("vertical", TWO_TO_ONE, TWO_TO_ONE, 500.0);
    let mut model = Model::from_design(&plant, TessellationOptions::chord(5.0)).unwrap();
    let mut course = plant.vessels[0].parts[1].clone();
    if let vesselcad::design::PartDesign::Shell(s) = &mut course {
        s.length += 400.0;
    }
    model
        .apply(Edit::SetPart {
            vessel: "V-1".into(),
            part: course,
        })
        .unwrap();
    model
        .apply(Edit::SetOperating {
            vessel: "V-1".into(),
            operating: Some(OperatingDesign {
                liquid_level: 1800.0,
                liquid_density: None,
            }),
        })
        .unwrap();
    let counters = model.update();
    assert_eq!(counters.vessels_resolved, 1, "{counters:?}");
    let world = model.world();
    let mut q = world
        .try_query::<&OperatingState>()
        .expect("operating states exist");
    let shown = *q.iter(world).next().expect("one vessel");
    assert_eq!(shown, OperatingState(state(&model.design())));
    assert_eq!(
        model.design().vessels[0].operating.unwrap().liquid_level,
        1800.0
    );
}

/// Parts above an eccentric reducer stand on an axis shifted by
/// e = (D₁ − D₂)/2: the centre of gravity moves sideways with them (it was
/// reported on the vessel's axis). Empty vertical vessel, flat plain heads, walls
/// 10 mm: each wall's volume is its mid-surface area times 10 (Pappus), the
/// reducer's cross-sections centred on the line joining its end centres, so its
/// lateral moment is e times its volume times the height fraction of its wall's
/// centroid, (r_a + 2 r_b) / 3 (r_a + r_b).
#[test]
fn the_centre_of_gravity_follows_the_parts_above_an_eccentric_reducer() {
    let text = format!(
        r#"{{"format": "vesselcad/1", "vessels": [{{"tag": "V-1", "kind": "vertical",
        "parts": [
          {{"head": {{"id": "H1", "thickness": {T}, "shape": "flat"}}}},
          {{"shell": {{"id": "S1", "od": 2000, "length": 2000, "thickness": {T}}}}},
          {{"reducer": {{"id": "R1", "length": 800, "eccentric": 90, "thickness": {T}}}}},
          {{"shell": {{"id": "S2", "od": 1400, "length": 2000, "thickness": {T}}}}},
          {{"head": {{"id": "H2", "thickness": {T}, "shape": "flat"}}}}
        ]}}]}}"#
    );
    let design = parse(&text).unwrap();
    let resolved = resolve(&design).unwrap();
    let s2 = resolved[0].parts.iter().find(|p| p.id == "S2").unwrap();
    let shift = s2.frame.translation.truncate();
    let e = 300.0;
    assert!((shift.length() - e).abs() < 1e-9, "{shift}");
    let h = T / 2.0;
    let head1 = PI * (1000.0 - h).powi(2) * T;
    let shell1 = 2.0 * PI * (1000.0 - h) * 2000.0 * T;
    let radial = h * (1.0 + (300.0f64 / 800.0).powi(2)).sqrt();
    let (ra, rb) = (1000.0 - radial, 700.0 - radial);
    let reducer = PI * (ra + rb) * (ra - rb).hypot(800.0) * T;
    let fraction = (ra + 2.0 * rb) / (3.0 * (ra + rb));
    let shell2 = 2.0 * PI * (700.0 - h) * 2000.0 * T;
    let head2 = PI * (700.0 - h).powi(2) * T;
    let total = head1 + shell1 + reducer + shell2 + head2;
    let sideways = e * (reducer * fraction + shell2 + head2) / total;
    let s = state_of_design(&design.vessels[0], &resolved[0]).unwrap();
    assert!(close(s.metal_mass, total * M3 * 7850.0, 1e-9));
    let cog = s.centre_of_gravity.truncate();
    let along = cog.dot(shift / e);
    let across = cog.perp_dot(shift / e);
    assert!(close(along, sideways, 1e-9), "{along} vs {sideways}");
    assert!(across.abs() < 1e-9, "{cog}");
}
