//! Drawing views: exact silhouettes, hidden-line classification and the
//! incremental Project stage (work counters, agreement with a fresh build).

mod common;

use common::examples::example;
use std::sync::Arc;

use vesselcad::design::{NozzleDesign, parse};
use vesselcad::drawing::vessel_views;
use vesselcad::mesh::TessellationOptions;
use vesselcad::model::{Edit, Model};
use vesselcad::project::{EntityView, LineKind, View, ViewKind};

fn options() -> TessellationOptions {
    TessellationOptions::chord(0.5)
}

/// A vertical drum with 2:1 heads; nozzles N1 at north (behind the shell in the
/// front view) and N2 at south (in front of it).
const DRUM: &str = r#"{
  "format": "vesselcad/1",
  "vessels": [{
    "tag": "D-1", "kind": "vertical",
    "parts": [
      { "head": { "id": "H1", "shape": "ellipsoidal", "ratio": 2, "straight_flange": 50 } },
      { "shell": { "id": "S1", "od": 2000, "length": 3000 } },
      { "head": { "id": "H2", "shape": "ellipsoidal", "ratio": 2, "straight_flange": 50 } }
    ],
    "nozzles": [
      { "mark": "N1", "size": 4, "rating": 150, "host": "S1", "orientation": 0, "elevation": 1500, "projection": 1400 },
      { "mark": "N2", "size": 4, "rating": 150, "host": "S1", "orientation": 180, "elevation": 1500, "projection": 1400 }
    ]
  }]
}"#;

fn entity<'a>(view: &'a View, id: &str) -> &'a EntityView {
    view.entities
        .iter()
        .find(|e| e.id == id)
        .unwrap_or_else(|| panic!("no entity {id} in the {:?} view", view.projection.kind))
}

fn extent(l: &vesselcad::project::ViewLine) -> f64 {
    let (lo, hi) = l
        .points
        .iter()
        .fold((l.points[0], l.points[0]), |(lo, hi), p| {
            (lo.min(*p), hi.max(*p))
        });
    (hi - lo).length()
}

fn count(e: &EntityView, kind: LineKind) -> usize {
    e.lines.iter().filter(|l| l.kind == kind).count()
}

#[test]
fn a_two_to_one_head_shows_an_exact_half_ellipse() {
    let model = Model::from_design(&parse(DRUM).unwrap(), options()).unwrap();
    let views = vessel_views(&model, "D-1").unwrap();
    let front = &views[0];
    assert_eq!(front.projection.kind, ViewKind::Front);
    // The datum is the bottom head's tangent line (where its dome begins); the
    // course runs from 50 to 3050 between the straight flanges. Top head: dome
    // base at z = 3100, semi-axes 1000 across and 500 up; bottom head: dome base
    // at z = 0, opening downwards.
    for (id, base, up) in [("D-1/H2", 3100.0, 1.0), ("D-1/H1", 0.0, -1.0)] {
        let head = entity(front, id);
        let mut on_dome = 0;
        let (mut min_x, mut max_x, mut peak) = (f64::MAX, f64::MIN, 0.0f64);
        for line in head.lines.iter().filter(|l| l.kind == LineKind::Visible) {
            for p in &line.points {
                let h = (p.y - base) * up;
                if h <= 1e-6 {
                    continue;
                }
                on_dome += 1;
                let e = (p.x / 1000.0).powi(2) + (h / 500.0).powi(2);
                assert!(
                    (e - 1.0).abs() < 1e-9,
                    "{id}: outline point {p} is off the ellipse (x/a)² + (h/b)² = {e}"
                );
                min_x = min_x.min(p.x);
                max_x = max_x.max(p.x);
                peak = peak.max(h);
            }
        }
        assert!(
            on_dome >= 40,
            "{id}: only {on_dome} outline points on the dome"
        );
        assert!(
            min_x < -999.0 && max_x > 999.0,
            "{id}: outline spans x {min_x}..{max_x}"
        );
        assert!(
            (peak - 500.0).abs() < 1e-9,
            "{id}: the outline reaches {peak}, not the pole"
        );
    }
}

#[test]
fn a_nozzle_behind_the_shell_is_hidden_and_one_in_front_is_visible() {
    let model = Model::from_design(&parse(DRUM).unwrap(), options()).unwrap();
    let views = vessel_views(&model, "D-1").unwrap();
    let front = &views[0];
    let behind = entity(front, "D-1/N1");
    let ahead = entity(front, "D-1/N2");
    assert!(count(behind, LineKind::Hidden) > 5);
    assert_eq!(
        count(behind, LineKind::Visible),
        0,
        "N1 is behind the shell"
    );
    // N2 is seen face-on: its flange face is in front of everything (visible);
    // its neck, seen end-on behind the flange, is hidden by the flange.
    assert!(count(ahead, LineKind::Visible) > 3);
    let widest = ahead
        .lines
        .iter()
        .filter(|l| l.kind != LineKind::Centre)
        .max_by(|a, b| extent(a).total_cmp(&extent(b)))
        .unwrap();
    assert_eq!(
        widest.kind,
        LineKind::Visible,
        "N2's flange outline is in front"
    );
    // Both are seen end-on: their axes are crosses.
    assert_eq!(count(behind, LineKind::Centre), 2);
    // The shell: its hole for N2 is visible, the one for N1 hidden, and its back
    // tangent-line halves are hidden.
    let shell = entity(front, "D-1/S1");
    assert!(count(shell, LineKind::Hidden) >= 3);
    // Plan view (from above): both nozzles stick out of the shell, visible there.
    let plan = &views[1];
    for id in ["D-1/N1", "D-1/N2"] {
        assert!(
            count(entity(plan, id), LineKind::Visible) > 5,
            "{id} in plan"
        );
    }
    // In plan the top head hides the bottom head except where their tangent-line
    // circles coincide with the outline (r = 1000).
    let bottom = entity(plan, "D-1/H1");
    for l in bottom.lines.iter().filter(|l| l.kind == LineKind::Visible) {
        for p in &l.points {
            assert!(
                (p.length() - 1000.0).abs() < 1.0,
                "H1 visible in plan at {p}"
            );
        }
    }
    assert!(count(bottom, LineKind::Hidden) > 0);
}

/// Every view's entity views, by (view, id), as shared pointers.
fn snapshot(model: &Model, tag: &str) -> Vec<(ViewKind, String, Arc<EntityView>)> {
    vessel_views(model, tag)
        .unwrap()
        .into_iter()
        .flat_map(|v| {
            let kind = v.projection.kind;
            v.entities.into_iter().map(move |e| (kind, e.id.clone(), e))
        })
        .collect()
}

/// Asserts two views agree: same lines of the same kinds, points within `tol`.
fn assert_close(a: &EntityView, b: &EntityView, tol: f64, what: &str) {
    assert_eq!(a.lines.len(), b.lines.len(), "{what}: line count");
    for (la, lb) in a.lines.iter().zip(&b.lines) {
        assert_eq!(la.kind, lb.kind, "{what}: line kind");
        assert_eq!(la.points.len(), lb.points.len(), "{what}: points");
        for (p, q) in la.points.iter().zip(&lb.points) {
            assert!((*p - *q).length() <= tol, "{what}: {p} vs {q}");
        }
    }
}

#[test]
fn moving_one_nozzle_rebuilds_its_views_and_its_hosts_not_the_vessels() {
    let mut model = Model::from_design(&example("vertical-column"), options()).unwrap();
    let before = snapshot(&model, "C-201");
    let members = before.len() / 4;
    assert_eq!(members, 16, "6 parts and 10 nozzles");
    assert_eq!(model.update().views_rebuilt, 0, "nothing changed");
    let design = model.design();
    let mut n8: NozzleDesign = design.vessels[0]
        .nozzles
        .iter()
        .find(|n| n.mark == "N8")
        .cloned()
        .unwrap();
    n8.elevation = Some(20300.0);
    let counters = model
        .edit(Edit::SetNozzle {
            vessel: "C-201".into(),
            nozzle: n8,
        })
        .unwrap();
    let after = snapshot(&model, "C-201");
    let rebuilt: Vec<(ViewKind, &str)> = before
        .iter()
        .zip(&after)
        .filter(|(b, a)| !Arc::ptr_eq(&b.2, &a.2))
        .map(|(_, a)| (a.0, a.1.as_str()))
        .collect();
    assert_eq!(counters.views_rebuilt, rebuilt.len() as u64);
    for view in ViewKind::ALL {
        for id in ["C-201/N8", "C-201/S2"] {
            assert!(
                rebuilt.contains(&(view, id)),
                "{id} not rebuilt in {view:?}"
            );
        }
    }
    for id in [
        "C-201/SK", "C-201/H1", "C-201/S1", "C-201/N4", "C-201/N5", "C-201/N6",
    ] {
        assert!(
            !rebuilt.iter().any(|(_, r)| *r == id),
            "{id} is far from N8 but was rebuilt"
        );
    }
    assert!(
        rebuilt.len() <= 4 * members / 3,
        "{} of {} entity views rebuilt: {rebuilt:?}",
        rebuilt.len(),
        4 * members
    );
    // The incremental views agree with a fresh build of the edited design.
    let fresh = Model::from_design(&model.design(), options()).unwrap();
    for ((kind, id, a), (_, _, b)) in after.iter().zip(&snapshot(&fresh, "C-201")) {
        assert_close(a, b, 1.0, &format!("{id} in {kind:?}"));
    }
}

#[test]
fn turning_a_vessel_in_plan_rebuilds_all_its_views_and_moving_it_none() {
    let mut model = Model::from_design(&example("vertical-column"), options()).unwrap();
    let mut placement = model.design().vessels[0].placement;
    placement.position[0] += 5000.0;
    let c = model
        .edit(Edit::MoveVessel {
            tag: "C-201".into(),
            placement,
        })
        .unwrap();
    assert_eq!(c.views_rebuilt, 0, "views are in the vessel's frame");
    placement.rotation = 30.0;
    let c = model
        .edit(Edit::MoveVessel {
            tag: "C-201".into(),
            placement,
        })
        .unwrap();
    assert_eq!(c.views_rebuilt, 64, "the plan turned: every view changes");
}

#[test]
fn a_shell_silhouette_is_its_generators_cut_at_the_openings_on_it() {
    let model = Model::from_design(&example("horizontal-drum"), options()).unwrap();
    let views = vessel_views(&model, "V-101").unwrap();
    let shell = entity(&views[0], "V-101/S1");
    // Course from z = 50 to 7250 (after H1's straight flange), radius 1200: its
    // silhouettes in the front elevation are the generators y = ±1200.
    let generators: Vec<&vesselcad::project::ViewLine> = shell
        .lines
        .iter()
        .filter(|l| {
            l.kind == LineKind::Visible
                && l.points.iter().all(|p| (p.y.abs() - 1200.0).abs() < 1e-6)
        })
        .collect();
    let covered = |y: f64| -> Vec<(f64, f64)> {
        let mut spans: Vec<(f64, f64)> = generators
            .iter()
            .filter(|l| (l.points[0].y - y).abs() < 1e-6)
            .map(|l| {
                let xs = l.points.iter().map(|p| p.x);
                (
                    xs.clone().fold(f64::MAX, f64::min),
                    xs.fold(f64::MIN, f64::max),
                )
            })
            .collect();
        spans.sort_by(|a, b| a.0.total_cmp(&b.0));
        spans
    };
    let bottom = covered(-1200.0);
    let top = covered(1200.0);
    assert!(
        !bottom.is_empty() && !top.is_empty(),
        "{:?}",
        shell.lines.len()
    );
    assert!((bottom[0].0 - 50.0).abs() < 1e-6 && (bottom.last().unwrap().1 - 7250.0).abs() < 1e-6);
    assert!((top[0].0 - 50.0).abs() < 1e-6 && (top.last().unwrap().1 - 7250.0).abs() < 1e-6);
    // N1 at x = 800 on the top has a 420 mm pad: the host's opening there is the
    // pad's outer loop, x = 590..1010 on the top line; the generator stops there.
    let ends: Vec<f64> = top.iter().flat_map(|(a, b)| [*a, *b]).collect();
    for x in [590.0, 1010.0] {
        assert!(
            ends.iter().any(|e| (e - x).abs() < 0.5),
            "no end at {x}: {top:?}"
        );
    }
    for (a, b) in &top {
        assert!(
            *b <= 590.5 || *a >= 1009.5,
            "top generator crosses N1's pad: {a}..{b}"
        );
    }
}

/// A model that does not keep views (a plant build, a simulation) builds none and
/// says so when asked for a drawing; turning views on builds them on the next
/// update, the same as a model that kept them from the start.
#[test]
fn views_can_be_left_off_and_turned_on_later() {
    use vesselcad::drawing::{DrawingError, SheetOptions, sheet_svg};
    use vesselcad::model::Views;
    let design = example("vertical-column");
    let mut model = Model::new(options()).unwrap();
    model.set_views(Views::Off);
    model.apply(Edit::ReplaceDesign(design.clone())).unwrap();
    let counters = model.update();
    assert!(counters.meshes_rebuilt > 0);
    assert_eq!(counters.views_rebuilt, 0);
    let tag = design.vessels[0].tag.clone();
    assert!(matches!(
        sheet_svg(&model, &tag, &SheetOptions::default()),
        Err(DrawingError::NotBuilt { .. })
    ));
    model.set_views(Views::Kept);
    let counters = model.update();
    assert!(counters.views_rebuilt > 0);
    assert_eq!(
        counters.meshes_rebuilt, 0,
        "turning views on re-meshes nothing"
    );
    let kept = Model::from_design(&design, options()).unwrap();
    assert_eq!(
        sheet_svg(&model, &tag, &SheetOptions::default()).unwrap(),
        sheet_svg(&kept, &tag, &SheetOptions::default()).unwrap()
    );
}

/// Whether every entity view of `tag` is the same `Arc` in both snapshots.
fn untouched(before: &[(ViewKind, String, Arc<EntityView>)], model: &Model, tag: &str) -> bool {
    let after = snapshot(model, tag);
    before.len() == after.len()
        && before
            .iter()
            .zip(&after)
            .all(|(b, a)| Arc::ptr_eq(&b.2, &a.2))
}

#[test]
fn in_a_plant_an_edit_rebuilds_only_its_vessels_views() {
    use vesselcad::model::Views;
    let tags = ["V-101", "V-102", "C-201", "TK-301"];
    let mut model = Model::from_design(&example("small-plant"), options()).unwrap();
    let before: Vec<_> = tags.iter().map(|t| snapshot(&model, t)).collect();
    assert_eq!(model.update().views_rebuilt, 0, "nothing changed");
    // A nozzle removed: its footprint frees the lines behind it, and its views go.
    let counters = model
        .edit(Edit::RemoveNozzle {
            vessel: "C-201".into(),
            mark: "N7".into(),
        })
        .unwrap();
    assert!(counters.views_rebuilt > 0);
    for (i, tag) in tags.iter().enumerate().filter(|(_, t)| **t != "C-201") {
        assert!(untouched(&before[i], &model, tag), "{tag} was rebuilt");
    }
    let after = snapshot(&model, "C-201");
    assert_eq!(after.len(), before[2].len() - 4, "N7's four views are gone");
    let fresh = Model::from_design(&model.design(), options()).unwrap();
    for ((kind, id, a), (_, _, b)) in after.iter().zip(&snapshot(&fresh, "C-201")) {
        assert_close(a, b, 1.0, &format!("{id} in {kind:?}"));
    }
    // A nozzle moved while views are off: turning them on catches up with it
    // and leaves the other vessels as they were.
    let before: Vec<_> = tags.iter().map(|t| snapshot(&model, t)).collect();
    model.set_views(Views::Off);
    let design = model.design();
    let mut n5 = design.vessels[2].nozzles[4].clone();
    assert_eq!(n5.mark, "N5");
    n5.elevation = Some(2500.0);
    model
        .edit(Edit::SetNozzle {
            vessel: "C-201".into(),
            nozzle: n5,
        })
        .unwrap();
    model.set_views(Views::Kept);
    assert!(model.update().views_rebuilt > 0);
    for (i, tag) in tags.iter().enumerate().filter(|(_, t)| **t != "C-201") {
        assert!(untouched(&before[i], &model, tag), "{tag} was rebuilt");
    }
    let fresh = Model::from_design(&model.design(), options()).unwrap();
    let after = snapshot(&model, "C-201");
    assert_eq!(after.len(), before[2].len());
    for ((kind, id, a), (_, _, b)) in after.iter().zip(&snapshot(&fresh, "C-201")) {
        assert_close(a, b, 1.0, &format!("{id} in {kind:?}"));
    }
    assert_eq!(model.update().views_rebuilt, 0, "nothing changed since");
}
