//! The example designs of `examples/designs/`, by name (without `.json`).

use std::path::PathBuf;

use vesselcad::design::{Design, load};

/// The example designs every suite sweeps: a drum, a column, a tank and a plant of
/// all three.
pub const EXAMPLES: [&str; 4] = [
    "horizontal-drum",
    "vertical-column",
    "storage-tank",
    "small-plant",
];

/// The path of `examples/designs/<name>.json`.
pub fn example_path(name: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("examples/designs")
        .join(format!("{name}.json"))
}

/// The example design `name`, loaded (and so checked) as `vesselcad` loads it.
pub fn example(name: &str) -> Design {
    let path = example_path(name);
    load(&path).unwrap_or_else(|e| panic!("example {}: {e}", path.display()))
}
