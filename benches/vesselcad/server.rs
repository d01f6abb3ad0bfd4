//! Live-session edits: one nozzle edit on the example plant sent as a JSON Patch
//! through a session (parse, patch a copy of the design JSON, check it, replace
//! the design in the model — which rebuilds only that nozzle and its host patch —,
//! append it to the journal with an fsync, write the delta GLB) against the same
//! edit given to the model directly as `Edit::SetNozzle`. The ratio is the cost of
//! the patch path, which must stay a small factor, not grow with the plant.

use std::hint::black_box;
use std::time::Duration;

use criterion::{Criterion, criterion_group};
use vesselcad::design::load;
use vesselcad::mesh::TessellationOptions;
use vesselcad::model::{Edit, Model};
use vesselcad::server::session::Session;

const PLANT: &str = concat!(
    env!("CARGO_MANIFEST_DIR"),
    "/examples/designs/small-plant.json"
);

fn bench(c: &mut Criterion) {
    let options = TessellationOptions::DEFAULT;
    let dir = std::env::temp_dir().join(format!("vesselcad-bench-server-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("temp folder");
    let path = dir.join("plant.json");
    std::fs::copy(PLANT, &path).expect("copy the example plant");
    let _ = std::fs::remove_file(dir.join("plant.json.journal"));
    let design = load(&path).expect("the example plant is valid");
    let tag = design.vessels[0].tag.clone();
    let nozzle = design.vessels[0].nozzles[0].clone();

    let mut group = c.benchmark_group("server");
    group
        .measurement_time(Duration::from_secs(4))
        .sample_size(20);

    let mut session = Session::open(&path, options).expect("session");
    let mut flip = false;
    group.bench_function(
        "plant nozzle edit as JSON Patch (session, journal fsync, delta GLB)",
        |b| {
            b.iter(|| {
            flip = !flip;
            let value = nozzle.projection + if flip { 50.0 } else { 0.0 };
            let patch = format!(
                r#"[{{"op":"replace","path":"/vessels/0/nozzles/0/projection","value":{value}}}]"#
            );
            black_box(session.apply_patch(patch.as_bytes()).expect("valid edit"))
        })
        },
    );

    let mut model = Model::from_design(&design, options).expect("valid");
    group.bench_function("plant nozzle edit as Edit::SetNozzle (model only)", |b| {
        b.iter(|| {
            flip = !flip;
            let mut n = nozzle.clone();
            n.projection += if flip { 50.0 } else { 0.0 };
            black_box(
                model
                    .edit(Edit::SetNozzle {
                        vessel: tag.clone(),
                        nozzle: n,
                    })
                    .expect("valid edit"),
            )
        })
    });
    group.finish();
    let _ = std::fs::remove_dir_all(&dir);
}

criterion_group!(group, bench);
