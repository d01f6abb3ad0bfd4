//! The edit every "check accepts it, the mesher cannot build it" test uses
//! (issue 30 §1): the horizontal-drum example meshed at 1 mm under a vertex
//! budget just above what its largest patch needs, and an edit that `check`
//! accepts which makes one patch need more.
//!
//! Measured at 1 mm (`TessellationOptions::max_vertices`, the budget each
//! region is meshed within): the example builds from a budget of 1 708 (its
//! largest patch is the crown of head H2, 1 665 vertices meshed); with head H2
//! hemispherical instead of 2:1 ellipsoidal, its crown needs a budget of
//! 2 081. [`MAX_VERTICES`] lies between the two, 5 % above the first and 13 %
//! below the second; at 0.5 mm the example's crowns need more than it too.

use serde_json::{Value, json};
use vesselcad::design::{Design, parse};
use vesselcad::mesh::TessellationOptions;

/// The chordal tolerance the fixture is measured at, mm.
pub const TOLERANCE: f64 = 1.0;

/// The vertex budget: the example builds within it at [`TOLERANCE`], the edited
/// design does not.
pub const MAX_VERTICES: usize = 1800;

/// The design path of the part whose patch cannot be meshed after the edit.
pub const PATH: &str = "vessels[0].parts[2]";

/// Its stable id.
pub const ENTITY: &str = "V-101/H2";

/// The patch that cannot be meshed.
pub const PATCH: &str = "crown";

/// The options the fixture is built with: [`TOLERANCE`], [`MAX_VERTICES`].
pub fn options() -> TessellationOptions {
    TessellationOptions::chord(TOLERANCE).with_max_vertices(MAX_VERTICES)
}

/// The options as `build`, `check` and `serve` take them.
pub fn option_args() -> [String; 4] {
    [
        "--tolerance".into(),
        TOLERANCE.to_string(),
        "--max-vertices".into(),
        MAX_VERTICES.to_string(),
    ]
}

/// The design that builds: the horizontal-drum example, as JSON.
pub fn buildable_json() -> Value {
    serde_json::from_str(include_str!("../../examples/designs/horizontal-drum.json"))
        .expect("the example is JSON")
}

/// The edit, as a JSON Patch: head H2 hemispherical instead of ellipsoidal.
pub fn edit() -> Value {
    json!([
        { "op": "test", "path": "/vessels/0/parts/2/head/id", "value": "H2" },
        { "op": "replace", "path": "/vessels/0/parts/2/head/shape", "value": "hemispherical" },
        { "op": "remove", "path": "/vessels/0/parts/2/head/ratio" }
    ])
}

/// The edited design, as JSON.
pub fn unbuildable_json() -> Value {
    let mut design = buildable_json();
    let patch: json_patch::Patch = serde_json::from_value(edit()).expect("a JSON Patch");
    json_patch::patch(&mut design, &patch).expect("the edit applies to the example");
    design
}

/// The design that builds, parsed and checked.
pub fn buildable() -> Design {
    parse(&buildable_json().to_string()).expect("the example passes every rule")
}

/// The edited design, parsed and checked: it passes every rule.
pub fn unbuildable() -> Design {
    parse(&unbuildable_json().to_string()).expect("the edit passes every rule")
}

/// Writes `design` to `design.json` in a new temporary directory (removed when
/// the returned guard drops) and returns both.
pub fn written(design: &Value) -> (tempfile::TempDir, std::path::PathBuf) {
    let dir = tempfile::Builder::new()
        .prefix("vesselcad-unbuildable-")
        .tempdir()
        .expect("a temporary directory");
    let path = dir.path().join("design.json");
    std::fs::write(&path, serde_json::to_string_pretty(design).unwrap()).unwrap();
    (dir, path)
}
