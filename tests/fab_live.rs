//! Fabrication plans live in the model: every vessel's flat patterns and
//! process plan equal the pure `fab::plan_process` of its design after an
//! edit; an edit plans again only the vessel it touched, and moving a nozzle
//! develops again only its opening and plate(s) and lays out only the seams
//! of its part (work counters, pointer identity of the plates kept).

mod common;

use std::sync::Arc;

use common::examples::example;
use vesselcad::design;
use vesselcad::fab::{FabPlan, FabWork, ShopRules, plan_process, plan_vessel};
use vesselcad::mesh::TessellationOptions;
use vesselcad::model::{Edit, Model};

fn fresh_both(m: &Model, tag: &str) -> (FabPlan, vesselcad::fab::ProcessPlan) {
    plan_process(&m.design(), tag, &ShopRules::builtin()).unwrap()
}

fn fresh(m: &Model, tag: &str) -> vesselcad::fab::ProcessPlan {
    fresh_both(m, tag).1
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

/// What moving nozzle `mark` must do again from `before` to `after`:
/// (courses: those of its part and of parts whose course below changed;
/// plates: those holding it before or after, and those of courses that
/// changed).
fn expected_work(before: &FabPlan, after: &FabPlan, mark: &str) -> (usize, Vec<String>) {
    let host = |p: &FabPlan| {
        let c = p.openings.cuts.iter().find(|c| c.mark == mark)?;
        Some(p.developments.rolled[c.rolled].id.clone())
    };
    let hosts = [host(before), host(after)];
    let mut courses = 0;
    for part in &after.seams.parts {
        let id = &after.developments.rolled[part.rolled].id;
        let old = before
            .seams
            .parts
            .iter()
            .find(|o| &before.developments.rolled[o.rolled].id == id);
        if hosts.contains(&Some(id.clone())) || old.is_none_or(|o| o.below != part.below) {
            courses += part.courses.len();
        }
    }
    let mut plates = plates_with(before, mark);
    plates.extend(plates_with(after, mark));
    for p in &after.plates {
        let course = &after.seams.courses[p.course_index];
        let old = before.seams.courses.iter().find(|c| c.id == course.id);
        if old != Some(course) {
            plates.push(p.id.clone());
        }
    }
    plates.sort();
    plates.dedup();
    (courses, plates)
}

/// The plates of `plan` that hold nozzle `mark`.
fn plates_with(plan: &FabPlan, mark: &str) -> Vec<String> {
    plan.plates
        .iter()
        .filter(|p| p.openings.iter().any(|o| o.mark == mark))
        .map(|p| p.id.clone())
        .collect()
}

#[test]
fn moving_a_nozzle_develops_only_its_opening_and_plates_again() {
    let mut m =
        Model::from_design(&example("vertical-column"), TessellationOptions::chord(5.0)).unwrap();
    m.set_process_planning(Some(Arc::new(ShopRules::builtin())));
    let c = m.update();
    let tag = "C-201";
    let before = m.fab_plan(tag).unwrap().unwrap();
    assert_eq!(*before, fresh_both(&m, tag).0);
    assert!(before.plates.len() > 4, "{}", before.plates.len());
    assert_eq!(c.fab_plates_cut, before.plates.len() as u64);
    assert_eq!(c.fab_courses_laid_out, before.seams.courses.len() as u64);

    // Turn nozzle N1 by 2° about its course (a radial shell nozzle).
    let design = m.design();
    let k = design.vessels[0]
        .nozzles
        .iter()
        .position(|n| n.mark == "N1")
        .unwrap();
    let mut n = design.vessels[0].nozzles[k].clone();
    n.orientation += 2.0;
    let c = m
        .edit(Edit::SetNozzle {
            vessel: tag.into(),
            nozzle: n,
        })
        .unwrap();
    let after = m.fab_plan(tag).unwrap().unwrap();
    let (fresh_fab, fresh_process) = fresh_both(&m, tag);
    assert_eq!(*after, fresh_fab, "incremental = full");
    assert_eq!(*m.process_plan(tag).unwrap().unwrap(), fresh_process);
    let (courses, touched) = expected_work(&before, &after, "N1");
    assert_eq!(c.fab_parts_developed, 0, "{c:?}");
    assert_eq!(c.fab_openings_developed, 1, "{c:?}");
    assert_eq!(c.fab_courses_laid_out, courses as u64, "{c:?}");
    assert!(courses < after.seams.courses.len(), "{courses}");
    assert_eq!(c.fab_plates_cut, touched.len() as u64, "{c:?} {touched:?}");
    assert!(touched.len() < after.plates.len(), "{touched:?}");
    // Every other plate is the one kept from before, not a copy.
    for p in &after.plates {
        let old = before.plates.iter().find(|q| q.id == p.id).unwrap();
        assert_eq!(Arc::ptr_eq(old, p), !touched.contains(&p.id), "{}", p.id);
    }
    // The opening turned 2° about its course.
    let theta = |plan: &FabPlan| {
        plan.openings
            .cuts
            .iter()
            .find(|c| c.mark == "N1")
            .unwrap()
            .centre
            .x
    };
    let turned = (theta(&after) - theta(&before)).abs().to_degrees();
    assert!((turned - 2.0).abs() < 1e-9, "{turned}");
}

#[test]
fn plan_vessel_from_a_previous_plan_equals_a_fresh_plan() {
    // The pure function: for every example vessel, moving each course nozzle
    // in turn and planning from the previous plan gives the fresh plan.
    let rules = ShopRules::builtin();
    for name in ["small-plant", "vertical-column", "horizontal-drum"] {
        let mut d = example(name);
        for vi in 0..d.vessels.len() {
            let tag = d.vessels[vi].tag.clone();
            let Ok((mut previous, _)) = plan_process(&d, &tag, &rules) else {
                continue;
            };
            for ni in 0..d.vessels[vi].nozzles.len() {
                d.vessels[vi].nozzles[ni].orientation += 1.0;
                let resolved = match design::resolve(&d) {
                    Ok(r) => r,
                    Err(_) => {
                        d.vessels[vi].nozzles[ni].orientation -= 1.0;
                        continue;
                    }
                };
                let fresh = plan_vessel(&d.vessels[vi], vi, &resolved[vi], &rules.plates, None);
                let kept = plan_vessel(
                    &d.vessels[vi],
                    vi,
                    &resolved[vi],
                    &rules.plates,
                    Some(&previous),
                );
                match (fresh, kept) {
                    (Ok((f, all)), Ok((k, work))) => {
                        assert_eq!(f, k, "{name} {tag} nozzle {ni}");
                        let mark = &d.vessels[vi].nozzles[ni].mark;
                        let (courses, plates) = expected_work(&previous, &k, mark);
                        let on_course = k.openings.cuts.iter().any(|c| &c.mark == mark);
                        // A head nozzle's opening is mapped onto its blank
                        // again, when the turn moved it (a centre one's
                        // resolves the same).
                        let on_blank = k
                            .openings
                            .formed
                            .iter()
                            .any(|f| &f.mark == mark && f.blank.is_some())
                            && previous.resolved.nozzles[ni] != k.resolved.nozzles[ni];
                        let expected = FabWork {
                            parts: 0,
                            openings: usize::from(on_course || on_blank),
                            courses,
                            plates: plates.len(),
                        };
                        assert_eq!(work, expected, "{name} {tag} {mark}, fresh {all:?}");
                        previous = k;
                    }
                    (Err(f), Err(k)) => assert_eq!(f.to_string(), k.to_string()),
                    (f, k) => panic!(
                        "{name} {tag} nozzle {ni}: {:?} vs {:?}",
                        f.is_ok(),
                        k.is_ok()
                    ),
                }
            }
        }
    }
}
