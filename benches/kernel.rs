//! Benchmarks of the NURBS kernel: one criterion entry point, one module per topic.
//!
//! Run with `cargo bench --bench kernel`; each topic keeps its measurement short so
//! the whole run takes a minute or two.

use criterion::criterion_main;

#[path = "kernel/grid.rs"]
mod grid;

criterion_main!(grid::group);
