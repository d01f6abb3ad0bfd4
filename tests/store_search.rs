//! Similar-design search against brute force, on every backend (SQLite always,
//! PostgreSQL when `$VESSELCAD_TEST_PG` is set): generated plants are imported,
//! and `--like` must return exactly the `n` nearest vessels by the documented
//! distance (computed here independently over every stored vessel, ties by
//! design and tag), with and without a `--where`; `--where` alone returns the
//! first matches by design and tag.

mod common;

use common::stores::test_stores;
use vesselcad::design::Units;
use vesselcad::plant::generate_plant;
use vesselcad::store::{Change, Features, Hit, Store};

/// The distance of `vesselcad::store::search`'s documentation, written out.
fn distance(a: &Features, like: &Features) -> f64 {
    let od = like.od.max(1.0);
    let length = like.length.max(1.0);
    let differ = |x: &str, y: &str, w: f64| if x == y { 0.0 } else { w };
    4.0 * (a.od - od).abs() / od
        + 2.0 * (a.length - length).abs() / length
        + 2.0 * (a.pressure - like.pressure).abs() / like.pressure.max(100.0)
        + (a.temperature - like.temperature).abs() / 200.0
        + differ(&a.kind, &like.kind, 1.0)
        + differ(&a.head, &like.head, 0.5)
        + differ(&a.material, &like.material, 0.5)
        + 0.1 * (a.nozzles - like.nozzles).abs() as f64
        + 0.25 * (a.max_nozzle - like.max_nozzle).abs() / like.max_nozzle.max(1.0)
}

/// Every stored vessel, with its design's name.
fn everything(store: &mut Store) -> Vec<Hit> {
    store.search_where("od > 0", 1_000_000).unwrap()
}

/// The `n` nearest of `all` to `like` among those `keep` accepts, by brute force.
fn nearest(all: &[Hit], like: &Features, n: usize, keep: impl Fn(&Hit) -> bool) -> Vec<Hit> {
    let mut ranked: Vec<(f64, &Hit)> = all
        .iter()
        .filter(|h| keep(h))
        .map(|h| (distance(&h.features, like), h))
        .collect();
    ranked.sort_by(|a, b| {
        a.0.total_cmp(&b.0)
            .then_with(|| a.1.design.cmp(&b.1.design))
            .then_with(|| a.1.features.tag.cmp(&b.1.features.tag))
    });
    ranked
        .into_iter()
        .take(n)
        .map(|(d, h)| Hit {
            distance: Some(d),
            ..h.clone()
        })
        .collect()
}

fn same(found: &[Hit], expected: &[Hit], what: &str) {
    let names = |hits: &[Hit]| -> Vec<(String, String)> {
        hits.iter()
            .map(|h| (h.design.clone(), h.features.tag.clone()))
            .collect()
    };
    // Equal distances may come back in either order only if they differ in the
    // last bits; the names must agree where the distances do.
    assert_eq!(found.len(), expected.len(), "{what}");
    for (f, e) in found.iter().zip(expected) {
        let (df, de) = (f.distance.unwrap(), e.distance.unwrap());
        assert!((df - de).abs() < 1e-9, "{what}: distance {df} vs {de}");
    }
    assert_eq!(names(found), names(expected), "{what}");
}

/// Wanted vessels: stored ones, and stored ones moved off in every feature.
fn probes(all: &[Hit]) -> Vec<Features> {
    let mut out = Vec::new();
    for (k, h) in all.iter().step_by(97).enumerate() {
        out.push(h.features.clone());
        let mut moved = h.features.clone();
        let s = 1.0 + 0.07 * ((k % 5) as f64 - 2.0);
        moved.od *= s;
        moved.length *= 2.0 - s;
        moved.pressure = moved.pressure * s + 35.0;
        moved.temperature += 40.0 * ((k % 3) as f64 - 1.0);
        moved.nozzles += (k % 4) as i64;
        if k % 2 == 0 {
            moved.kind = "none of those".into();
        }
        out.push(moved);
    }
    // One far from everything: only the second look (or all) can answer it.
    let mut far = all[0].features.clone();
    far.od = 20_000.0;
    far.pressure = 9_000.0;
    out.push(far);
    out
}

#[test]
fn like_returns_exactly_the_nearest_by_the_documented_distance() {
    for t in test_stores() {
        let mut store = Store::open(&t.location).unwrap();
        for p in 0..3 {
            let change = Change {
                author: "test".into(),
                message: "generated".into(),
            };
            let design = generate_plant(300, 40 + p).unwrap();
            store
                .import(&format!("plant-{p}"), &design, Units::Mm, &change)
                .unwrap();
        }
        let all = everything(&mut store);
        assert_eq!(all.len(), 900, "{}", t.label);
        for (k, like) in probes(&all).iter().enumerate() {
            for n in [1, 10, 25] {
                let found = store.search_like(like, None, n).unwrap();
                let expected = nearest(&all, like, n, |_| true);
                same(&found, &expected, &format!("{} probe {k} n {n}", t.label));
            }
            let found = store
                .search_like(like, Some("pressure >= 500"), 10)
                .unwrap();
            let expected = nearest(&all, like, 10, |h| h.features.pressure >= 500.0);
            same(&found, &expected, &format!("{} probe {k} where", t.label));
        }
        assert!(
            store
                .search_like(&all[0].features, None, 0)
                .unwrap()
                .is_empty()
        );
    }
}

#[test]
fn where_returns_the_first_matches_by_design_and_tag() {
    for t in test_stores() {
        let mut store = Store::open(&t.location).unwrap();
        let change = Change {
            author: "test".into(),
            message: "generated".into(),
        };
        let design = generate_plant(400, 7).unwrap();
        store.import("plant", &design, Units::Mm, &change).unwrap();
        let all = everything(&mut store);
        let found = store
            .search_where("od between 2000 and 2600 and pressure >= 1000", 10)
            .unwrap();
        let mut expected: Vec<&Hit> = all
            .iter()
            .filter(|h| {
                let f = &h.features;
                (2000.0..=2600.0).contains(&f.od) && f.pressure >= 1000.0
            })
            .collect();
        expected.sort_by(|a, b| a.features.tag.cmp(&b.features.tag));
        let tags = |hits: Vec<&Hit>| -> Vec<String> {
            hits.iter().map(|h| h.features.tag.clone()).collect()
        };
        assert!(!found.is_empty(), "{}", t.label);
        assert_eq!(
            tags(found.iter().collect()),
            tags(expected.into_iter().take(10).collect()),
            "{}",
            t.label
        );
    }
}
