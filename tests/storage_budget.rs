//! The storage budget (the chordal tolerance less the `f32` rounding of the
//! plant's largest part) costs what an edit changed (issue 30 §5): each update
//! reads the extents of the patches it rebuilt only, never the plant's, and the
//! running maximum still follows a part that grows past the floor's 32 m and
//! goes again.

mod common;

use common::examples::example;
use vesselcad::components::Tessellation;
use vesselcad::design::{VesselDesign, parse};
use vesselcad::mesh::{OptionsError, TessellationOptions, storage_options};
use vesselcad::model::{Edit, Model, ModelError};
use vesselcad::plant::build_plant;

fn options() -> TessellationOptions {
    TessellationOptions::chord(2.0)
}

/// A 70 m flat-bottomed tank: its course reaches 35 m from its axis, past the
/// floor's 32 m.
fn big_tank() -> VesselDesign {
    let text = r#"{
      "format": "vesselcad/1",
      "units": "mm",
      "vessels": [
        {
          "tag": "TK-70",
          "kind": "tank",
          "placement": { "position": [0, 200000, 0], "rotation": 0 },
          "design": { "pressure": 2, "temperature": 40, "corrosion_allowance": 1.5, "material": "A283-C" },
          "parts": [
            { "head": { "id": "BTM", "shape": "flat", "thickness": 12 } },
            { "shell": { "id": "S1", "od": 70000, "length": 2400, "thickness": 30 } },
            { "head": { "id": "ROOF", "shape": "conical", "half_angle": 80, "thickness": 8 } }
          ],
          "nozzles": []
        }
      ]
    }"#;
    parse(text).unwrap().vessels.remove(0)
}

fn tolerance(model: &Model) -> f64 {
    model.world().resource::<Tessellation>().0.tolerance
}

#[test]
fn an_edit_reads_the_extents_of_what_it_rebuilt_only() {
    let mut m = Model::from_design(&example("small-plant"), options()).unwrap();
    let first = m
        .world()
        .resource::<vesselcad::systems::WorkCounters>()
        .storage_extents_read;
    assert!(first > 50, "the first build reads every patch: {first}");
    let design = m.design();
    let mut nozzle = design.vessels[1].nozzles[0].clone();
    nozzle.projection += 40.0;
    let c = m
        .edit(Edit::SetNozzle {
            vessel: design.vessels[1].tag.clone(),
            nozzle,
        })
        .unwrap();
    assert!(c.patches_rebuilt > 0, "{c:?}");
    assert!(
        c.storage_extents_read <= c.patches_rebuilt && c.storage_extents_read < first / 10,
        "{c:?} (the plant has {first} patches)"
    );
    // A move rebuilds no patch and reads no extent.
    let c = m
        .edit(Edit::MoveVessel {
            tag: design.vessels[0].tag.clone(),
            placement: vesselcad::design::Placement {
                rotation: design.vessels[0].placement.rotation + 15.0,
                ..design.vessels[0].placement
            },
        })
        .unwrap();
    assert_eq!(c.storage_extents_read, 0, "{c:?}");
}

#[test]
fn the_running_maximum_follows_a_large_part_in_and_out() {
    let mut m = Model::from_design(&example("small-plant"), options()).unwrap();
    let floor = tolerance(&m);
    assert_eq!(floor, storage_options(&options(), 0.0).tolerance);
    let c = m.edit(Edit::SetVessel(big_tank())).unwrap();
    assert!(tolerance(&m) < floor, "{} !< {floor}", tolerance(&m));
    assert_eq!(
        tolerance(&m),
        storage_options(&options(), 35_000.0).tolerance
    );
    assert!(c.storage_extents_read > 0);
    common::full_build::assert_matches_full_build(&m, &options());
    m.edit(Edit::RemoveVessel {
        tag: "TK-70".into(),
    })
    .unwrap();
    assert_eq!(tolerance(&m), floor, "the maximum went with the tank");
    common::full_build::assert_matches_full_build(&m, &options());
}

/// A tolerance whose storage budget leaves the mesher less than its 1e-6 mm
/// floor (f32 rounding of at least 0.00165 mm takes half of any tolerance up
/// to 0.0033 mm) is one options error before any work — from `Model::new`,
/// `set_tessellation` and `build_plant` (which names the design's largest
/// part) — not one mesh failure per patch. The 70 m tank rounds coarser but
/// has the same floor.
#[test]
fn a_tolerance_below_the_storage_floor_is_refused_up_front() {
    let below = |e: &ModelError| match e {
        ModelError::Options(OptionsError::BelowStorageFloor {
            tolerance,
            extent,
            meshed,
            smallest,
            ..
        }) => Some((*tolerance, *extent, *meshed, *smallest)),
        _ => None,
    };
    let err = Model::new(TessellationOptions::chord(1e-6)).err().unwrap();
    assert_eq!(below(&err), Some((1e-6, None, 0.5e-6, 2e-6)), "{err}");
    assert!(Model::new(TessellationOptions::chord(2e-6)).is_ok());
    let mut m = Model::from_design(&example("horizontal-drum"), options()).unwrap();
    let err = m
        .set_tessellation(TessellationOptions::chord(1.9e-6))
        .unwrap_err();
    assert_eq!(below(&err).map(|b| b.3), Some(2e-6), "{err}");
    assert_eq!(m.update(), Default::default(), "the options in force stay");
    let mut plant = example("horizontal-drum");
    plant.vessels.push(big_tank());
    let err = build_plant(&plant, TessellationOptions::chord(1e-6), &mut |_, _| {})
        .err()
        .unwrap();
    let (_, extent, _, smallest) = below(&err).unwrap_or_else(|| panic!("{err}"));
    // The tank's course: radius 35 000 mm in its part's frame.
    assert!(extent.is_some_and(|e| (e - 35_000.0).abs() < 1e-6), "{err}");
    assert_eq!(smallest, 2e-6);
    let text = err.to_string();
    assert!(
        text.contains("largest part reaches 35000 mm")
            && text.contains("the smallest tolerance is 2e-6 mm"),
        "{text}"
    );
}
