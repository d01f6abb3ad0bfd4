//! The checked-in JSON Schema (`docs/vesselcad-1.schema.json`) is the one the serde
//! types generate, it is a valid draft 2020-12 schema, every example design
//! validates against it, and it refuses what the design rules refuse.
//!
//! Regenerate the file after changing the design types with
//! `UPDATE_SCHEMA=1 cargo test --test design_schema`.

mod common;

use std::path::{Path, PathBuf};

use common::examples::{EXAMPLES, example_path};
use serde_json::{Value, json};
use vesselcad::json_schema::{SCHEMA_ID, json_schema_text};

fn repo() -> &'static Path {
    Path::new(env!("CARGO_MANIFEST_DIR"))
}

fn schema_path() -> PathBuf {
    repo().join(SCHEMA_ID)
}

fn validator() -> jsonschema::Validator {
    let schema: Value = serde_json::from_str(&json_schema_text()).unwrap();
    jsonschema::draft202012::new(&schema).expect("the generated schema compiles")
}

fn example_designs() -> Vec<(String, Value)> {
    EXAMPLES
        .iter()
        .map(|name| {
            let text = std::fs::read_to_string(example_path(name)).unwrap();
            (name.to_string(), serde_json::from_str(&text).unwrap())
        })
        .collect()
}

#[test]
fn checked_in_schema_is_the_generated_one() {
    let generated = json_schema_text();
    let path = schema_path();
    if std::env::var_os("UPDATE_SCHEMA").is_some() {
        std::fs::write(&path, &generated).unwrap();
    }
    let checked_in = std::fs::read_to_string(&path).unwrap_or_default();
    if checked_in != generated {
        let line = checked_in
            .lines()
            .zip(generated.lines())
            .position(|(a, b)| a != b)
            .map_or(
                checked_in.lines().count().min(generated.lines().count()),
                |i| i,
            );
        panic!(
            "{} differs from the schema the design types generate (first at line {}): \
             regenerate it with `UPDATE_SCHEMA=1 cargo test --test design_schema`",
            path.display(),
            line + 1
        );
    }
}

#[test]
fn schema_is_a_valid_draft_2020_12_schema() {
    let schema: Value = serde_json::from_str(&json_schema_text()).unwrap();
    assert_eq!(
        schema["$schema"],
        json!("https://json-schema.org/draft/2020-12/schema")
    );
    jsonschema::meta::validate(&schema).expect("the schema obeys the draft 2020-12 meta-schema");
}

#[test]
fn every_example_design_validates() {
    // EXAMPLES, which the other suites sweep too, names every file there is.
    let dir = example_path("x").parent().unwrap().to_path_buf();
    let mut files: Vec<String> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "json"))
        .map(|p| p.file_stem().unwrap().to_string_lossy().into_owned())
        .collect();
    files.sort();
    let mut listed: Vec<String> = EXAMPLES.iter().map(|s| s.to_string()).collect();
    listed.sort();
    assert_eq!(
        files, listed,
        "tests/common/examples.rs: EXAMPLES against {dir:?}"
    );
    let validator = validator();
    for (name, design) in example_designs() {
        let errors: Vec<String> = validator
            .iter_errors(&design)
            .map(|e| format!("{} at {}", e, e.instance_path()))
            .collect();
        assert!(errors.is_empty(), "{name} fails the schema: {errors:#?}");
    }
}

/// The drum example with one value set at a JSON pointer (an object's member is
/// added if the example leaves it out).
fn drum_with(pointer: &str, value: Value) -> Value {
    let mut design = example_designs()
        .into_iter()
        .find(|(name, _)| name == "horizontal-drum")
        .unwrap()
        .1;
    let (parent, key) = pointer.rsplit_once('/').unwrap();
    match design.pointer_mut(parent) {
        Some(Value::Object(members)) => {
            members.insert(key.to_string(), value);
        }
        Some(Value::Array(items)) => items[key.parse::<usize>().unwrap()] = value,
        _ => panic!("the drum example has no {parent}"),
    }
    design
}

#[test]
fn schema_refuses_what_the_rules_refuse() {
    let validator = validator();
    let cases = [
        ("/format", json!("vesselcad/2")),
        ("/units", json!("ft")),
        ("/vessels/0/kind", json!("spherical")),
        ("/vessels/0/nozzles/0/size", json!(2.2)),
        ("/vessels/0/nozzles/0/rating", json!(250)),
        ("/vessels/0/nozzles/0/schedule", json!("S40")),
        ("/vessels/0/nozzles/0/orientation", json!(400.0)),
        ("/vessels/0/nozzles/0/projection", json!(0.0)),
        ("/vessels/0/parts/1/shell/od", json!(-2400.0)),
        ("/vessels/0/design/pressure", json!(-200.0)),
        ("/vessels/0/design/temperature", json!(-300.0)),
        ("/vessels/0/tag", json!("")),
    ];
    for (pointer, value) in cases {
        let design = drum_with(pointer, value.clone());
        assert!(
            !validator.is_valid(&design),
            "the schema accepts {value} at {pointer}"
        );
        assert!(
            vesselcad::design::parse(&design.to_string()).is_err(),
            "the loader accepts {value} at {pointer}: the case is not a bad design"
        );
    }
    // An unknown field is refused, as by the loader.
    let mut design = drum_with("/vessels/0/tag", json!("V-101"));
    design["vessels"][0]["colour"] = json!("red");
    assert!(!validator.is_valid(&design));
}
