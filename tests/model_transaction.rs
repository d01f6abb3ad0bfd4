//! An edit is one transaction with its geometry (issue 30 §1): an edit that
//! passes every rule but whose geometry cannot be built is refused by
//! `Model::edit`, naming the part or nozzle by its JSON path, and leaves the
//! model as it was — design, meshes, errors and change log. The library's other
//! path, `Model::apply` then `Model::update` (or `try_update`), is the same
//! transaction: a failed update puts back every edit applied since the last
//! update that built. The edit is `common::unbuildable`'s: head H2 of the
//! horizontal drum made hemispherical under a vertex budget its crown then
//! needs more than.

use vesselcad::design::validate;
use vesselcad::export::write_glb;
use vesselcad::mesh::TessellationOptions;
use vesselcad::mesh::cdt::CdtError;
use vesselcad::model::{BuildCause, Edit, Model, ModelError, ModelFailure};

mod common;

use common::unbuildable::{
    ENTITY, MAX_VERTICES, PATCH, PATH, TOLERANCE, buildable, options, unbuildable,
};

#[test]
fn an_edit_whose_geometry_fails_is_refused_and_changes_nothing() {
    let design = buildable();
    let mut model = Model::from_design(&design, options()).unwrap();
    model.take_changes();
    let before = model.design();
    let glb = write_glb(&model.scene()).unwrap();
    let edited = unbuildable();
    validate(&edited).expect("the edit passes every rule");
    let err = model.edit(Edit::ReplaceDesign(edited)).unwrap_err();
    let ModelError::Geometry(failures) = &err else {
        panic!("expected a geometry refusal, got {err}");
    };
    assert_eq!(failures.len(), 1, "{err}");
    let v = &failures[0];
    assert_eq!((v.path.as_str(), v.entity.as_str()), (PATH, ENTITY), "{v}");
    // A mesher failure, typed, of the head's crown: not a broken rule.
    assert_eq!(
        (v.cause.stage(), v.cause.patch()),
        ("mesh", Some(PATCH)),
        "{v}"
    );
    assert!(
        matches!(
            &v.cause,
            BuildCause::Mesh {
                source: CdtError::BudgetExceeded { .. },
                ..
            }
        ),
        "{v}"
    );
    assert!(err.to_string().contains("nothing changed"), "{err}");
    // As it was: design, meshes, no errors, nothing to send to viewers.
    assert_eq!(model.design(), before);
    assert!(model.errors().0.is_empty(), "{:?}", model.errors());
    let changes = model.take_changes();
    assert!(
        changes.changed.is_empty() && changes.removed.is_empty(),
        "{changes:?}"
    );
    assert_eq!(write_glb(&model.scene()).unwrap(), glb);
    // And it goes on taking edits.
    let mut moved = design.clone();
    moved.vessels[0].placement.rotation += 10.0;
    model.edit(Edit::ReplaceDesign(moved)).unwrap();
    assert!(model.errors().0.is_empty(), "{:?}", model.errors());
}

/// A geometry failure names the part by its JSON path, never an ECS entity
/// (a pad's patch was named `103v0`); a design that cannot be built is refused
/// by `from_design` with every failure. The fixture fails by the budget alone:
/// with the default budget it builds.
#[test]
fn a_failure_is_named_by_the_design_not_by_the_entity() {
    let err = Model::from_design(&unbuildable(), options())
        .err()
        .expect("the design cannot be built");
    let ModelError::Geometry(failures) = &err else {
        panic!("expected a geometry refusal, got {err}");
    };
    assert!(!failures.is_empty());
    for v in failures {
        assert_eq!((v.path.as_str(), v.entity.as_str()), (PATH, ENTITY), "{v}");
    }
    let model = Model::from_design(&unbuildable(), TessellationOptions::chord(TOLERANCE))
        .expect("within the default budget, the edit builds");
    assert!(model.errors().0.is_empty(), "{:?}", model.errors());
}

/// `apply` then `update`: the update that cannot build puts back every edit
/// applied since the last update that built (here a valid move and the roof
/// nozzle), keeps the failures in `errors()` and counts them; the next update
/// builds nothing and reports nothing.
#[test]
fn apply_then_update_rolls_back_a_failed_build() {
    let design = buildable();
    let mut model = Model::from_design(&design, options()).unwrap();
    model.take_changes();
    let before = model.design();
    let glb = write_glb(&model.scene()).unwrap();
    let mut moved = design.clone();
    moved.vessels[0].placement.rotation += 10.0;
    model.apply(Edit::ReplaceDesign(moved)).unwrap();
    model.apply(Edit::ReplaceDesign(unbuildable())).unwrap();
    let work = model.update();
    assert!(work.failures > 0, "{work:?}");
    let errors = &model.errors().0;
    assert_eq!(errors.len(), 1, "{errors:?}");
    let ModelFailure::Build(failure) = &errors[0] else {
        panic!("a build failure, not a rule: {errors:?}");
    };
    assert_eq!(failure.path, PATH);
    assert_eq!(model.design(), before, "both edits are undone");
    assert_eq!(write_glb(&model.scene()).unwrap(), glb);
    let changes = model.take_changes();
    assert!(
        changes.changed.is_empty() && changes.removed.is_empty(),
        "{changes:?}"
    );
    assert_eq!(model.update(), Default::default());
    assert!(model.errors().0.is_empty());
    // `try_update` returns the failure instead, with the same rollback.
    model.apply(Edit::ReplaceDesign(unbuildable())).unwrap();
    let err = model.try_update().unwrap_err();
    assert!(
        matches!(&err, ModelError::Geometry(v) if v.len() == 1),
        "{err}"
    );
    assert!(model.errors().0.is_empty(), "{:?}", model.errors());
    assert_eq!(model.design(), before);
    // An update that builds keeps its edits and reports what changed,
    // including what was removed before it.
    let mut fewer = design.clone();
    let n1 = fewer.vessels[0].nozzles.remove(0).mark;
    fewer.vessels[0].notes.retain(|n| n.target != n1);
    model.apply(Edit::ReplaceDesign(fewer.clone())).unwrap();
    model.update();
    assert!(model.errors().0.is_empty(), "{:?}", model.errors());
    assert_eq!(
        model.design().vessels[0].nozzles.len(),
        fewer.vessels[0].nozzles.len()
    );
    let changes = model.take_changes();
    let tag = &fewer.vessels[0].tag;
    assert!(
        changes.removed.contains(&format!("{tag}/{n1}")),
        "{changes:?}"
    );
}

/// New tessellation options are part of the transaction (issue 31 §4): options
/// some patch cannot be meshed to are put back, every patch keeps the mesh of
/// the options in force, the failure is reported typed, and no mesh of other
/// options stands as current (the GLB is byte for byte the one before).
#[test]
fn options_that_cannot_be_meshed_are_put_back() {
    // Builds at 1 mm within the budget; its crowns cannot be meshed within
    // it at 0.5 mm.
    let mut model = Model::from_design(&buildable(), options()).unwrap();
    model.take_changes();
    let glb = write_glb(&model.scene()).unwrap();
    let finer = TessellationOptions::chord(TOLERANCE / 2.0).with_max_vertices(MAX_VERTICES);
    model.set_tessellation(finer).unwrap();
    let err = model.try_update().unwrap_err();
    let ModelError::Geometry(failures) = &err else {
        panic!("expected a geometry refusal, got {err}");
    };
    assert!(
        failures
            .iter()
            .any(|f| f.path == PATH && f.cause.stage() == "mesh"),
        "{err}"
    );
    assert_eq!(write_glb(&model.scene()).unwrap(), glb);
    // The options in force are the ones before: the next update has nothing to do.
    assert_eq!(model.update(), Default::default());
    assert!(model.errors().0.is_empty(), "{:?}", model.errors());
    // `update` does the same, keeping the failures in `errors()`.
    model.set_tessellation(finer).unwrap();
    let work = model.update();
    assert!(work.failures > 0, "{work:?}");
    assert!(!model.errors().0.is_empty());
    assert_eq!(write_glb(&model.scene()).unwrap(), glb);
}
