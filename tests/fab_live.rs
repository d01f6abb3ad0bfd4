//! Process plans live in the model: every vessel's plan equals the pure
//! `fab::process_plan` of its design after an edit, and an edit plans again only
//! the vessel it touched (work counters).

mod common;

use std::sync::Arc;

use common::examples::example;
use vesselcad::design;
use vesselcad::fab::{ShopRules, process_plan};
use vesselcad::mesh::TessellationOptions;
use vesselcad::model::{Edit, Model};

fn fresh(m: &Model, tag: &str) -> vesselcad::fab::ProcessPlan {
    let d = m.design();
    let resolved = design::resolve(&d).unwrap();
    let i = d.vessels.iter().position(|v| v.tag == tag).unwrap();
    process_plan(&d.vessels[i], &resolved[i], &ShopRules::builtin()).unwrap()
}

#[test]
fn a_nozzle_edit_plans_its_vessel_again_and_no_other() {
    let mut m =
        Model::from_design(&example("small-plant"), TessellationOptions::chord(5.0)).unwrap();
    assert!(
        m.process_plan("V-101").is_none(),
        "not kept until asked for"
    );
    m.set_process_planning(Some(Arc::new(ShopRules::builtin())));
    let c = m.update();
    let tags: Vec<String> = m.design().vessels.iter().map(|v| v.tag.clone()).collect();
    assert_eq!(c.process_plans, tags.len() as u64);
    for tag in &tags {
        assert_eq!(
            *m.process_plan(tag).unwrap().unwrap(),
            fresh(&m, tag),
            "{tag}"
        );
    }
    let before: Vec<_> = tags
        .iter()
        .map(|t| m.process_plan(t).unwrap().unwrap())
        .collect();

    // Move a nozzle of V-101 up the course: only V-101 is planned again, and
    // its nozzle weld follows.
    let mut n = m.design().vessels[0].nozzles[1].clone();
    n.projection += 100.0;
    let mark = n.mark.clone();
    let c = m
        .edit(Edit::SetNozzle {
            vessel: "V-101".into(),
            nozzle: n,
        })
        .unwrap();
    assert_eq!(c.process_plans, 1, "{c:?}");
    let after = m.process_plan("V-101").unwrap().unwrap();
    assert_eq!(*after, fresh(&m, "V-101"));
    let pipe = |p: &vesselcad::fab::ProcessPlan| {
        p.bom
            .lines
            .iter()
            .find(|l| l.item == mark && l.kind == "pipe")
            .unwrap()
            .size
            .clone()
    };
    assert_ne!(
        pipe(&after),
        pipe(&before[0]),
        "the neck's cut length follows"
    );
    for (tag, old) in tags.iter().zip(&before).skip(1) {
        assert!(
            Arc::ptr_eq(old, &m.process_plan(tag).unwrap().unwrap()),
            "{tag}"
        );
    }
    // Nothing touched, nothing planned.
    assert_eq!(m.update().process_plans, 0);
    // Turning planning off drops the plans from view.
    m.set_process_planning(None);
    assert!(m.process_plan("V-101").is_none());
}
