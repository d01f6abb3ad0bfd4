//! Writes past the model's edits. Only code inside the model can write its world
//! (`Model::world` and `Model::query` are read-only, a doctest on `query` shows a
//! mutable query does not compile); this test writes a parameter from inside, as
//! a bug in the model would, and checks the Validate stage still resolves the
//! vessel from the world rather than from the resolution the edit's check left.
//! A second test moves a nozzle off its host the same way, to show a cut that
//! fails is reported as a typed build failure.

use crate::components::NozzleSpec;
use crate::design::parse;
use crate::export::{build_scene, write_glb};
use crate::mesh::TessellationOptions;
use crate::model::{Edit, Model};

#[test]
fn a_vessel_written_around_apply_is_resolved_again() {
    let options = TessellationOptions::chord(2.0);
    let design = parse(include_str!("../../examples/designs/small-plant.json")).unwrap();
    let mut m = Model::from_design(&design, options).unwrap();
    let mut n = m.design().vessels[0].nozzles[0].clone();
    n.orientation = 45.0;
    m.apply(Edit::SetNozzle {
        vessel: "V-101".into(),
        nozzle: n.clone(),
    })
    .unwrap();
    // Written past the edit: the nozzle turned further before the update.
    let mut q = m.world.query::<&mut NozzleSpec>();
    let mut turned = 0;
    for mut spec in q.iter_mut(&mut m.world) {
        if spec.0 == n {
            spec.0.orientation = 90.0;
            turned += 1;
        }
    }
    assert_eq!(turned, 1);
    let c = m.update();
    assert_eq!(c.vessels_resolved, 1, "{c:?}");
    assert_eq!(c.resolutions_reused, 0, "{c:?}");
    assert_eq!(m.design().vessels[0].nozzles[0].orientation, 90.0);
    assert!(m.errors().0.is_empty());
    let full = build_scene(&m.design(), &options).unwrap();
    assert!(write_glb(&m.scene()).unwrap() == write_glb(&full).unwrap());
}

/// A nozzle whose opening the cutter cannot cut (moved 100 m off its host
/// past the edits, as a bug would; no design reaches this through the checked
/// edits) is reported as a build failure, typed, by its design path: not as a
/// broken rule.
#[test]
fn an_opening_that_cannot_be_cut_is_a_typed_build_failure() {
    use crate::components::{BuildCause, DirtyParts, ModelFailure, PartFrame};
    use crate::mesh::CutError;
    use glam::{DAffine3, DVec3};

    let options = TessellationOptions::chord(2.0);
    let design = parse(include_str!("../../examples/designs/small-plant.json")).unwrap();
    let mut m = Model::from_design(&design, options).unwrap();
    let (tag, mark) = (&design.vessels[0].tag, &design.vessels[0].nozzles[0].mark);
    let mut q = m.world.query::<(bevy_ecs::entity::Entity, &NozzleSpec)>();
    let vessel_of = |e| {
        let parent = m.world.get::<bevy_ecs::hierarchy::ChildOf>(e)?.parent();
        Some(
            m.world
                .get::<crate::components::VesselSpec>(parent)?
                .tag
                .clone(),
        )
    };
    let nozzle = q
        .iter(&m.world)
        .find(|(e, s)| &s.0.mark == mark && vessel_of(*e).as_ref() == Some(tag))
        .map(|(e, _)| e)
        .unwrap();
    let away = DAffine3::from_translation(DVec3::new(1e5, 0.0, 0.0));
    let frame = m.world.get::<PartFrame>(nozzle).unwrap().0;
    m.world.get_mut::<PartFrame>(nozzle).unwrap().0 = away * frame;
    m.world.resource_mut::<DirtyParts>().frames.push(nozzle);
    let work = m.update();
    assert_eq!(work.failures, 1, "{work:?}");
    let errors = &m.errors().0;
    let [ModelFailure::Build(failure)] = errors.as_slice() else {
        panic!("one build failure, no rule: {errors:?}");
    };
    assert_eq!(failure.path, "vessels[0].nozzles[0]", "{failure}");
    assert_eq!(failure.entity, format!("{tag}/{mark}"), "{failure}");
    assert_eq!(failure.cause.stage(), "opening", "{failure}");
    let BuildCause::Opening { host, source } = &failure.cause else {
        panic!("{failure}");
    };
    assert!(host.starts_with(&format!("{tag}/")), "{failure}");
    assert!(
        matches!(
            source,
            CutError::Intersection { .. } | CutError::NotWithinPatch { .. }
        ),
        "{failure}"
    );
    assert!(source.patch().is_some(), "{failure}");
}
