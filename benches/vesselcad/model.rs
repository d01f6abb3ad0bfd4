//! The incremental model against a full build: building the example column from
//! scratch (ECS model, and the direct non-incremental scene build as a baseline),
//! and one edit followed by the incremental update. The ratio full / edit is the
//! payoff of change detection.

use std::hint::black_box;
use std::time::Duration;

use criterion::{Criterion, criterion_group};
use vesselcad::design::{Design, load};
use vesselcad::export::build_scene;
use vesselcad::mesh::TessellationOptions;
use vesselcad::model::{Edit, Model};

fn column() -> Design {
    load(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/examples/designs/vertical-column.json"
    ))
    .expect("the example column is valid")
}

fn bench(c: &mut Criterion) {
    let design = column();
    let options = TessellationOptions::DEFAULT;
    let mut group = c.benchmark_group("model");
    group
        .measurement_time(Duration::from_secs(5))
        .sample_size(20);
    group.bench_function("column full build (ECS model)", |b| {
        b.iter(|| black_box(Model::from_design(&design, options).expect("valid")))
    });
    group.bench_function("column full build (direct)", |b| {
        b.iter(|| black_box(build_scene(&design, &options).expect("valid")))
    });
    // One edit: alternate a nozzle's projection between two values, so every
    // iteration really changes something (that nozzle's patches and meshes).
    let mut model = Model::from_design(&design, options).expect("valid");
    let nozzle = design.vessels[0].nozzles[0].clone();
    let mut flip = false;
    group.bench_function("column one nozzle edit + update", |b| {
        b.iter(|| {
            flip = !flip;
            let mut n = nozzle.clone();
            n.projection += if flip { 50.0 } else { 0.0 };
            let counters = model
                .edit(Edit::SetNozzle {
                    vessel: "C-201".into(),
                    nozzle: n,
                })
                .expect("valid edit");
            black_box(counters)
        })
    });
    // A frame-only edit: move the vessel back and forth (no patch is rebuilt).
    let mut placement = design.vessels[0].placement;
    group.bench_function("column move + update", |b| {
        b.iter(|| {
            placement.position[0] += 1.0;
            black_box(
                model
                    .edit(Edit::MoveVessel {
                        tag: "C-201".into(),
                        placement,
                    })
                    .expect("valid"),
            )
        })
    });
    group.finish();
}

criterion_group!(group, bench);
