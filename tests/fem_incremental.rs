//! The FE mesh is incremental like the render meshes: a build through a
//! `FemCache` meshes only the pieces (an envelope part with its nozzles,
//! saddles and pads; the skirt) whose inputs an edit changed, takes the others
//! as they were, and the welded mesh equals a from-scratch mesh of the edited
//! design node for node and element for element. A load edit meshes nothing.

mod common;

use std::sync::Arc;

use common::examples::example;
use common::fem::assert_good;
use vesselcad::calc::MaterialTable;
use vesselcad::design::{Design, PartDesign, resolve};
use vesselcad::fem::{
    FeMesh, FemCache, FemOptions, LoadCase, build_envelope, build_envelope_cached, vessel_model,
    vessel_model_cached,
};

/// The mesh of vessel `tag` of `design` through `cache`.
fn cached(design: &Design, tag: &str, cache: &mut FemCache) -> FeMesh {
    let resolved = resolve(design).expect("valid design");
    let i = design
        .vessels
        .iter()
        .position(|v| v.tag == tag)
        .expect("tag");
    build_envelope_cached(
        &design.vessels[i],
        &resolved[i],
        &FemOptions::default(),
        cache,
    )
    .expect("mesh")
}

/// The mesh of vessel `tag` of `design`, every piece meshed afresh.
fn fresh(design: &Design, tag: &str) -> FeMesh {
    let resolved = resolve(design).expect("valid design");
    let i = design
        .vessels
        .iter()
        .position(|v| v.tag == tag)
        .expect("tag");
    build_envelope(&design.vessels[i], &resolved[i], &FemOptions::default()).expect("mesh")
}

/// The column's pieces: its heads, courses, reducer, centre necks and skirt.
const COLUMN: [&str; 8] = ["H1", "S1", "R1", "S2", "H2", "N3", "N4", "SK"];

fn column_cache() -> (Design, FemCache, FeMesh) {
    let design = example("vertical-column");
    let mut cache = FemCache::new();
    let mesh = cached(&design, "C-201", &mut cache);
    let c = cache.counters();
    let mut names = c.meshed_pieces.clone();
    names.sort();
    let mut want: Vec<String> = COLUMN.iter().map(|s| s.to_string()).collect();
    want.sort();
    assert_eq!((c.meshed, c.reused, names), (COLUMN.len(), 0, want));
    assert_eq!(
        mesh,
        fresh(&design, "C-201"),
        "a cold cache builds the mesh"
    );
    (design, cache, mesh)
}

/// The pieces of `names`, as `cache` holds them now.
fn held(cache: &FemCache, names: &[&str]) -> Vec<Arc<vesselcad::fem::piece::Piece>> {
    names
        .iter()
        .map(|n| cache.piece("C-201", n).expect("piece held"))
        .collect()
}

#[test]
fn moving_a_course_nozzle_remeshes_that_course_only() {
    let (mut design, mut cache, before) = column_cache();
    let others: Vec<&str> = COLUMN.iter().copied().filter(|&n| n != "S2").collect();
    let kept = held(&cache, &others);
    let nozzle = design.vessels[0]
        .nozzles
        .iter_mut()
        .find(|n| n.mark == "N2")
        .expect("N2 on S2");
    nozzle.orientation = 250.0;
    let after = cached(&design, "C-201", &mut cache);
    let c = cache.counters();
    assert_eq!(
        (c.meshed, c.reused, c.meshed_pieces.clone()),
        (1, COLUMN.len() - 1, vec!["S2".to_string()]),
        "only the nozzle's course (with its necks and pads) is re-meshed"
    );
    // The others are the very pieces meshed before, bit for bit.
    for (name, (a, b)) in others.iter().zip(kept.iter().zip(held(&cache, &others))) {
        assert!(Arc::ptr_eq(a, &b), "{name} was re-meshed");
    }
    assert_ne!(after, before, "the edit moved the nozzle");
    assert_eq!(
        after,
        fresh(&design, "C-201"),
        "incremental = from scratch, node for node"
    );
    assert_good("C-201 after N2 moved", &after);
}

#[test]
fn a_thicker_course_remeshes_its_junctions_not_the_far_parts() {
    let (mut design, mut cache, _) = column_cache();
    for part in &mut design.vessels[0].parts {
        if let PartDesign::Shell(s) = part
            && s.id == "S2"
        {
            s.thickness = Some(11.0);
        }
    }
    let after = cached(&design, "C-201", &mut cache);
    let c = cache.counters().clone();
    assert!(c.meshed_pieces.contains(&"S2".to_string()), "{c:?}");
    for far in ["H1", "N4", "S1", "SK"] {
        assert!(
            !c.meshed_pieces.contains(&far.to_string()),
            "{far} re-meshed: {c:?}"
        );
    }
    assert_eq!(c.meshed + c.reused, COLUMN.len());
    assert_eq!(after, fresh(&design, "C-201"));
}

#[test]
fn a_pressure_edit_remeshes_nothing() {
    let design = example("horizontal-drum");
    let table = MaterialTable::builtin();
    let options = FemOptions::default();
    let mut cache = FemCache::new();
    let before = vessel_model_cached(
        &design,
        "V-101",
        &options,
        LoadCase::Design,
        &table,
        &mut cache,
    )
    .expect("model");
    let pieces = cache.counters().meshed;
    // Its heads, its course (with its saddles and course nozzles) and the
    // manway's neck on a head's centre.
    let mut names = cache.counters().meshed_pieces.clone();
    names.sort();
    assert_eq!(names, ["H1", "H2", "M1", "S1"].map(String::from).to_vec());
    let mut edited = design.clone();
    let old = edited.vessels[0]
        .design
        .pressure
        .expect("a design pressure");
    edited.vessels[0].design.pressure = Some(2.0 * old);
    let after = vessel_model_cached(
        &edited,
        "V-101",
        &options,
        LoadCase::Design,
        &table,
        &mut cache,
    )
    .expect("model");
    let c = cache.counters();
    assert_eq!((c.meshed, c.reused), (0, pieces), "{c:?}");
    let scratch =
        vessel_model(&edited, "V-101", &options, LoadCase::Design, &table).expect("model");
    assert_eq!(after.mesh, scratch.mesh);
    assert_eq!(after.mesh, before.mesh);
    assert_eq!(after.pressure, scratch.pressure, "the loads are the edit's");
    assert_ne!(after.pressure, before.pressure);
}
