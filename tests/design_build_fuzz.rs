//! Check agrees with build (issue 30 §1): random designs that `check` accepts —
//! one to four numeric fields of an example perturbed at once across their
//! allowed ranges (`common/perturb.rs`) — all build, with no part failing to
//! mesh or cut. A fixed seed and case count for CI; `examples/check_build_fuzz`
//! runs thousands.

#[path = "common/perturb.rs"]
mod perturb;

use std::panic::{AssertUnwindSafe, catch_unwind};

use perturb::{Rng, perturb};
use serde_json::Value;
use vesselcad::design::parse;
use vesselcad::mesh::TessellationOptions;
use vesselcad::model::Model;

const EXAMPLES: [(&str, &str); 3] = [
    (
        "horizontal-drum",
        include_str!("../examples/designs/horizontal-drum.json"),
    ),
    (
        "vertical-column",
        include_str!("../examples/designs/vertical-column.json"),
    ),
    (
        "storage-tank",
        include_str!("../examples/designs/storage-tank.json"),
    ),
];

/// Cases run in CI.
const CASES: u64 = 120;

#[test]
fn accepted_perturbed_designs_all_build() {
    let mut failures = Vec::new();
    let (mut accepted, mut refused) = (0, 0);
    for case in 0..CASES {
        let mut rng = Rng(0x5eed_0030 + case);
        let (name, text) = *rng.pick(&EXAMPLES);
        let mut design: Value = serde_json::from_str(text).unwrap();
        let made = perturb(&mut design, &mut rng);
        let Ok(parsed) = parse(&design.to_string()) else {
            refused += 1;
            continue;
        };
        accepted += 1;
        let outcome = catch_unwind(AssertUnwindSafe(|| {
            Model::from_design(&parsed, TessellationOptions::DEFAULT).map(|m| m.errors().0.clone())
        }));
        match outcome {
            Ok(Ok(errors)) if errors.is_empty() => {}
            Ok(Ok(errors)) => failures.push(format!("case {case} {name} {made:?}: {errors:?}")),
            Ok(Err(e)) => failures.push(format!("case {case} {name} {made:?}: {e}")),
            Err(_) => failures.push(format!("case {case} {name} {made:?}: panicked")),
        }
    }
    eprintln!("{accepted} accepted, {refused} refused");
    assert!(
        accepted >= CASES as usize / 4,
        "too few accepted: {accepted}"
    );
    assert!(failures.is_empty(), "\n{}", failures.join("\n"));
}
