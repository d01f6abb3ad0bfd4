//! An edit is one transaction with its geometry (issue 30 §1): an edit that
//! passes every rule but whose geometry cannot be built is refused by
//! `Model::edit`, naming the part or nozzle by its JSON path, and leaves the
//! model as it was — design, meshes, errors and change log. The library's other
//! path, `Model::apply` then `Model::update` (or `try_update`), is the same
//! transaction: a failed update puts back every edit applied since the last
//! update that built.

use vesselcad::design::{Design, load, validate};
use vesselcad::export::write_glb;
use vesselcad::mesh::TessellationOptions;
use vesselcad::mesh::cdt::CdtError;
use vesselcad::model::{BuildCause, Edit, Model, ModelError, ModelFailure};

/// The plant whose storage tank's conical roof could not be meshed at 1 mm
/// with nozzle N3 (`vessels[3].nozzles[1]`): a loop segment along a cone
/// generator, fanned to the apex. The roof now builds (see
/// `mesh_watertight::the_fuzz_plants_conical_roof_builds_closed_at_1_and_0_7_mm`),
/// so the tests using it are ignored until they get another design that
/// `check` accepts and `build` refuses, or an injected mesher failure.
fn unbuildable() -> Design {
    load(format!(
        "{}/tests/repros/fuzz-seed1-accepted-edit-roof-4M-vertices.json",
        env!("CARGO_MANIFEST_DIR")
    ))
    .unwrap()
}

/// The same plant without the tank's roof nozzle N3: it builds at 1 mm.
fn buildable() -> Design {
    let mut design = unbuildable();
    let tank = &mut design.vessels[3];
    let n3 = tank.nozzles.remove(1);
    assert_eq!(n3.mark, "N3");
    tank.notes.retain(|n| n.target != n3.mark);
    design
}

const TOLERANCE: f64 = 1.0;

#[test]
#[ignore = "needs an edit that check accepts and the mesher cannot build: the fuzz plant's roof at 1 mm, the last one known, builds since the pole-row fix (issue 30)"]
fn an_edit_whose_geometry_fails_is_refused_and_changes_nothing() {
    let design = buildable();
    let mut model = Model::from_design(&design, TessellationOptions::chord(TOLERANCE)).unwrap();
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
    assert_eq!(
        (v.path.as_str(), v.entity.as_str()),
        ("vessels[3].parts[2]", "TK-301/ROOF"),
        "{v}"
    );
    // A mesher failure, typed, of the roof's cone: not a broken rule.
    assert_eq!(
        (v.cause.stage(), v.cause.patch()),
        ("mesh", Some("cone")),
        "{v}"
    );
    assert!(
        matches!(
            &v.cause,
            BuildCause::Mesh {
                source: CdtError::RefinementRunaway { .. } | CdtError::NotConverged { .. },
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
/// by `from_design` with every failure.
#[test]
#[ignore = "needs an edit that check accepts and the mesher cannot build: the fuzz plant's roof at 1 mm, the last one known, builds since the pole-row fix (issue 30)"]
fn a_failure_is_named_by_the_design_not_by_the_entity() {
    let err = Model::from_design(&unbuildable(), TessellationOptions::chord(TOLERANCE))
        .err()
        .expect("the design cannot be built");
    let ModelError::Geometry(failures) = &err else {
        panic!("expected a geometry refusal, got {err}");
    };
    assert!(!failures.is_empty());
    for v in failures {
        assert!(v.entity.starts_with("TK-301/"), "{v}");
        assert_eq!(v.path, "vessels[3].parts[2]", "{v}");
    }
}

/// `apply` then `update`: the update that cannot build puts back every edit
/// applied since the last update that built (here a valid move and the roof
/// nozzle), keeps the failures in `errors()` and counts them; the next update
/// builds nothing and reports nothing.
#[test]
#[ignore = "needs an edit that check accepts and the mesher cannot build: the fuzz plant's roof at 1 mm, the last one known, builds since the pole-row fix (issue 30)"]
fn apply_then_update_rolls_back_a_failed_build() {
    let design = buildable();
    let mut model = Model::from_design(&design, TessellationOptions::chord(TOLERANCE)).unwrap();
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
    assert_eq!(failure.path, "vessels[3].parts[2]");
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
#[ignore = "needs an edit that check accepts and the mesher cannot build: the fuzz plant's roof at 1 mm, the last one known, builds since the pole-row fix (issue 30)"]
fn options_that_cannot_be_meshed_are_put_back() {
    // Builds at the default 0.5 mm; its roof cannot be meshed at 1 mm.
    let mut model = Model::from_design(&unbuildable(), TessellationOptions::DEFAULT).unwrap();
    model.take_changes();
    let glb = write_glb(&model.scene()).unwrap();
    model
        .set_tessellation(TessellationOptions::chord(TOLERANCE))
        .unwrap();
    let err = model.try_update().unwrap_err();
    let ModelError::Geometry(failures) = &err else {
        panic!("expected a geometry refusal, got {err}");
    };
    assert!(
        failures
            .iter()
            .any(|f| f.path == "vessels[3].parts[2]" && f.cause.stage() == "mesh"),
        "{err}"
    );
    assert_eq!(write_glb(&model.scene()).unwrap(), glb);
    // The options in force are the ones before: the next update has nothing to do.
    assert_eq!(model.update(), Default::default());
    assert!(model.errors().0.is_empty(), "{:?}", model.errors());
    // `update` does the same, keeping the failures in `errors()`.
    model
        .set_tessellation(TessellationOptions::chord(TOLERANCE))
        .unwrap();
    let work = model.update();
    assert!(work.failures > 0, "{work:?}");
    assert!(!model.errors().0.is_empty());
    assert_eq!(write_glb(&model.scene()).unwrap(), glb);
}
