//! Standard output of every command. A reader that goes away early
//! (`vesselcad info plant.json | head -1`) closes the pipe: the next write fails
//! with `EPIPE` (Rust ignores `SIGPIPE`), which `println!` turns into a panic.
//! Here it ends the command quietly with status 0 instead — the reader had what it
//! wanted; any other write error is reported with status 2.

use std::fmt;
use std::io::{self, Write};
use std::process::ExitCode;

/// Writes `args` to standard output and flushes, or ends the process (see
/// [`failed`]).
pub fn print(args: fmt::Arguments<'_>) {
    let mut out = io::stdout().lock();
    if let Err(e) = out.write_fmt(args).and_then(|()| out.flush()) {
        drop(out);
        let broken = e.kind() == io::ErrorKind::BrokenPipe;
        let _ = failed(&e);
        std::process::exit(if broken { 0 } else { 2 });
    }
}

/// The exit status for an error writing standard output: success, silently, for
/// a closed pipe; otherwise 2, with the error on standard error.
pub fn failed(error: &io::Error) -> ExitCode {
    if error.kind() == io::ErrorKind::BrokenPipe {
        ExitCode::SUCCESS
    } else {
        eprintln!("error: writing standard output: {error}");
        ExitCode::from(2)
    }
}

/// Whether `error`, or an error it wraps, is a closed pipe.
pub fn is_broken_pipe(error: &(dyn std::error::Error + 'static)) -> bool {
    let mut cause = Some(error);
    while let Some(e) = cause {
        if e.downcast_ref::<io::Error>()
            .is_some_and(|io| io.kind() == io::ErrorKind::BrokenPipe)
        {
            return true;
        }
        cause = e.source();
    }
    false
}

/// `print!` through [`print`].
macro_rules! out {
    ($($arg:tt)*) => {
        $crate::cli::output::print(format_args!($($arg)*))
    };
}

/// `println!` through [`print`].
macro_rules! outln {
    ($($arg:tt)*) => {
        $crate::cli::output::print(format_args!("{}\n", format_args!($($arg)*)))
    };
}

pub(crate) use {out, outln};
