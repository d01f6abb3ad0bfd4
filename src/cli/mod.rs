//! The `vesselcad` command line, one file per command, each a thin layer over
//! the library that parses arguments, prints and picks the exit status: `build`,
//! `check`, `serve`, `drawing`, `info`, `plant`, `simulate`, `bench`, `export`, `fab`, `fem`,
//! `store`, `scan`.
//! [`output`] is their standard output (quiet on a closed pipe), [`progress`]
//! the progress bar and [`alloc`] the heap measurement of `info --memory` and
//! `bench`.

pub mod alloc;
pub mod bench;
pub mod build;
pub mod calc;
pub mod check;
pub mod drawing;
pub mod export;
pub mod fab;
pub mod fem;
pub mod info;
pub mod output;
pub mod pdf;
pub mod plant;
pub mod progress;
pub mod scan;
pub mod serve;
pub mod simulate;
pub mod store;

use std::process::ExitCode;

use vesselcad::design::DesignError;
use vesselcad::model::ModelError;

/// Prints a design error and returns the exit status for it: 2 for a file that
/// cannot be read, 1 otherwise.
pub fn fail(error: &DesignError) -> ExitCode {
    eprintln!("error: {error}");
    match error {
        DesignError::Io { .. } => ExitCode::from(2),
        _ => ExitCode::from(1),
    }
}

/// The message of a model refusal, bad tessellation options naming the flag
/// that set them and its value (`--tolerance 0.000001: …`).
pub fn model_error(error: &ModelError) -> String {
    match error {
        ModelError::Options(o) => {
            format!("--{} {}: {o}", o.field().replace('_', "-"), o.value())
        }
        e => e.to_string(),
    }
}
