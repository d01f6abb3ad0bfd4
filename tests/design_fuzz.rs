//! Validation is complete: whatever [`parse`] accepts, the later stages can build.
//!
//! Each case takes an example design as a `serde_json::Value` and applies one to
//! three random mutations — a numeric leaf set to a negative, zero, tiny, huge or
//! plausible value; a key deleted; a string replaced by another name the format
//! knows (or an empty one); an optional field added; two array items swapped; an
//! array item duplicated — then parses the text. `parse` must answer `Ok` or
//! `Err` and never panic; when it answers `Ok`, the design must resolve, every part
//! and nozzle must build its patches with finite control points and positive
//! weights, every frame and note position must be finite, and the canonical save
//! must load back to the same design. Fixed seed, fixed case count.

use std::panic::{AssertUnwindSafe, catch_unwind};

use proptest::prelude::*;
use proptest::sample::Index;
use proptest::test_runner::{Config, RngSeed};
use serde_json::Value;
use vesselcad::design::{Design, parse, resolve, to_canonical_json};

const EXAMPLES: [&str; 4] = [
    include_str!("../examples/designs/horizontal-drum.json"),
    include_str!("../examples/designs/vertical-column.json"),
    include_str!("../examples/designs/storage-tank.json"),
    include_str!("../examples/designs/small-plant.json"),
];

/// Names a design file uses, to swap in for any string.
const NAMES: [&str; 30] = [
    "",
    " ",
    "V-101",
    "S1",
    "S2",
    "H1",
    "H2",
    "R1",
    "SK",
    "SD1",
    "B1",
    "N1",
    "M1",
    "T1",
    "shell",
    "vertical",
    "horizontal",
    "tank",
    "hemispherical",
    "ellipsoidal",
    "torispherical",
    "toriconical",
    "conical",
    "flat",
    "FF",
    "RTJ",
    "SO",
    "blind",
    "XXS",
    "in",
];

/// One step of a JSON path.
#[derive(Clone, Debug)]
enum Step {
    Key(String),
    Item(usize),
}

/// Paths of every leaf (and every object member) of `value`.
fn walk(value: &Value, here: &mut Vec<Step>, out: &mut Vec<(Vec<Step>, Value)>) {
    match value {
        Value::Object(map) => {
            for (k, v) in map {
                here.push(Step::Key(k.clone()));
                out.push((here.clone(), v.clone()));
                walk(v, here, out);
                here.pop();
            }
        }
        Value::Array(items) => {
            for (i, v) in items.iter().enumerate() {
                here.push(Step::Item(i));
                out.push((here.clone(), v.clone()));
                walk(v, here, out);
                here.pop();
            }
        }
        _ => {}
    }
}

fn at_mut<'a>(value: &'a mut Value, path: &[Step]) -> Option<&'a mut Value> {
    path.iter().try_fold(value, |v, step| match step {
        Step::Key(k) => v.get_mut(k.as_str()),
        Step::Item(i) => v.get_mut(*i),
    })
}

/// What a mutation does.
#[derive(Clone, Debug)]
enum Mutation {
    /// Set a numeric leaf; the value is chosen from the original by `NumberChoice`.
    Number(Index, NumberChoice),
    /// Delete an object member.
    Delete(Index),
    /// Replace a string leaf by one of [`NAMES`].
    Rename(Index, Index),
    /// Add one of [`OPTIONAL_KEYS`] with a number to an object.
    Insert(Index, Index, NumberChoice),
    /// Swap two items of an array (reorders the stack, the vessels, ...).
    Swap(Index, Index, Index),
    /// Append a copy of an item of an array (duplicate ids, extra parts, ...).
    Duplicate(Index, Index),
}

/// Optional numeric fields of the format, to add where they may or may not apply.
const OPTIONAL_KEYS: [&str; 17] = [
    "offset",
    "inclination",
    "elevation",
    "eccentric",
    "position",
    "ratio",
    "crown_radius",
    "knuckle_radius",
    "half_angle",
    "small_od",
    "straight_flange",
    "flare_angle",
    "base_ring_width",
    "web_thickness",
    "thickness",
    "rotation",
    "contact_angle",
];

/// Replacement numbers, weighted towards trouble; JSON holds no NaN or infinity.
#[derive(Clone, Copy, Debug)]
enum NumberChoice {
    Negative(f64),
    Zero,
    Tiny,
    Huge,
    VeryHuge,
    Max,
    /// The original times a factor in [0, 3).
    Scaled(f64),
    /// A value in [-1000, 10000).
    InRange(f64),
    /// A small integer.
    Small(i64),
}

impl NumberChoice {
    fn apply(self, original: f64) -> Value {
        let x = match self {
            NumberChoice::Negative(f) => -(original.abs() * f + 1.0),
            NumberChoice::Zero => 0.0,
            NumberChoice::Tiny => 1e-300,
            NumberChoice::Huge => 1e300,
            NumberChoice::VeryHuge => 1e308,
            NumberChoice::Max => f64::MAX,
            NumberChoice::Scaled(f) => original * f,
            NumberChoice::InRange(x) => x,
            NumberChoice::Small(n) => return Value::from(n),
        };
        // Keep whole numbers integral so that integer fields (rating, count) see
        // integers when the choice allows it.
        if x.fract() == 0.0 && x.abs() < 1e15 {
            Value::from(x as i64)
        } else {
            Value::from(x)
        }
    }
}

fn number_choice() -> impl Strategy<Value = NumberChoice> {
    prop_oneof![
        1 => (0.0..2.0f64).prop_map(NumberChoice::Negative),
        1 => Just(NumberChoice::Zero),
        1 => Just(NumberChoice::Tiny),
        1 => Just(NumberChoice::Huge),
        1 => Just(NumberChoice::VeryHuge),
        1 => Just(NumberChoice::Max),
        3 => (0.0..3.0f64).prop_map(NumberChoice::Scaled),
        2 => (-1000.0..10000.0f64).prop_map(NumberChoice::InRange),
        1 => (-2i64..1000).prop_map(NumberChoice::Small),
    ]
}

fn mutation() -> impl Strategy<Value = Mutation> {
    prop_oneof![
        4 => (any::<Index>(), number_choice()).prop_map(|(i, c)| Mutation::Number(i, c)),
        1 => any::<Index>().prop_map(Mutation::Delete),
        2 => (any::<Index>(), any::<Index>()).prop_map(|(i, n)| Mutation::Rename(i, n)),
        2 => (any::<Index>(), any::<Index>(), number_choice())
            .prop_map(|(i, k, c)| Mutation::Insert(i, k, c)),
        1 => (any::<Index>(), any::<Index>(), any::<Index>())
            .prop_map(|(i, a, b)| Mutation::Swap(i, a, b)),
        1 => (any::<Index>(), any::<Index>()).prop_map(|(i, a)| Mutation::Duplicate(i, a)),
    ]
}

/// Applies a mutation; a mutation with nothing to act on leaves the design alone.
fn mutate(design: &mut Value, m: &Mutation) {
    let mut leaves = Vec::new();
    walk(design, &mut Vec::new(), &mut leaves);
    let pick = |pred: &dyn Fn(&Value) -> bool, i: &Index| {
        let matching: Vec<&(Vec<Step>, Value)> = leaves.iter().filter(|(_, v)| pred(v)).collect();
        (!matching.is_empty()).then(|| matching[i.index(matching.len())].clone())
    };
    match m {
        Mutation::Number(i, choice) => {
            if let Some((path, v)) = pick(&|v| v.is_number(), i)
                && let Some(slot) = at_mut(design, &path)
            {
                *slot = choice.apply(v.as_f64().unwrap_or(0.0));
            }
        }
        Mutation::Delete(i) => {
            let members: Vec<&Vec<Step>> = leaves
                .iter()
                .map(|(p, _)| p)
                .filter(|p| matches!(p.last(), Some(Step::Key(_))))
                .collect();
            if members.is_empty() {
                return;
            }
            let path = members[i.index(members.len())];
            let (Some(Step::Key(key)), parent) = (path.last(), &path[..path.len() - 1]) else {
                return;
            };
            if let Some(Value::Object(map)) = at_mut(design, parent) {
                map.remove(key);
            }
        }
        Mutation::Rename(i, n) => {
            if let Some((path, _)) = pick(&|v| v.is_string(), i)
                && let Some(slot) = at_mut(design, &path)
            {
                *slot = Value::from(NAMES[n.index(NAMES.len())]);
            }
        }
        Mutation::Insert(i, k, choice) => {
            if let Some((path, _)) = pick(&|v| v.is_object(), i)
                && let Some(Value::Object(map)) = at_mut(design, &path)
            {
                let key = OPTIONAL_KEYS[k.index(OPTIONAL_KEYS.len())];
                map.insert(key.to_string(), choice.apply(1000.0));
            }
        }
        Mutation::Swap(i, a, b) => {
            if let Some((path, _)) = pick(&|v| v.as_array().is_some_and(|a| a.len() > 1), i)
                && let Some(Value::Array(items)) = at_mut(design, &path)
            {
                let n = items.len();
                items.swap(a.index(n), b.index(n));
            }
        }
        Mutation::Duplicate(i, a) => {
            if let Some((path, _)) = pick(&|v| v.as_array().is_some_and(|a| !a.is_empty()), i)
                && let Some(Value::Array(items)) = at_mut(design, &path)
            {
                let copy = items[a.index(items.len())].clone();
                items.push(copy);
            }
        }
    }
}

/// Everything downstream of validation succeeds for an accepted design.
fn check_accepted(design: &Design) -> Result<(), TestCaseError> {
    let vessels = resolve(design)
        .map_err(|e| TestCaseError::fail(format!("parse accepted, resolve refused: {e}")))?;
    for vessel in &vessels {
        prop_assert!(vessel.frame.is_finite(), "{}: frame", vessel.tag);
        for part in &vessel.parts {
            let patches = part.geometry.patches().map_err(|e| {
                TestCaseError::fail(format!("{}/{}: patches: {e}", vessel.tag, part.id))
            })?;
            prop_assert!(
                !patches.is_empty(),
                "{}/{}: no patches",
                vessel.tag,
                part.id
            );
            for p in &patches {
                prop_assert!(
                    p.surface
                        .homogeneous_points()
                        .iter()
                        .all(|q| q.is_finite() && q.w > 0.0),
                    "{}/{}: patch {} has a bad control point",
                    vessel.tag,
                    part.id,
                    p.name
                );
            }
            prop_assert!(part.frame.is_finite(), "{}/{}: frame", vessel.tag, part.id);
            prop_assert!(part.span.0.is_finite() && part.span.1.is_finite());
        }
        for nozzle in &vessel.nozzles {
            let patches = nozzle.geometry.patches().map_err(|e| {
                TestCaseError::fail(format!("{}/{}: patches: {e}", vessel.tag, nozzle.mark))
            })?;
            prop_assert!(!patches.is_empty());
            for p in &patches {
                prop_assert!(
                    p.surface
                        .homogeneous_points()
                        .iter()
                        .all(|q| q.is_finite() && q.w > 0.0),
                    "{}/{}: patch {} has a bad control point",
                    vessel.tag,
                    nozzle.mark,
                    p.name
                );
            }
            prop_assert!(
                nozzle.frame.is_finite(),
                "{}/{}: frame",
                vessel.tag,
                nozzle.mark
            );
        }
        for note in &vessel.notes {
            prop_assert!(
                note.position.is_finite(),
                "{}/{}: position",
                vessel.tag,
                note.id
            );
        }
    }
    let again = parse(&to_canonical_json(design))
        .map_err(|e| TestCaseError::fail(format!("canonical save does not load: {e}")))?;
    prop_assert_eq!(&again, design, "canonical save does not round-trip");
    Ok(())
}

fn config() -> Config {
    Config {
        cases: 256,
        rng_seed: RngSeed::Fixed(0x7e55_e1ca_d001),
        failure_persistence: None,
        ..Config::default()
    }
}

proptest! {
    #![proptest_config(config())]

    #[test]
    fn mutated_examples_are_rejected_or_fully_buildable(
        example in 0..EXAMPLES.len(),
        mutations in prop::collection::vec(mutation(), 1..=3),
    ) {
        let mut design: Value = serde_json::from_str(EXAMPLES[example])
            .map_err(|e| TestCaseError::fail(format!("example {example}: {e}")))?;
        for m in &mutations {
            mutate(&mut design, m);
        }
        let text = design.to_string();
        let parsed = catch_unwind(AssertUnwindSafe(|| parse(&text)))
            .map_err(|_| TestCaseError::fail(format!("parse panicked on {text}")))?;
        if let Ok(accepted) = parsed {
            let outcome = catch_unwind(AssertUnwindSafe(|| check_accepted(&accepted)))
                .map_err(|_| TestCaseError::fail(format!("building panicked on {text}")))?;
            outcome.map_err(|e| TestCaseError::fail(format!("{e}\nmutations: {mutations:?}")))?;
        }
    }
}

/// An inch file is converted to mm on load; its canonical save must load back to
/// the very same numbers. serde_json's default float parser is not correctly
/// rounded (about one value in ten of the converted lengths comes back one ulp
/// off), so this needs serde_json's `float_roundtrip` feature.
#[test]
fn inch_design_saves_and_reloads_exactly() {
    let text = r#"{"format": "vesselcad/1", "units": "in", "vessels": [{"tag": "V-1",
        "kind": "vertical", "parts": [
        {"head": {"id": "H1", "shape": "ellipsoidal", "straight_flange": 1.7}},
        {"shell": {"id": "S1", "od": 39.37, "length": 118.11, "thickness": 0.3937}},
        {"head": {"id": "H2", "shape": "ellipsoidal"}}],
        "nozzles": [{"mark": "N1", "size": 4, "rating": 150, "host": "S1",
        "orientation": 0, "elevation": 59.055, "projection": 31.4961}]}]}"#;
    let design = parse(text).expect("valid inch design");
    let again = parse(&to_canonical_json(&design)).expect("canonical save loads");
    assert_eq!(again, design);
}
