//! Benchmarks of vesselcad: one criterion entry point, one module per topic.
//!
//! Run with `cargo bench --bench vesselcad` (or `-- exchange` / `-- grid` / `-- mesh` / `-- model` / `-- opening` / `-- plant` / `-- project` / `-- scan` / `-- server` for one
//! topic); each topic keeps its measurement short so the whole run takes a few
//! minutes.

use criterion::criterion_main;

#[path = "vesselcad/exchange.rs"]
mod exchange;
#[path = "vesselcad/grid.rs"]
mod grid;
#[path = "vesselcad/mesh.rs"]
mod mesh;
#[path = "vesselcad/mesh_tuning.rs"]
mod mesh_tuning;
#[path = "vesselcad/model.rs"]
mod model;
#[path = "vesselcad/opening.rs"]
mod opening;
#[path = "vesselcad/plant.rs"]
mod plant;
#[path = "vesselcad/project.rs"]
mod project;
#[path = "vesselcad/scan.rs"]
mod scan;
#[path = "vesselcad/server.rs"]
mod server;

criterion_main!(
    exchange::group,
    grid::group,
    mesh::group,
    model::group,
    opening::group,
    plant::group,
    project::group,
    scan::group,
    server::group
);
