//! The ECS model redoes only the work that depends on an edit, refuses bad edits
//! without changing anything, and after any sequence of edits holds exactly what a
//! from-scratch build of its design gives.

mod common;

use common::examples::example;
use vesselcad::design::{PartDesign, to_canonical_json};
use vesselcad::export::{build_scene, write_glb};
use vesselcad::mesh::TessellationOptions;
use vesselcad::model::{Edit, Model, ModelError};

fn options() -> TessellationOptions {
    TessellationOptions::chord(2.0)
}

fn model(name: &str) -> Model {
    Model::from_design(&example(name), options()).unwrap()
}

/// The incremental model's GLB equals a from-scratch build of its design.
fn assert_matches_full_build(model: &Model) {
    common::full_build::assert_matches_full_build(model, &options());
}

/// The comparison names the first node that differs, not only that bytes do.
#[test]
fn a_mismatch_names_the_first_differing_node() {
    let m = model("small-plant");
    let mut design = m.design();
    design.vessels[1].nozzles[2].orientation += 10.0;
    let moved = design.vessels[1].nozzles[2].mark.clone();
    let tag = design.vessels[1].tag.clone();
    let other = build_scene(&design, &options()).unwrap();
    let found =
        common::full_build::first_difference(&m.scene(), &other).expect("the scenes differ");
    assert!(
        found.starts_with(&format!("{tag}/{moved}: frame")),
        "{found}"
    );
    let same = build_scene(&m.design(), &options()).unwrap();
    assert_eq!(
        common::full_build::first_difference(&m.scene(), &same),
        None
    );
}

#[test]
fn first_update_builds_everything_once() {
    let mut m = model("small-plant");
    assert!(m.errors().0.is_empty());
    assert_matches_full_build(&m);
    // Nothing changed since: a second update does no work at all.
    let counters = m.update();
    assert_eq!(counters, Default::default());
}

#[test]
fn nozzle_orientation_moves_only_that_nozzle() {
    let mut m = model("small-plant");
    m.take_changes();
    let mut n = m.design().vessels[0].nozzles[0].clone();
    n.orientation = 45.0;
    let c = m
        .edit(Edit::SetNozzle {
            vessel: "V-101".into(),
            nozzle: n,
        })
        .unwrap();
    assert_eq!(c.vessels_resolved, 1);
    // Resolved once, when the edit was checked: the Validate stage took that.
    assert_eq!(c.resolutions_reused, 1, "{c:?}");
    assert_eq!(c.frames_updated, 1, "{c:?}");
    assert_eq!(
        c.patches_rebuilt, 0,
        "a frame change must not rebuild patches: {c:?}"
    );
    // The opening turns about the course's axis: placed from its kept
    // canonical cut, turned. The neck's region and the pad (patch and region,
    // in the nozzle's frame) come out the same, so only the host shell (one
    // patch) is re-meshed.
    assert_eq!((c.openings_cut, c.openings_placed), (1, 1), "{c:?}");
    assert_eq!(c.meshes_rebuilt, 1, "{c:?}");
    let log = m.take_changes();
    assert_eq!(
        log.changed.into_iter().collect::<Vec<_>>(),
        vec!["V-101/N1".to_string(), "V-101/S1".to_string()]
    );
    assert_matches_full_build(&m);
}

#[test]
fn nozzle_elevation_places_its_opening_without_marching_and_keeps_neck_and_pad_meshes() {
    let mut m = model("small-plant");
    m.take_changes();
    let mut n = m.design().vessels[0].nozzles[0].clone();
    n.elevation = n.elevation.map(|e| e + 300.0);
    let c = m
        .edit(Edit::SetNozzle {
            vessel: "V-101".into(),
            nozzle: n,
        })
        .unwrap();
    // The nozzle only moved along its course's axis: the opening is placed
    // from its kept canonical cut. The neck's region and the pad's patch (the
    // course's canonical copy, in the nozzle's frame) and region come out the
    // same, so both keep their meshes: only the host course is meshed again.
    // Turning it (below) does the same.
    assert_eq!((c.openings_cut, c.openings_placed), (1, 1), "{c:?}");
    assert_eq!(c.meshes_rebuilt, 1, "{c:?}");
    // The neck is not even laid out again: its surface is the same and its
    // loop's neck side is the canonical march's, bit for bit. The host course's
    // region changes; the pad's comes out the same.
    assert_eq!((c.regions_unchanged, c.regions_laid_out), (1, 1), "{c:?}");
    // The course's other openings keep their cavities, whose triangles are
    // taken from its last meshing; the mesh is a fresh one's all the same.
    assert!(c.cavities_reused >= 1, "{c:?}");
    assert_matches_full_build(&m);
    // Turning it about the course's axis, too, places the kept cut.
    let mut n = m.design().vessels[0].nozzles[0].clone();
    n.orientation += 30.0;
    let c = m
        .edit(Edit::SetNozzle {
            vessel: "V-101".into(),
            nozzle: n,
        })
        .unwrap();
    assert_eq!((c.openings_cut, c.openings_placed), (1, 1), "{c:?}");
    assert_eq!(c.meshes_rebuilt, 1, "{c:?}");
    assert_matches_full_build(&m);
}

#[test]
fn nozzle_projection_rebuilds_only_that_nozzle() {
    let mut m = model("small-plant");
    m.take_changes();
    let mut n = m.design().vessels[0].nozzles[1].clone();
    n.projection += 100.0;
    let c = m
        .edit(Edit::SetNozzle {
            vessel: "V-101".into(),
            nozzle: n,
        })
        .unwrap();
    assert_eq!(c.shapes_rebuilt, 1, "{c:?}");
    assert!(c.patches_rebuilt > 0 && c.patches_rebuilt <= 8, "{c:?}");
    // The opening is cut again, on a neck whose reach the host sets (not the
    // projection): the loop comes out bit for bit the same on the host, so the
    // host course and the pad keep their regions and meshes. Only the nozzle's
    // own patches are meshed, and only the neck's region (its bottom loop, in
    // the longer neck's v) is laid out anew. In a straight course the canonical
    // cut kept from before is placed again, not marched: the neck it was marched
    // on is the same.
    assert_eq!((c.openings_cut, c.openings_placed), (1, 1), "{c:?}");
    assert_eq!(c.meshes_rebuilt, c.patches_rebuilt, "{c:?}");
    assert_eq!(c.regions_laid_out, 1, "{c:?}");
    let changed = m.take_changes().changed;
    assert_eq!(
        changed.into_iter().collect::<Vec<_>>(),
        vec!["V-101/N2".to_string()]
    );
    assert_matches_full_build(&m);
}

#[test]
fn shell_diameter_rebuilds_its_dependents_in_its_vessel_only() {
    let mut m = model("small-plant");
    m.take_changes();
    let design = m.design();
    let PartDesign::Shell(mut shell) = design.vessels[0].parts[1].clone() else {
        panic!()
    };
    shell.od = 2500.0;
    let c = m
        .edit(Edit::SetPart {
            vessel: "V-101".into(),
            part: PartDesign::Shell(shell),
        })
        .unwrap();
    assert_eq!(c.vessels_resolved, 1);
    // The shell, both heads, both saddles and the boot change shape; nozzles keep
    // theirs (projection is measured from the axis).
    assert_eq!(c.shapes_rebuilt, 6, "{c:?}");
    let changed = m.take_changes().changed;
    assert!(
        changed.iter().all(|id| id.starts_with("V-101")),
        "{changed:?}"
    );
    for id in [
        "V-101/S1",
        "V-101/H1",
        "V-101/H2",
        "V-101/SD1",
        "V-101/SD2",
        "V-101/B1",
    ] {
        assert!(changed.contains(id), "{id} missing from {changed:?}");
    }
    assert_matches_full_build(&m);
}

/// The boot of V-101 in the small plant.
fn boot(m: &Model) -> vesselcad::design::BootDesign {
    m.design().vessels[0]
        .parts
        .iter()
        .find_map(|p| match p {
            PartDesign::Boot(b) => Some(b.clone()),
            _ => None,
        })
        .unwrap()
}

#[test]
fn boot_length_rebuilds_only_the_boot_and_its_host_patch() {
    let mut m = model("small-plant");
    m.take_changes();
    let mut b = boot(&m);
    b.length += 250.0;
    let c = m
        .edit(Edit::SetPart {
            vessel: "V-101".into(),
            part: PartDesign::Boot(b),
        })
        .unwrap();
    assert_eq!(c.shapes_rebuilt, 1, "{c:?}");
    // The boot's shell is cut again against the course; the boot's own patches
    // and at most the course's one patch (if the hole's samples moved) re-mesh.
    assert_eq!(c.openings_cut, 1, "{c:?}");
    assert!(c.patches_rebuilt > 0, "{c:?}");
    assert!(
        c.meshes_rebuilt >= c.patches_rebuilt && c.meshes_rebuilt <= c.patches_rebuilt + 1,
        "{c:?}"
    );
    let changed = m.take_changes().changed;
    assert!(changed.contains("V-101/B1"), "{changed:?}");
    assert!(
        changed
            .iter()
            .all(|id| id == "V-101/B1" || id == "V-101/S1"),
        "{changed:?}"
    );
    assert_matches_full_build(&m);
}

#[test]
fn moving_the_boot_recuts_its_opening_without_rebuilding_patches() {
    let mut m = model("small-plant");
    m.take_changes();
    let mut b = boot(&m);
    b.position += 700.0;
    let c = m
        .edit(Edit::SetPart {
            vessel: "V-101".into(),
            part: PartDesign::Boot(b),
        })
        .unwrap();
    assert_eq!((c.shapes_rebuilt, c.patches_rebuilt), (0, 0), "{c:?}");
    assert_eq!(c.frames_updated, 1, "{c:?}");
    // The hole moves in the course: the boot's shell and the course re-mesh, at
    // most (the boot's own bottom loop is unchanged in its (u, v)).
    assert_eq!(c.openings_cut, 1, "{c:?}");
    assert!(c.meshes_rebuilt >= 1 && c.meshes_rebuilt <= 2, "{c:?}");
    assert_eq!(
        m.take_changes().changed.into_iter().collect::<Vec<_>>(),
        vec!["V-101/B1".to_string(), "V-101/S1".to_string()]
    );
    assert_matches_full_build(&m);
}

#[test]
fn a_nozzle_across_a_head_seam_recuts_both_host_patches_incrementally() {
    // N3 moved out to cross the knuckle–crown seam of the torispherical top head
    // (at a radius of about 655 mm).
    let mut design = example("vertical-column");
    let n3 = design.vessels[0]
        .nozzles
        .iter_mut()
        .find(|n| n.mark == "N3")
        .unwrap();
    n3.size = 3.0;
    n3.offset = Some(640.0);
    let mut m = Model::from_design(&design, options()).unwrap();
    assert!(m.errors().0.is_empty(), "{:?}", m.errors());
    assert_matches_full_build(&m);
    m.take_changes();
    let mut n = m.design().vessels[0]
        .nozzles
        .iter()
        .find(|n| n.mark == "N3")
        .unwrap()
        .clone();
    n.orientation = 100.0;
    let c = m
        .edit(Edit::SetNozzle {
            vessel: "C-201".into(),
            nozzle: n,
        })
        .unwrap();
    assert_eq!((c.frames_updated, c.patches_rebuilt), (1, 0), "{c:?}");
    // The neck, the knuckle and the crown, nothing else.
    assert_eq!(c.openings_cut, 1, "{c:?}");
    assert_eq!(c.meshes_rebuilt, 3, "{c:?}");
    assert_eq!(
        m.take_changes().changed.into_iter().collect::<Vec<_>>(),
        vec!["C-201/H2".to_string(), "C-201/N3".to_string()]
    );
    assert!(m.errors().0.is_empty(), "{:?}", m.errors());
    assert_matches_full_build(&m);
    // Moved inside the crown: the knuckle loses its notch and is re-meshed whole.
    let mut n = m.design().vessels[0]
        .nozzles
        .iter()
        .find(|n| n.mark == "N3")
        .unwrap()
        .clone();
    n.offset = Some(400.0);
    let c = m
        .edit(Edit::SetNozzle {
            vessel: "C-201".into(),
            nozzle: n,
        })
        .unwrap();
    assert_eq!(c.meshes_rebuilt, 3, "{c:?}");
    assert!(m.errors().0.is_empty(), "{:?}", m.errors());
    assert_matches_full_build(&m);
}

#[test]
fn lengthening_a_course_moves_what_is_above_without_rebuilding_it() {
    let mut m = model("vertical-column");
    m.take_changes();
    let design = m.design();
    let PartDesign::Shell(mut s1) = design.vessels[0].parts[2].clone() else {
        panic!()
    };
    s1.length += 500.0;
    let c = m
        .edit(Edit::SetPart {
            vessel: "C-201".into(),
            part: PartDesign::Shell(s1),
        })
        .unwrap();
    // Only S1 changes shape. The reducer, S2, the top head and the nozzle on the
    // head move; shell nozzles keep their elevation above the datum, so they stay.
    assert_eq!(c.shapes_rebuilt, 1, "{c:?}");
    assert_eq!(c.frames_updated, 4, "{c:?}");
    // The shell nozzles on S1 and S2 are cut again, but each only moved along its
    // course's axis: all placed from their canonical cuts, without marching, and
    // no neck or pad is meshed again — only the two courses.
    assert_eq!((c.openings_cut, c.openings_placed), (8, 8), "{c:?}");
    assert_eq!(c.meshes_rebuilt, 2, "{c:?}");
    let changed = m.take_changes().changed;
    for id in ["C-201/H2", "C-201/N3", "C-201/R1", "C-201/S1", "C-201/S2"] {
        assert!(changed.contains(id), "{id} missing from {changed:?}");
    }
    // Beyond those, only nozzles whose host changed or moved may be re-trimmed.
    let hosted = [
        "C-201/M1", "C-201/M2", "C-201/N1", "C-201/N2", "C-201/N5", "C-201/N6", "C-201/N7",
        "C-201/N8",
    ];
    for id in &changed {
        assert!(
            ["C-201/H2", "C-201/N3", "C-201/R1", "C-201/S1", "C-201/S2"].contains(&id.as_str())
                || hosted.contains(&id.as_str()),
            "{id} should not have changed"
        );
    }
    assert_matches_full_build(&m);
}

#[test]
fn moving_a_vessel_rebuilds_no_patch() {
    let mut m = model("small-plant");
    m.take_changes();
    let mut placement = m.design().vessels[2].placement;
    placement.position[0] += 5000.0;
    let c = m
        .edit(Edit::MoveVessel {
            tag: "C-201".into(),
            placement,
        })
        .unwrap();
    assert_eq!(
        (c.patches_rebuilt, c.meshes_rebuilt, c.shapes_rebuilt),
        (0, 0, 0),
        "{c:?}"
    );
    assert_eq!(
        m.take_changes().changed.into_iter().collect::<Vec<_>>(),
        vec!["C-201".to_string()]
    );
    assert_matches_full_build(&m);
}

#[test]
fn an_edit_to_the_same_value_does_nothing() {
    let mut m = model("small-plant");
    let n = m.design().vessels[0].nozzles[0].clone();
    let c = m
        .edit(Edit::SetNozzle {
            vessel: "V-101".into(),
            nozzle: n,
        })
        .unwrap();
    assert_eq!(c, Default::default());
    let design = m.design();
    let c = m.edit(Edit::ReplaceDesign(design)).unwrap();
    assert_eq!(c, Default::default());
}

#[test]
fn rejected_edits_leave_the_model_unchanged() {
    let mut m = model("small-plant");
    let before = to_canonical_json(&m.design());
    let glb_before = write_glb(&m.scene()).unwrap();
    // A nozzle larger than its shell.
    let mut n = m.design().vessels[1].nozzles[0].clone();
    n.size = 24.0;
    n.host = "S1".into();
    n.elevation = Some(2500.0);
    let mut big = m.design().vessels[0].clone();
    big.tag = "V-102".into();
    let err = m.apply(Edit::SetNozzle {
        vessel: "V-102".into(),
        nozzle: {
            let mut x = n.clone();
            x.size = 30.0;
            x
        },
    });
    assert!(err.is_err());
    // A knuckle larger than its crown, in a batch with a valid edit: all or nothing.
    let mut placement = m.design().vessels[0].placement;
    placement.position[1] += 100.0;
    let bad_head = PartDesign::Head(vesselcad::design::HeadDesign {
        id: "H2".into(),
        shape: vesselcad::design::HeadShape::Torispherical,
        ratio: None,
        crown_radius: Some(2400.0),
        knuckle_radius: Some(2500.0),
        half_angle: None,
        small_od: None,
        straight_flange: 50.0,
        thickness: None,
    });
    let err = m
        .apply(Edit::Batch(vec![
            Edit::MoveVessel {
                tag: "V-101".into(),
                placement,
            },
            Edit::SetPart {
                vessel: "V-101".into(),
                part: bad_head,
            },
        ]))
        .unwrap_err();
    let ModelError::Design(e) = &err else {
        panic!("{err}")
    };
    let v = &e.violations()[0];
    assert_eq!(v.entity, "V-101/H2");
    assert_eq!(v.field, "knuckle_radius");
    assert_eq!(v.value, "2500");
    assert!(v.rule.contains("crown radius"), "{v}");
    assert_eq!(v.path, "vessels[0].parts[2].head.knuckle_radius");
    // Unknown targets.
    assert!(matches!(
        m.apply(Edit::RemoveVessel {
            tag: "X-999".into()
        }),
        Err(ModelError::UnknownVessel { .. })
    ));
    assert_eq!(m.update(), Default::default());
    assert_eq!(before, to_canonical_json(&m.design()));
    assert!(glb_before == write_glb(&m.scene()).unwrap());
    let _ = big;
}

#[test]
fn structural_edits_match_a_full_build() {
    let mut m = model("small-plant");
    // Remove a nozzle, add another, add a note, remove a vessel, change a head shape.
    m.edit(Edit::RemoveNozzle {
        vessel: "V-101".into(),
        mark: "N7".into(),
    })
    .unwrap();
    let mut n = m.design().vessels[0].nozzles[0].clone();
    n.mark = "N9".into();
    n.elevation = Some(3300.0);
    m.edit(Edit::SetNozzle {
        vessel: "V-101".into(),
        nozzle: n,
    })
    .unwrap();
    m.edit(Edit::RemoveVessel {
        tag: "V-102".into(),
    })
    .unwrap();
    let design = m.design();
    let PartDesign::Head(mut h) = design.vessels[0].parts[2].clone() else {
        panic!()
    };
    h.shape = vesselcad::design::HeadShape::Hemispherical;
    h.ratio = None;
    m.edit(Edit::SetPart {
        vessel: "V-101".into(),
        part: PartDesign::Head(h),
    })
    .unwrap();
    assert!(m.errors().0.is_empty());
    assert_eq!(m.design().vessels.len(), 3);
    assert_matches_full_build(&m);
    let removed = m.take_changes().removed;
    assert!(
        removed.contains("V-102") && removed.contains("V-101/N7"),
        "{removed:?}"
    );
}
