//! The example designs load, pass every rule, and survive load → save → load.

mod common;

use common::examples::{EXAMPLES, example_path as path};
use vesselcad::design::{load, parse, resolve, to_canonical_json};

#[test]
fn examples_load_and_resolve() {
    for name in EXAMPLES {
        let design = load(path(name)).unwrap_or_else(|e| panic!("{name}: {e}"));
        let vessels = resolve(&design).unwrap();
        assert_eq!(vessels.len(), design.vessels.len());
    }
}

#[test]
fn save_is_canonical_and_round_trips() {
    for name in EXAMPLES {
        let design = load(path(name)).unwrap();
        let text = to_canonical_json(&design);
        let again = parse(&text).unwrap();
        assert_eq!(design, again, "{name}");
        assert_eq!(
            text,
            to_canonical_json(&again),
            "{name}: save is not canonical"
        );
    }
}
