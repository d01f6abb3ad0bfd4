//! STEP export of the exact model (`vesselcad::exchange`): the example column
//! and a generated plant, each written whole from its design with no cached
//! vessel blocks (one thread: the benchmark runs in a one-thread rayon pool),
//! reported as bytes/s and vessels/s by criterion's throughput.

use std::hint::black_box;
use std::path::Path;
use std::time::Duration;

use criterion::{Criterion, Throughput, criterion_group};
use vesselcad::design::{Design, load};
use vesselcad::exchange::{ExchangeOptions, StepBlocks, export_step};
use vesselcad::plant::generate_plant;

/// Vessels in the benchmark plant.
const VESSELS: usize = 100;

fn export(design: &Design) -> String {
    export_step(
        design,
        &[],
        &ExchangeOptions::DEFAULT,
        "bench.step",
        &mut StepBlocks::default(),
    )
    .expect("exports")
}

fn bench(c: &mut Criterion) {
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .build()
        .expect("pool");
    let column =
        load(Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/designs/vertical-column.json"))
            .expect("example");
    let plant = generate_plant(VESSELS, 1).expect("generated");
    let mut group = c.benchmark_group("exchange");
    group
        .warm_up_time(Duration::from_secs(1))
        .measurement_time(Duration::from_secs(5))
        .sample_size(10);
    let bytes = pool.install(|| export(&column)).len() as u64;
    group.throughput(Throughput::Bytes(bytes));
    group.bench_function("STEP of the example column, bytes", |b| {
        b.iter(|| pool.install(|| black_box(export(&column))))
    });
    group.throughput(Throughput::Elements(VESSELS as u64));
    group.bench_function("STEP of a 100-vessel plant, vessels", |b| {
        b.iter(|| pool.install(|| black_box(export(&plant))))
    });
    group.finish();
}

criterion_group!(group, bench);
