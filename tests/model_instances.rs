//! Equal patches share one mesh: a patch with the same surface, region and
//! options as one whose mesh is in use takes that mesh instead of being meshed
//! again, at the first build and after edits, and the model still holds exactly
//! what a from-scratch build of its design gives.

mod common;

use std::collections::HashSet;
use std::sync::Arc;

use vesselcad::components::PatchMesh;
use vesselcad::design::{Design, HeadShape, PartDesign, VesselDesign};
use vesselcad::export::{build_scene, write_glb};
use vesselcad::mesh::TessellationOptions;
use vesselcad::model::{Edit, Model};

fn options() -> TessellationOptions {
    TessellationOptions::chord(2.0)
}

fn small_plant() -> Design {
    common::examples::example("small-plant")
}

/// Distinct meshes held by the model's patches, and the number of patches.
fn distinct_meshes(model: &mut Model) -> (usize, usize) {
    let mut q = model.query::<&PatchMesh>();
    let world = model.world();
    let all: Vec<*const _> = q.iter(world).map(|m| Arc::as_ptr(&m.0)).collect();
    let distinct: HashSet<_> = all.iter().collect();
    (distinct.len(), all.len())
}

/// The ids of `vessel`'s heads that carry no nozzle.
fn free_heads(vessel: &VesselDesign) -> Vec<String> {
    vessel
        .parts
        .iter()
        .filter(|p| matches!(p, PartDesign::Head(_)))
        .map(|p| p.id().to_string())
        .filter(|id| !vessel.nozzles.iter().any(|n| n.host == *id))
        .collect()
}

/// `vessel` with head `id` made torispherical (ASME F&D defaults).
fn torispherical(vessel: &VesselDesign, id: &str) -> Edit {
    let mut part = vessel
        .parts
        .iter()
        .find(|p| p.id() == id)
        .expect("the head exists")
        .clone();
    let PartDesign::Head(h) = &mut part else {
        panic!("{id} is a head");
    };
    h.shape = HeadShape::Torispherical;
    h.ratio = None;
    Edit::SetPart {
        vessel: vessel.tag.clone(),
        part,
    }
}

fn assert_matches_full_build(model: &Model) {
    common::full_build::assert_matches_full_build(model, &options());
}

#[test]
fn equal_patches_share_one_mesh_from_the_first_build_on() {
    let mut model = Model::new(options()).expect("valid options");
    model
        .apply(Edit::ReplaceDesign(small_plant()))
        .expect("the example is valid");
    let c = model.update();
    // The plant's two drums have equal 2:1 heads and many equal flanges.
    assert!(c.meshes_shared > 0, "{c:?}");
    assert!(c.meshes_shared < c.meshes_rebuilt, "{c:?}");
    let (distinct, patches) = distinct_meshes(&mut model);
    assert_eq!(patches as u64, c.meshes_rebuilt);
    assert_eq!(
        distinct as u64,
        c.meshes_rebuilt - c.meshes_shared,
        "each distinct patch is meshed once: {c:?}"
    );
    assert!(model.errors().0.is_empty());
    assert_matches_full_build(&model);
}

#[test]
fn an_edit_that_repeats_a_patch_in_use_meshes_nothing() {
    let design = small_plant();
    let (a, b) = (&design.vessels[0], &design.vessels[1]);
    let (head_a, head_b) = (free_heads(a), free_heads(b));
    let (Some(head_a), Some(head_b)) = (head_a.first(), head_b.first()) else {
        panic!("the example's drums have heads without nozzles");
    };
    let mut model = Model::from_design(&design, options()).expect("the example is valid");
    // The first drum's head becomes torispherical: new patches, meshed.
    let first = model
        .edit(torispherical(a, head_a))
        .expect("a valid head swap");
    assert!(first.triangles_meshed > 0, "{first:?}");
    // The second drum's equal head becomes the same: every patch is one the
    // model already holds, so nothing is meshed.
    let second = model
        .edit(torispherical(b, head_b))
        .expect("a valid head swap");
    assert!(second.meshes_rebuilt > 0, "{second:?}");
    assert_eq!(second.meshes_shared, second.meshes_rebuilt, "{second:?}");
    assert_eq!(second.triangles_meshed, 0, "{second:?}");
    assert!(model.errors().0.is_empty());
    assert_matches_full_build(&model);
}

/// The canonical cut each nozzle of vessel `tag` was placed from, by mark.
fn cuts_of(model: &mut Model, tag: &str) -> Vec<(String, *const vesselcad::mesh::AxialCut)> {
    use bevy_ecs::hierarchy::ChildOf;
    use vesselcad::components::OpeningInput;
    use vesselcad::components::{NozzleSpec, VesselSpec};
    let mut q = model.query::<(&NozzleSpec, &ChildOf, &OpeningInput)>();
    let world = model.world();
    let mut out: Vec<_> = q
        .iter(world)
        .filter(|(_, parent, _)| {
            world
                .get::<VesselSpec>(parent.parent())
                .is_some_and(|v| v.tag == tag)
        })
        .filter_map(|(n, _, input)| {
            let cut = input.axial()? as *const vesselcad::mesh::AxialCut;
            Some((n.0.mark.clone(), cut))
        })
        .collect();
    out.sort();
    out
}

#[test]
fn openings_of_one_size_in_one_course_diameter_share_one_march() {
    let design = small_plant();
    let mut m = Model::from_design(&design, options()).unwrap();
    // V-101's 2" nozzles on its course face three ways at four elevations:
    // all four are placed from one canonical march; the 3", 6" and 8" (with a
    // pad) each have their own.
    let cuts = cuts_of(&mut m, "V-101");
    let of = |mark: &str| cuts.iter().find(|(m, _)| m == mark).map(|c| c.1);
    let two = of("N3").expect("N3 is cut in a straight course");
    for mark in ["N4", "N6", "N7"] {
        assert_eq!(of(mark), Some(two), "{mark}");
    }
    for mark in ["N1", "N2", "N5"] {
        assert_ne!(of(mark), Some(two), "{mark}");
    }
    // A second vessel like V-101, its nozzles turned and its course longer,
    // shares V-101's marches; its first update places every opening.
    let v101 = design.vessels[0].clone();
    let mut twin = v101.clone();
    twin.tag = "V-109".into();
    twin.placement.position[0] += 20_000.0;
    for n in &mut twin.nozzles {
        n.orientation = (n.orientation + 45.0) % 360.0;
    }
    for p in &mut twin.parts {
        if let PartDesign::Shell(s) = p {
            s.length += 300.0;
        }
    }
    let c = m.edit(Edit::SetVessel(twin)).unwrap();
    let course_nozzles = v101.nozzles.iter().filter(|n| n.host == "S1").count() as u64;
    assert!(c.openings_placed >= course_nozzles, "{c:?}");
    let twins = cuts_of(&mut m, "V-109");
    for (mark, cut) in cuts_of(&mut m, "V-101") {
        if v101
            .nozzles
            .iter()
            .any(|n| n.mark == mark && n.host == "S1")
        {
            assert_eq!(
                twins.iter().find(|t| t.0 == mark).map(|t| t.1),
                Some(cut),
                "{mark}"
            );
        }
    }
    assert_eq!(
        write_glb(&m.scene()).unwrap(),
        write_glb(&build_scene(&m.design(), &options()).unwrap()).unwrap(),
        "the model holds what a full build gives"
    );
}
