//! Similar-design search over 100,000 stored vessels: generated plants imported
//! into a SQLite store (or the PostgreSQL URL given as the second argument), then
//! `--like` and `--where` queries timed. The issue's target is ≤ 50 ms a query.
//! Each query is timed twice: wall clock, and the CPU time of this thread (from
//! `/proc/thread-self/schedstat`), which on a SQLite store is the query's own
//! work, the figure a busy machine does not inflate by waiting.
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
    let mut times = Times::default();
    for probe in probes.iter().take(40) {
        let hits = times.time(|| store.search_like(probe, None, 10).expect("search"));
        assert_eq!(hits[0].distance, Some(0.0));
    }
    times.report("--like, -n 10");
    let mut times = Times::default();
    for _ in 0..20 {
        times.time(|| {
            store
                .search_where("od between 2000 and 2600 and pressure >= 1000", 10)
                .expect("search")
        });
    }
    times.report("--where od between … and pressure >= …, -n 10");
    let mut times = Times::default();
    for probe in probes.iter().take(20) {
        times.time(|| {
            store
                .search_like(probe, Some("pressure >= 500"), 10)
                .expect("search")
        });
    }
    times.report("--like with --where pressure >= 500");
}

/// Wall-clock and thread-CPU milliseconds of each query.
#[derive(Default)]
struct Times {
    wall: Vec<f64>,
    cpu: Vec<f64>,
}

impl Times {
    fn time<T>(&mut self, query: impl FnOnce() -> T) -> T {
        let (c, t) = (thread_cpu_ms(), Instant::now());
        let out = query();
        self.wall.push(t.elapsed().as_secs_f64() * 1e3);
        if let (Some(a), Some(b)) = (c, thread_cpu_ms()) {
            self.cpu.push(b - a);
        }
        out
    }

    fn report(mut self, what: &str) {
        let summary = |v: &mut Vec<f64>| {
            v.sort_by(f64::total_cmp);
            (v[v.len() / 2], v[v.len() - 1])
        };
        let (median, worst) = summary(&mut self.wall);
        print!("{what}: wall median {median:.1} ms, worst {worst:.1} ms");
        if self.cpu.len() == self.wall.len() {
            let (median, worst) = summary(&mut self.cpu);
            print!("; thread CPU median {median:.1} ms, worst {worst:.1} ms");
        }
        println!(" over {} queries", self.wall.len());
    }
}

/// CPU time this thread has run, ms (Linux's scheduler statistics).
fn thread_cpu_ms() -> Option<f64> {
    let text = std::fs::read_to_string("/proc/thread-self/schedstat").ok()?;
    let ns: f64 = text.split_whitespace().next()?.parse().ok()?;
    Some(ns / 1e6)
}
