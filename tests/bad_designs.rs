//! The corpus of broken designs in `tests/bad_designs/`: one small file per way a
//! design can be wrong, each with its expectation in `tests/bad_designs/expected.json`
//! (`{"kind": "syntax" | "format" | "invalid" | "valid", "path": ..., "contains":
//! [...], "count": n}`).
//!
//! For every case, [`parse`] must return the expected kind of error, at the exact
//! JSON path (the `serde_path_to_error` path for syntax errors, a
//! [`RuleViolation`]'s path for broken rules), with the expected message fragments,
//! and with a `Display` that names the path. Every violation must name its path,
//! entity, field, value and rule. Nothing may panic: each case runs under
//! `catch_unwind`, so a panic is reported as that case's failure. Two `valid`
//! controls are the bases the other cases were made from, so each broken case
//! fails for the one thing changed in it.

use std::collections::BTreeMap;
use std::panic::{AssertUnwindSafe, catch_unwind};
use std::path::PathBuf;

use serde::Deserialize;
use vesselcad::design::{Design, DesignError, RuleViolation, parse};

/// What kind of result a case must give.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "lowercase")]
enum Kind {
    /// Parses and passes every rule (a control).
    Valid,
    /// [`DesignError::Syntax`].
    Syntax,
    /// [`DesignError::Format`].
    Format,
    /// [`DesignError::Invalid`].
    Invalid,
}

/// One entry of `expected.json`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct Expectation {
    kind: Kind,
    /// Exact JSON path of the error (syntax) or of one of the violations (invalid).
    path: Option<String>,
    /// Fragments that must appear in the message (syntax) or in that violation.
    contains: Vec<String>,
    /// Exact number of violations, for `invalid`.
    #[serde(default)]
    count: Option<usize>,
}

fn corpus_dir() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("tests/bad_designs")
}

fn expectations() -> BTreeMap<String, Expectation> {
    let path = corpus_dir().join("expected.json");
    let text = std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{path:?}: {e}"));
    serde_json::from_str(&text).unwrap_or_else(|e| panic!("{path:?}: {e}"))
}

fn read_case(name: &str) -> String {
    let path = corpus_dir().join(name);
    std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{path:?}: {e}"))
}

/// Parses under `catch_unwind`; a panic becomes `Err` with its message.
fn parse_guarded(text: &str) -> Result<Result<Design, DesignError>, String> {
    catch_unwind(AssertUnwindSafe(|| parse(text))).map_err(|payload| {
        payload
            .downcast_ref::<&str>()
            .map(|s| s.to_string())
            .or_else(|| payload.downcast_ref::<String>().cloned())
            .unwrap_or_else(|| "non-string panic payload".into())
    })
}

/// Every field of a violation is filled in.
fn violation_is_complete(v: &RuleViolation) -> bool {
    [&v.path, &v.entity, &v.field, &v.value, &v.rule]
        .iter()
        .all(|s| !s.trim().is_empty())
}

fn missing_fragments(text: &str, contains: &[String]) -> Vec<String> {
    contains
        .iter()
        .filter(|c| !text.contains(c.as_str()))
        .cloned()
        .collect()
}

/// Checks one case; returns what is wrong with its result.
fn check_case(name: &str, exp: &Expectation) -> Vec<String> {
    let text = read_case(name);
    let result = match parse_guarded(&text) {
        Ok(r) => r,
        Err(panic) => return vec![format!("panicked: {panic}")],
    };
    let mut problems = Vec::new();
    let error = match (result, exp.kind) {
        (Ok(_), Kind::Valid) => return problems,
        (Ok(_), kind) => return vec![format!("parsed Ok, expected a {kind:?} error")],
        (Err(e), Kind::Valid) => return vec![format!("expected Ok, got: {e}")],
        (Err(e), _) => e,
    };
    let display = error.to_string();
    match (&error, exp.kind) {
        (DesignError::Syntax { path, message }, Kind::Syntax) => {
            if let Some(want) = &exp.path
                && path != want
            {
                problems.push(format!("path {path:?}, expected {want:?}"));
            }
            if !display.contains(path.as_str()) {
                problems.push(format!("display {display:?} does not name the path"));
            }
            for m in missing_fragments(message, &exp.contains) {
                problems.push(format!("message {message:?} lacks {m:?}"));
            }
        }
        (DesignError::Format { .. }, Kind::Format) => {
            if exp.path.as_deref().is_some_and(|p| !display.starts_with(p)) {
                problems.push(format!("display {display:?} does not name the path"));
            }
            for m in missing_fragments(&display, &exp.contains) {
                problems.push(format!("display {display:?} lacks {m:?}"));
            }
        }
        (DesignError::Invalid(violations), Kind::Invalid) => {
            if violations.is_empty() {
                problems.push("Invalid with no violations".into());
            }
            for v in violations.iter().filter(|v| !violation_is_complete(v)) {
                problems.push(format!("incomplete violation {v:?}"));
            }
            for v in violations {
                if !display.contains(&v.path) {
                    problems.push(format!("display does not name {:?}", v.path));
                }
            }
            if let Some(count) = exp.count
                && violations.len() != count
            {
                problems.push(format!(
                    "{} violations, expected {count}: {display}",
                    violations.len()
                ));
            }
            match exp.path.as_ref() {
                None => problems.push("an invalid case needs a path".into()),
                Some(want) => match violations.iter().find(|v| &v.path == want) {
                    None => problems.push(format!("no violation at {want:?}: {display}")),
                    Some(v) => {
                        let shown = v.to_string();
                        for m in missing_fragments(&shown, &exp.contains) {
                            problems.push(format!("violation {shown:?} lacks {m:?}"));
                        }
                    }
                },
            }
        }
        (e, kind) => problems.push(format!("expected a {kind:?} error, got: {e}")),
    }
    problems
}

#[test]
fn corpus_and_expectations_match() {
    let expected = expectations();
    let mut files: Vec<String> = std::fs::read_dir(corpus_dir())
        .expect("corpus directory")
        .filter_map(|e| e.ok())
        .map(|e| e.file_name().to_string_lossy().into_owned())
        .filter(|n| n.ends_with(".json") && n != "expected.json")
        .collect();
    files.sort();
    let listed: Vec<String> = expected.keys().cloned().collect();
    assert_eq!(files, listed, "files and expected.json entries differ");
    assert!(files.len() >= 40, "only {} cases", files.len());
}

#[test]
fn every_bad_design_gives_its_expected_error() {
    let mut failures = Vec::new();
    for (name, exp) in &expectations() {
        for problem in check_case(name, exp) {
            failures.push(format!("{name}: {problem}"));
        }
    }
    assert!(failures.is_empty(), "\n{}", failures.join("\n"));
}

#[test]
fn several_independent_problems_are_all_reported() {
    let text = read_case("several_independent_problems.json");
    let error = parse(&text).expect_err("three problems");
    let mut paths: Vec<&str> = error.violations().iter().map(|v| v.path.as_str()).collect();
    paths.sort_unstable();
    assert_eq!(
        paths,
        [
            "vessels[0].nozzles[0].rating",
            "vessels[0].parts[1].shell.length",
            "vessels[0].placement.rotation",
        ],
        "{error}"
    );
    assert!(error.to_string().starts_with("3 problem(s)"), "{error}");
}

#[test]
fn problems_in_different_vessels_are_all_reported() {
    let text = read_case("control_vertical.json");
    let mut design: serde_json::Value = serde_json::from_str(&text).expect("control");
    let first = design["vessels"][0].clone();
    let mut second = first.clone();
    second["tag"] = "V-2".into();
    second["nozzles"][0]["size"] = 2.2.into();
    let mut third = first.clone();
    third["tag"] = "V-3".into();
    third["parts"][0]["head"]["shape"] = "conical".into();
    third["parts"][0]["head"]["half_angle"] = 90.into();
    third["notes"] = serde_json::json!([{ "id": "T1", "text": "x", "target": "nowhere" }]);
    design["vessels"] = serde_json::json!([first, second, third]);
    let error = parse(&design.to_string()).expect_err("three problems");
    let mut found: Vec<(&str, &str)> = error
        .violations()
        .iter()
        .map(|v| (v.path.as_str(), v.entity.as_str()))
        .collect();
    found.sort_unstable();
    assert_eq!(
        found,
        [
            ("vessels[1].nozzles[0].size", "V-2/N1"),
            ("vessels[2].notes[0].target", "V-3/T1"),
            ("vessels[2].parts[0].head.half_angle", "V-3/H1"),
        ],
        "{error}"
    );
}
