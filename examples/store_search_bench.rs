//! Similar-design search over 100,000 stored vessels: generated plants imported
//! into a SQLite store (or the PostgreSQL URL given as the second argument), then
//! `--like` and `--where` queries timed. The issue's target is ≤ 50 ms a query.
//!
//! ```text
//! cargo run --profile test --example store_search_bench -- [VESSELS] [STORE]
//! ```

use std::time::Instant;

use vesselcad::design::Units;
use vesselcad::plant::generate_plant;
use vesselcad::store::{Change, Features, Store};

fn main() {
    let mut args = std::env::args().skip(1);
    let total: usize = args.next().and_then(|a| a.parse().ok()).unwrap_or(100_000);
    let dir = tempfile::tempdir().expect("temp dir");
    let location = args
        .next()
        .unwrap_or_else(|| dir.path().join("bench.db").display().to_string());
    let mut store = Store::open(&location).expect("store");
    let per_plant = 4000.min(total);
    let plants = total.div_ceil(per_plant);
    let started = Instant::now();
    let mut probes = Vec::new();
    for p in 0..plants {
        let design = generate_plant(per_plant, 1000 + p as u64).expect("plant");
        probes.extend(design.vessels.iter().step_by(997).map(Features::of));
        let change = Change {
            author: "bench".into(),
            message: "generated".into(),
        };
        store
            .import(&format!("plant-{p}"), &design, Units::Mm, &change)
            .expect("import");
    }
    let stats = store.stats().expect("stats");
    println!(
        "imported {} vessels in {} plants in {:.1} s",
        stats.vessels,
        plants,
        started.elapsed().as_secs_f64()
    );
    let mut times = Vec::new();
    for probe in probes.iter().take(40) {
        let t = Instant::now();
        let hits = store.search_like(probe, None, 10).expect("search");
        times.push(t.elapsed().as_secs_f64() * 1e3);
        assert_eq!(hits[0].distance, Some(0.0));
    }
    report("--like, -n 10", &mut times);
    let mut times = Vec::new();
    for _ in 0..20 {
        let t = Instant::now();
        store
            .search_where("od between 2000 and 2600 and pressure >= 1000", 10)
            .expect("search");
        times.push(t.elapsed().as_secs_f64() * 1e3);
    }
    report("--where od between … and pressure >= …, -n 10", &mut times);
    let mut times = Vec::new();
    for probe in probes.iter().take(20) {
        let t = Instant::now();
        store
            .search_like(probe, Some("pressure >= 500"), 10)
            .expect("search");
        times.push(t.elapsed().as_secs_f64() * 1e3);
    }
    report("--like with --where pressure >= 500", &mut times);
}

fn report(what: &str, times: &mut [f64]) {
    times.sort_by(f64::total_cmp);
    let median = times[times.len() / 2];
    let worst = times[times.len() - 1];
    println!(
        "{what}: median {median:.1} ms, worst {worst:.1} ms over {} queries",
        times.len()
    );
}
