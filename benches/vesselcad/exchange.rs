//! STEP and IGES export of the exact model (`vesselcad::exchange`): the example
//! column and a generated 1,000-vessel plant, each written whole from its
//! design with no cached vessel blocks, and the plant's STEP again after one
//! vessel's edit with the other blocks cached (one thread: the benchmark runs
//! in a one-thread rayon pool), reported as bytes/s and vessels/s by
//! criterion's throughput. The file sizes are printed once.

use std::hint::black_box;
use std::path::Path;
use std::time::Duration;

use criterion::{Criterion, Throughput, criterion_group};
use vesselcad::design::{Design, load};
use vesselcad::exchange::{ExchangeOptions, StepBlocks, export_iges, export_step};
use vesselcad::plant::generate_plant;

/// Vessels in the benchmark plant.
const VESSELS: usize = 1000;

fn step(design: &Design, cache: &mut StepBlocks) -> String {
    export_step(design, &[], &ExchangeOptions::DEFAULT, "bench.step", cache).expect("exports")
}

fn iges(design: &Design) -> String {
    export_iges(design, &[], &ExchangeOptions::DEFAULT, "bench.igs").expect("exports")
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
    // The plant with its first vessel renamed: an edit of one vessel's block.
    let mut edited = plant.clone();
    edited.vessels[0].tag.push('X');

    let mut group = c.benchmark_group("exchange");
    group
        .warm_up_time(Duration::from_secs(1))
        .measurement_time(Duration::from_secs(5))
        .sample_size(10);
    let column_step = pool
        .install(|| step(&column, &mut StepBlocks::default()))
        .len() as u64;
    let column_iges = pool.install(|| iges(&column)).len() as u64;
    let plant_step = pool
        .install(|| step(&plant, &mut StepBlocks::default()))
        .len() as u64;
    let plant_iges = pool.install(|| iges(&plant)).len() as u64;
    let per = |bytes: u64| bytes as f64 / VESSELS as f64 / 1e3;
    eprintln!(
        "exchange sizes: column STEP {column_step} B, IGES {column_iges} B; \
         {VESSELS}-vessel plant STEP {plant_step} B ({:.1} kB/vessel), IGES {plant_iges} B ({:.1} kB/vessel)",
        per(plant_step),
        per(plant_iges)
    );
    group.throughput(Throughput::Bytes(column_step));
    group.bench_function("STEP of the example column, bytes", |b| {
        b.iter(|| pool.install(|| black_box(step(&column, &mut StepBlocks::default()))))
    });
    group.throughput(Throughput::Bytes(column_iges));
    group.bench_function("IGES of the example column, bytes", |b| {
        b.iter(|| pool.install(|| black_box(iges(&column))))
    });
    group.throughput(Throughput::Elements(VESSELS as u64));
    group.bench_function("STEP of a 1000-vessel plant, vessels", |b| {
        b.iter(|| pool.install(|| black_box(step(&plant, &mut StepBlocks::default()))))
    });
    group.bench_function("IGES of a 1000-vessel plant, vessels", |b| {
        b.iter(|| pool.install(|| black_box(iges(&plant))))
    });
    // Each export after the first builds one block (the vessel whose tag
    // alternates) and reuses the 999 others.
    let mut cache = StepBlocks::default();
    pool.install(|| step(&plant, &mut cache));
    let mut flip = false;
    group.throughput(Throughput::Bytes(plant_step));
    group.bench_function("STEP of the plant after one vessel's edit, bytes", |b| {
        b.iter(|| {
            flip = !flip;
            let design = if flip { &edited } else { &plant };
            let text = pool.install(|| step(design, &mut cache));
            assert_eq!((cache.built, cache.reused), (1, VESSELS - 1));
            black_box(text)
        })
    });
    group.finish();
}

criterion_group!(group, bench);
