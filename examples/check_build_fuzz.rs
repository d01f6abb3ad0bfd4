//! Check agrees with build, at scale (issue 30 §1): builds every design `check`
//! accepts among N random perturbations of the example designs (one to four
//! numeric fields across their allowed ranges, `tests/common/perturb.rs`) and
//! reports how many were accepted, refused, built and failed, with the
//! slowest build. `tests/design_build_fuzz.rs` runs a few hundred in CI.
//!
//! ```text
//! cargo run --release --example check_build_fuzz -- [cases=2000] [first-seed=0] [tolerance-mm=0.5]
//! ```

#[path = "../tests/common/perturb.rs"]
mod perturb;

use std::panic::{AssertUnwindSafe, catch_unwind};
use std::process::ExitCode;
use std::time::Instant;

use perturb::{Rng, perturb};
use serde_json::Value;
use vesselcad::design::parse;
use vesselcad::mesh::TessellationOptions;
use vesselcad::model::Model;

const EXAMPLES: [(&str, &str); 3] = [
    (
        "horizontal-drum",
        include_str!("designs/horizontal-drum.json"),
    ),
    (
        "vertical-column",
        include_str!("designs/vertical-column.json"),
    ),
    ("storage-tank", include_str!("designs/storage-tank.json")),
];

fn main() -> ExitCode {
    let mut args = std::env::args().skip(1);
    let cases: u64 = args.next().and_then(|a| a.parse().ok()).unwrap_or(2000);
    let first: u64 = args.next().and_then(|a| a.parse().ok()).unwrap_or(0);
    let options = args
        .next()
        .and_then(|a| a.parse().ok())
        .map_or(TessellationOptions::DEFAULT, TessellationOptions::chord);
    let (mut accepted, mut refused, mut failed) = (0u64, 0u64, 0u64);
    let mut slowest = (0.0f64, 0u64);
    let start = Instant::now();
    for case in first..first + cases {
        let mut rng = Rng(0xf022_0030 + case);
        let (name, text) = *rng.pick(&EXAMPLES);
        let mut design: Value = serde_json::from_str(text).expect("example");
        let made = perturb(&mut design, &mut rng);
        let Ok(parsed) = parse(&design.to_string()) else {
            refused += 1;
            continue;
        };
        accepted += 1;
        let t = Instant::now();
        let outcome = catch_unwind(AssertUnwindSafe(|| {
            Model::from_design(&parsed, options).map(|m| m.errors().0.clone())
        }));
        let took = t.elapsed().as_secs_f64();
        if took > slowest.0 {
            slowest = (took, case);
        }
        let problem = match outcome {
            Ok(Ok(errors)) if errors.is_empty() => continue,
            Ok(Ok(errors)) => format!("{errors:?}"),
            Ok(Err(e)) => e.to_string(),
            Err(_) => "panicked".to_string(),
        };
        failed += 1;
        println!("FAIL case {case} {name} {made:?} ({took:.2} s): {problem}");
    }
    println!(
        "{cases} cases at {} mm: {accepted} accepted, {refused} refused, {failed} accepted but failed to build; \
         slowest build {:.2} s (case {}); {:.1} s in all",
        options.tolerance,
        slowest.0,
        slowest.1,
        start.elapsed().as_secs_f64()
    );
    if failed == 0 {
        ExitCode::SUCCESS
    } else {
        ExitCode::FAILURE
    }
}
