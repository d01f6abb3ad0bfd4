//! An edit is one transaction with its geometry (issue 30 §1): an edit that
//! passes every rule but whose geometry cannot be built is refused by
//! `Model::edit`, naming the part or nozzle by its JSON path, and leaves the
//! model as it was — design, meshes, errors and change log.

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
/// (a pad's patch was named `103v0`).
#[test]
fn a_failure_is_named_by_the_design_not_by_the_entity() {
    let design = column();
    let (edited, k) = pad_across_the_seam(&design);
    let model = Model::from_design(&edited, TessellationOptions::chord(1.0)).unwrap();
    let errors = &model.errors().0;
    assert!(!errors.is_empty());
    for (label, violations) in errors {
        assert!(label.starts_with("C-201/"), "{label}");
        for v in violations {
            assert_eq!(v.path, format!("vessels[0].nozzles[{k}]"), "{v}");
        }
    }
}
