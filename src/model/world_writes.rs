//! Writes past the model's edits. Only code inside the model can write its world
//! (`Model::world` and `Model::query` are read-only, a doctest on `query` shows a
//! mutable query does not compile); this test writes a parameter from inside, as
//! a bug in the model would, and checks the Validate stage still resolves the
//! vessel from the world rather than from the resolution the edit's check left.

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
