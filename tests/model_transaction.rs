//! An edit is one transaction with its geometry (issue 30 §1): an edit that
//! passes every rule but whose geometry cannot be built is refused by
//! `Model::edit`, naming the part or nozzle by its JSON path, and leaves the
//! model as it was — design, meshes, errors and change log. The library's other
//! path, `Model::apply` then `Model::update` (or `try_update`), is the same
//! transaction: a failed update puts back every edit applied since the last
//! update that built.

use vesselcad::design::{Design, PadDesign, load, validate};
use vesselcad::export::write_glb;
use vesselcad::mesh::TessellationOptions;
use vesselcad::model::{Edit, Model, ModelError};
use vesselcad::parts::tables::{Nps, pipe};

fn column() -> Design {
    load(format!(
        "{}/examples/designs/vertical-column.json",
        env!("CARGO_MANIFEST_DIR")
    ))
    .unwrap()
}

/// Radius of the knuckle–crown seam of the column's torispherical head `id`.
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

/// The column with its top-head nozzle N3 made a 3-inch nozzle astride the
/// knuckle–crown seam of H2, with a reinforcing pad: every rule holds, but a pad
/// cannot be cut across a head's seam. Returns the design and N3's index.
fn pad_across_the_seam(design: &Design) -> (Design, usize) {
    let mut edited = design.clone();
    let seam = crown_seam_radius(design, "H2");
    let v = &mut edited.vessels[0];
    let k = v.nozzles.iter().position(|n| n.mark == "N3").unwrap();
    let n = &mut v.nozzles[k];
    n.size = 3.0;
    n.orientation = 30.0;
    n.offset = Some(seam - 0.5 * pipe(Nps::try_new(3.0).unwrap()).outside_diameter / 2.0);
    n.pad = Some(PadDesign {
        od: 120.0,
        thickness: 10.0,
    });
    (edited, k)
}

#[test]
fn an_edit_whose_geometry_fails_is_refused_and_changes_nothing() {
    let design = column();
    let mut model = Model::from_design(&design, TessellationOptions::chord(1.0)).unwrap();
    model.take_changes();
    let before = model.design();
    let glb = write_glb(&model.scene()).unwrap();
    let (edited, k) = pad_across_the_seam(&design);
    validate(&edited).expect("the edit passes every rule");
    let err = model.edit(Edit::ReplaceDesign(edited)).unwrap_err();
    let ModelError::Geometry(failures) = &err else {
        panic!("expected a geometry refusal, got {err}");
    };
    assert_eq!(failures.len(), 1, "{err}");
    let v = &failures[0];
    assert_eq!(
        (v.path.as_str(), v.entity.as_str(), v.field.as_str()),
        (
            format!("vessels[0].nozzles[{k}]").as_str(),
            "C-201/N3",
            "opening"
        ),
        "{v}"
    );
    assert!(v.rule.contains("reinforcing pad"), "{v}");
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
    // And it goes on taking edits: the same nozzle without its pad builds.
    let (mut edited, k) = pad_across_the_seam(&design);
    edited.vessels[0].nozzles[k].pad = None;
    model.edit(Edit::ReplaceDesign(edited)).unwrap();
    assert!(model.errors().0.is_empty(), "{:?}", model.errors());
}

/// A geometry failure names the part by its JSON path, never an ECS entity
/// (a pad's patch was named `103v0`); a design that cannot be built is refused
/// by `from_design` with every failure.
#[test]
fn a_failure_is_named_by_the_design_not_by_the_entity() {
    let design = column();
    let (edited, k) = pad_across_the_seam(&design);
    let err = Model::from_design(&edited, TessellationOptions::chord(1.0))
        .err()
        .expect("the design cannot be built");
    let ModelError::Geometry(failures) = &err else {
        panic!("expected a geometry refusal, got {err}");
    };
    assert!(!failures.is_empty());
    for v in failures {
        assert!(v.entity.starts_with("C-201/"), "{v}");
        assert_eq!(v.path, format!("vessels[0].nozzles[{k}]"), "{v}");
    }
}

/// `apply` then `update`: the update that cannot build puts back every edit
/// applied since the last update that built (here a valid move and the pad
/// across the seam), keeps the failures in `errors()` and counts them; the next
/// update builds nothing and reports nothing.
#[test]
fn apply_then_update_rolls_back_a_failed_build() {
    let design = column();
    let mut model = Model::from_design(&design, TessellationOptions::chord(1.0)).unwrap();
    model.take_changes();
    let before = model.design();
    let glb = write_glb(&model.scene()).unwrap();
    let mut moved = design.clone();
    moved.vessels[0].placement.rotation += 10.0;
    model.apply(Edit::ReplaceDesign(moved)).unwrap();
    let (edited, k) = pad_across_the_seam(&design);
    model.apply(Edit::ReplaceDesign(edited)).unwrap();
    let work = model.update();
    assert!(work.failures > 0, "{work:?}");
    let errors = &model.errors().0;
    assert_eq!(errors.len(), 1, "{errors:?}");
    assert_eq!(errors[0].1[0].path, format!("vessels[0].nozzles[{k}]"));
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
    let (edited, _) = pad_across_the_seam(&design);
    model.apply(Edit::ReplaceDesign(edited)).unwrap();
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
    assert!(
        changes.removed.contains(&format!("C-201/{n1}")),
        "{changes:?}"
    );
}
