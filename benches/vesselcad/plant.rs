//! Plant scale, the paths `vesselcad bench` measures, kept here for regressions
//! on a plant small enough for a short run: a full build, a one-parameter edit
//! (apply + incremental update of model and meshes), a tick of 100 edits, an
//! update with nothing to do (the change-detection overhead), the operating
//! figures of a vessel, packing the meshes into the model's compact form (exact
//! to 40/32 bits, octahedral normals), and streaming the GLB.

use std::hint::black_box;
use std::time::Duration;

use criterion::{Criterion, criterion_group};
use vesselcad::constraints::state_of_design;
use vesselcad::design::resolve;
use vesselcad::export::stream_glb;
use vesselcad::mesh::{Mesh, PackedMesh, TessellationOptions};
use vesselcad::model::{Model, Views};
use vesselcad::plant::{Simulation, generate_plant};

/// Vessels in the benchmark plant.
const VESSELS: usize = 40;

fn bench(c: &mut Criterion) {
    let options = TessellationOptions::chord(1.0);
    let design = generate_plant(VESSELS, 1).expect("generated");
    let mut group = c.benchmark_group("plant");
    group
        .warm_up_time(Duration::from_secs(1))
        .measurement_time(Duration::from_secs(3))
        .sample_size(10);
    group.bench_function("full build, 40 vessels at 1 mm", |b| {
        b.iter(|| black_box(Model::from_design_with(&design, options, Views::Off).expect("valid")))
    });
    // As `vesselcad bench`: a plant model keeps no drawing views.
    let model = Model::from_design_with(&design, options, Views::Off).expect("valid");
    let mut sim = Simulation::new(model, &design, 7);
    group.sample_size(50);
    group.bench_function("one-parameter edit + update", |b| {
        b.iter(|| black_box(sim.tick(1, 0)))
    });
    group.sample_size(10);
    group.bench_function("tick of 100 edits", |b| {
        b.iter(|| black_box(sim.tick(100, 0)))
    });
    group.sample_size(100);
    group.bench_function("update with nothing to do", |b| {
        b.iter(|| black_box(sim.model_mut().update()))
    });
    let resolved = resolve(&design).expect("valid");
    group.bench_function("operating figures of every vessel", |b| {
        b.iter(|| {
            for (d, r) in design.vessels.iter().zip(&resolved) {
                black_box(state_of_design(d, r).expect("figures"));
            }
        })
    });
    let scene = sim.model().scene();
    let meshes: Vec<Mesh> = scene
        .vessels
        .iter()
        .flat_map(|v| &v.nodes)
        .flat_map(|n| &n.patches)
        .map(|p| p.mesh.unpack())
        .collect();
    group.sample_size(10);
    group.bench_function("pack the plant's meshes", |b| {
        b.iter(|| {
            meshes
                .iter()
                .map(|m| black_box(PackedMesh::pack(m)).heap_bytes())
                .sum::<usize>()
        })
    });
    group.bench_function("stream GLB to memory", |b| {
        b.iter(|| {
            let mut out = Vec::new();
            black_box(stream_glb(&scene, &mut out, std::path::Path::new("mem")).expect("written"))
        })
    });
    group.finish();
}

criterion_group!(group, bench);
