//! OpenCASCADE's view of an exchange file: `tests/occt/check_exchange.py` run by the
//! Python of PyPI's `cadquery-ocp` (installed by `.ci/run` into
//! `target/occt-venv`, or named by `VESSELCAD_OCCT_PYTHON`). Where none is found
//! the OCCT tests say so and pass, except under CI (`CI` set), where they fail.

use std::path::{Path, PathBuf};
use std::process::Command;

use serde_json::Value;

/// The Python with OCP, or None (with the reason printed).
pub fn occt_python() -> Option<PathBuf> {
    let candidates = [
        std::env::var_os("VESSELCAD_OCCT_PYTHON").map(PathBuf::from),
        Some(Path::new(env!("CARGO_MANIFEST_DIR")).join("target/occt-venv/bin/python")),
    ];
    for python in candidates.into_iter().flatten() {
        let ok = Command::new(&python)
            .args(["-c", "import OCP"])
            .status()
            .is_ok_and(|s| s.success());
        if ok {
            return Some(python);
        }
    }
    assert!(
        std::env::var_os("CI").is_none(),
        "OpenCASCADE (cadquery-ocp) not found: .ci/run installs it into target/occt-venv"
    );
    eprintln!("skipped: no OpenCASCADE (pip install cadquery-ocp into target/occt-venv)");
    None
}

/// OCCT's report on the file `text`, written as `name` (its extension picks
/// the reader), with `samples`² points of each face's surface (0: no face list).
pub fn occt_report(python: &Path, text: &str, name: &str, samples: usize) -> Value {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR"));
    let path = dir.join(name);
    std::fs::write(&path, text).expect("write the exchange file");
    let script = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/occt/check_exchange.py");
    let out = Command::new(python)
        .arg(script)
        .arg(&path)
        .arg(samples.to_string())
        .output()
        .expect("python runs");
    assert!(
        out.status.success(),
        "check_exchange.py failed: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    // OCCT's readers print progress lines first; the report is the last line.
    let stdout = String::from_utf8_lossy(&out.stdout);
    let last = stdout.lines().rev().find(|l| l.starts_with('{'));
    serde_json::from_str(last.expect("a report line")).expect("json report")
}
