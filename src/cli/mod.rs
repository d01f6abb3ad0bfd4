//! The command line's plant-scale subcommands — `plant generate`, `simulate`,
//! `bench`, the chunked `build` with its progress bar and `info --memory` — each a
//! thin layer over `vesselcad::plant` that parses, prints and picks exit codes.

pub mod alloc;
pub mod bench;
pub mod build;
pub mod calc;
pub mod check;
pub mod export;
pub mod plant;
pub mod progress;
pub mod simulate;
