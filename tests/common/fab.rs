//! Running `vesselcad fab` on an example vessel into a temporary directory.

use std::process::Command;

/// The files `vesselcad fab examples/designs/<example>.json --vessel <tag>`
/// writes, in a temporary directory; panics with its stderr if it fails.
pub fn fab_files(example: &str, tag: &str) -> tempfile::TempDir {
    let dir = tempfile::tempdir().unwrap();
    let out = Command::new(env!("CARGO_BIN_EXE_vesselcad"))
        .args([
            "fab",
            &format!("examples/designs/{example}.json"),
            "--vessel",
            tag,
            "-o",
        ])
        .arg(dir.path())
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    dir
}
