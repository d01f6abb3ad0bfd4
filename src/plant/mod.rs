//! Plant scale: generating large plants, simulating operating ticks on them and
//! measuring the engine (`vesselcad plant generate`, `simulate`, `bench`).
//!
//! These sit on top of the whole data flow: they produce designs and edits, drive
//! [`crate::model::Model`], and read its work counters and operating states.

mod build;
mod generate;
pub mod rng;

pub use build::build_plant;
pub use generate::{GenerateError, PLOT_PITCH, generate_plant};
mod simulate;

pub use simulate::{Simulation, TickReport, after_edit, draw_edit, quantile};
mod bench;

pub use bench::{BenchConfig, BenchError, BenchRow, format_markdown, format_table, run_bench};
