//! Drawing views of the example column: all four views of every part and nozzle
//! built from scratch (occluders and hidden-line classification), the views a
//! nozzle edit must rebuild at least (the nozzle and its host, against fresh
//! occluders), and the whole pipeline's edit + update, which now includes the
//! Project stage's incremental rebuild. The sheet composition and SVG writing of
//! the column are measured too, and, in a generated plant whose views are kept,
//! an update with nothing to do and a one-parameter edit.

use std::hint::black_box;
use std::time::Duration;

use criterion::{Criterion, criterion_group};
use vesselcad::design::load;
use vesselcad::drawing::{SheetOptions, sheet, to_svg, view_inputs};
use vesselcad::mesh::TessellationOptions;
use vesselcad::model::{Edit, Model, Views};
use vesselcad::plant::{Simulation, generate_plant};
use vesselcad::project::build_views;

/// Vessels in the plant whose views are kept.
const PLANT: usize = 60;

fn bench(c: &mut Criterion) {
    let design = load(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/examples/designs/vertical-column.json"
    ))
    .expect("the example column is valid");
    let mut model = Model::from_design(&design, TessellationOptions::DEFAULT).expect("valid");
    let (inputs, projections, settings) = view_inputs(&model, "C-201").expect("built");
    let all: Vec<usize> = (0..inputs.len()).collect();
    let n8 = inputs.iter().position(|e| e.id == "C-201/N8").expect("N8");
    let s2 = inputs.iter().position(|e| e.id == "C-201/S2").expect("S2");
    let mut group = c.benchmark_group("project");
    group
        .measurement_time(Duration::from_secs(4))
        .warm_up_time(Duration::from_secs(1))
        .sample_size(20);
    group.bench_function("column all views (16 entities x 4 views)", |b| {
        b.iter(|| black_box(build_views(&inputs, &projections, &settings, &all)))
    });
    group.bench_function("column views of N8 and its host S2", |b| {
        b.iter(|| black_box(build_views(&inputs, &projections, &settings, &[n8, s2])))
    });
    let nozzle = design.vessels[0]
        .nozzles
        .iter()
        .find(|n| n.mark == "N8")
        .expect("N8")
        .clone();
    let mut flip = false;
    group.bench_function("column N8 elevation edit + update (incl. views)", |b| {
        b.iter(|| {
            flip = !flip;
            let mut n = nozzle.clone();
            n.elevation = n.elevation.map(|e| e - if flip { 200.0 } else { 0.0 });
            black_box(
                model
                    .edit(Edit::SetNozzle {
                        vessel: "C-201".into(),
                        nozzle: n,
                    })
                    .expect("valid edit"),
            )
        })
    });
    group.bench_function("column sheet + SVG", |b| {
        b.iter(|| {
            black_box(to_svg(
                &sheet(&model, "C-201", &SheetOptions::default()).expect("built"),
            ))
        })
    });
    // A plant with views kept, as a live session on a plant file keeps them: an
    // update with nothing to do must not look at every vessel, and an edit
    // rebuilds only its vessel's views.
    let plant = generate_plant(PLANT, 1).expect("generated");
    let model = Model::from_design_with(&plant, TessellationOptions::chord(1.0), Views::Kept)
        .expect("valid");
    let mut sim = Simulation::new(model, &plant, 7);
    group.bench_function("plant of 60, views kept: update with nothing to do", |b| {
        b.iter(|| black_box(sim.model_mut().update()))
    });
    group.bench_function(
        "plant of 60, views kept: one-parameter edit + update",
        |b| b.iter(|| black_box(sim.tick(1, 0))),
    );
    group.finish();
}

criterion_group!(group, bench);
