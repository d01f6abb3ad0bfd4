//! Headless Chromium as the drawings use it: where it is looked for and the
//! flags every run takes (no sandbox, GPU, network, first-run or sync work, a
//! profile directory of its own). The CLI prints PDFs through it (`cli::pdf`);
//! the render tests screenshot sheets with it.

use std::path::Path;
use std::process::Command;

/// Where headless Chromium is looked for (Debian's package, as `.ci/run` installs it).
pub const CHROMIUM: &str = "/usr/bin/chromium";

/// Flags every headless run takes.
pub const HEADLESS_FLAGS: [&str; 8] = [
    "--headless",
    "--no-sandbox",
    "--disable-gpu",
    "--disable-quic",
    "--no-first-run",
    "--disable-background-networking",
    "--disable-component-update",
    "--disable-sync",
];

/// A headless Chromium command with [`HEADLESS_FLAGS`] and the profile
/// directory `profile`; the caller adds what it does (print, screenshot) and
/// the page.
pub fn headless(profile: &Path) -> Command {
    let mut c = Command::new(CHROMIUM);
    c.args(HEADLESS_FLAGS)
        .arg(format!("--user-data-dir={}", profile.display()));
    c
}
