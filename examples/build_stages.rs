//! Where a full plant build's time goes, stage by stage, on 1 and 2 threads:
//! the stages that do not halve are the serial part of the build.
//!
//! `cargo run --release --example build_stages -- [vessels]`

use std::time::Instant;

use vesselcad::mesh::TessellationOptions;
use vesselcad::model::{Model, Views};
use vesselcad::plant::generate_plant;

fn main() {
    let vessels: usize = std::env::args()
        .nth(1)
        .and_then(|a| a.parse().ok())
        .unwrap_or(2000);
    let design = generate_plant(vessels, 1).expect("a generated plant");
    let names = [
        "Validate",
        "Constrain",
        "Geometry",
        "Tessellate",
        "Project",
        "Export",
    ];
    for threads in [1, 2] {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .expect("a pool");
        let start = Instant::now();
        let model = pool
            .install(|| {
                Model::from_design_with(&design, TessellationOptions::chord(1.0), Views::Off)
            })
            .expect("a valid plant");
        let total = start.elapsed().as_secs_f64();
        let stages = model.stage_times();
        let staged: f64 = stages.iter().map(|d| d.as_secs_f64()).sum();
        print!(
            "{threads} thread(s): total {total:.2} s, outside the stages {:.2} s |",
            total - staged
        );
        for (name, d) in names.iter().zip(stages) {
            print!(" {name} {:.2}", d.as_secs_f64());
        }
        println!();
        drop(pool.install(|| model));
    }
}
