//! Randomized nozzle layouts through both exchange writers (issue 32 §4): a
//! plant drawn by the plant generator (each vessel's kind, heads, courses and
//! nozzles — sizes, hosts, orientations, offsets, pads — drawn at random and
//! kept only when `check` accepts the vessel) is written as one STEP and one
//! IGES file, and OpenCASCADE reads each in one Python call: every shape and
//! face valid, nothing to sew, the free edges exactly the intended openings
//! (the bores), each face's area vesselcad's exact trimmed area to 1e-6
//! relative, and the IGES B-rep's free edges the STEP file's, before and after
//! sewing (it shares the same edges).
//!
//! CI runs a few cases (each a multi-vessel plant); `VESSELCAD_EXCHANGE_CASES=200
//! cargo test --test exchange_layouts` runs many. Without OCCT the test says so
//! and passes, except under CI.

mod common;

use std::collections::BTreeMap;
use std::path::Path;

use common::occt::{occt_python, occt_report};
use proptest::prelude::*;
use serde_json::Value;
use vesselcad::exchange::{
    ExchangeOptions, StepBlocks, VesselBrep, export_iges, export_step, face_measures, vessel_brep,
    vessel_sources,
};
use vesselcad::plant::generate_plant;

/// Cases in CI unless `VESSELCAD_EXCHANGE_CASES` says otherwise.
const CI_CASES: u32 = 3;

fn cases() -> u32 {
    std::env::var("VESSELCAD_EXCHANGE_CASES")
        .ok()
        .and_then(|c| c.parse().ok())
        .unwrap_or(CI_CASES)
}

/// Each face's exact trimmed area by its name (names repeat: a list each).
fn our_areas(breps: &[VesselBrep]) -> BTreeMap<String, Vec<f64>> {
    let mut areas: BTreeMap<String, Vec<f64>> = BTreeMap::new();
    for b in breps {
        for f in &b.faces {
            areas
                .entry(format!("{}/{}/{}", b.tag, b.nodes[f.node], f.patch))
                .or_default()
                .push(face_measures(&b.edges, f).area);
        }
    }
    areas
}

/// Edges used by one face only: the intended openings.
fn open_edges(breps: &[VesselBrep]) -> usize {
    breps
        .iter()
        .map(|b| {
            let mut uses = vec![0usize; b.edges.len()];
            for f in &b.faces {
                for e in f.outer.iter().chain(f.holes.iter().flatten()) {
                    uses[e.edge] += 1;
                }
            }
            uses.iter().filter(|&&u| u == 1).count()
        })
        .sum()
}

/// OCCT's findings on one file that do not hold, as messages.
fn problems(label: &str, report: &Value, areas: &BTreeMap<String, Vec<f64>>) -> Vec<String> {
    let mut out = Vec::new();
    for (key, want) in [
        ("read", Value::from(true)),
        ("read_failures", Value::from(0)),
        ("valid", Value::from(true)),
        ("sewing_contiguous", Value::from(0)),
        ("sewing_multiple", Value::from(0)),
    ] {
        // IGES faces share no edges: sewing joins them (checked by its free
        // edges).
        if label == "IGES" && key == "sewing_contiguous" {
            continue;
        }
        if report[key] != want {
            out.push(format!("{label}: {key} = {}", report[key]));
        }
    }
    let faces: usize = areas.values().map(Vec::len).sum();
    if report["faces"] != faces {
        out.push(format!("{label}: {} faces, ours {faces}", report["faces"]));
    }
    for f in report["face_list"].as_array().into_iter().flatten() {
        let name = f["name"].as_str().unwrap_or("(no name)");
        let area = f["area"].as_f64().unwrap_or(f64::NAN);
        if f["valid"] != true {
            out.push(format!("{label}: {name} invalid"));
        }
        match areas.get(name) {
            Some(ours) if ours.iter().any(|a| (a - area).abs() <= 1e-6 * a) => {}
            ours => out.push(format!("{label}: {name}: OCCT area {area}, ours {ours:?}")),
        }
    }
    out
}

proptest! {
    #![proptest_config(ProptestConfig {
        cases: cases(),
        failure_persistence: None,
        // Another seed is another plant: nothing to shrink.
        max_shrink_iters: 0,
        ..ProptestConfig::default()
    })]

    #[test]
    fn random_layouts_read_valid_and_sewn_in_occt(seed in any::<u64>(), vessels in 2usize..6) {
        let Some(python) = occt_python() else {
            return Ok(());
        };
        let design = generate_plant(vessels, seed).expect("the generator draws valid vessels");
        let options = ExchangeOptions::DEFAULT;
        let step = export_step(&design, &[], &options, "layout.step", &mut StepBlocks::default())
            .map_err(|e| TestCaseError::fail(format!("seed {seed}: STEP: {e}")))?;
        let iges = export_iges(&design, &[], &options, "layout.igs")
            .map_err(|e| TestCaseError::fail(format!("seed {seed}: IGES: {e}")))?;
        let breps: Vec<VesselBrep> = vessel_sources(&design, &[], options.tolerance)
            .expect("sources")
            .iter()
            .map(|s| vessel_brep(s).expect("brep"))
            .collect();
        let areas = our_areas(&breps);
        let name = format!("layout-{seed:016x}-{vessels}");
        let on_step = occt_report(&python, &step, &format!("{name}.step"), 1);
        let on_iges = occt_report(&python, &iges, &format!("{name}.igs"), 1);
        let mut found = problems("STEP", &on_step, &areas);
        found.extend(problems("IGES", &on_iges, &areas));
        let once = open_edges(&breps);
        if on_step["free_edges"] != once {
            found.push(format!("STEP: {} free edges, {once} openings", on_step["free_edges"]));
        }
        // The IGES B-rep shares the STEP file's edges: the same free edges,
        // before and after sewing.
        if on_iges["free_edges"] != once {
            found.push(format!("IGES: {} free edges, {once} openings", on_iges["free_edges"]));
        }
        if on_iges["sewing_free"] != on_step["sewing_free"] {
            found.push(format!(
                "IGES sews to {} free edges, STEP to {}",
                on_iges["sewing_free"], on_step["sewing_free"]
            ));
        }
        if !found.is_empty() {
            let kept = Path::new(env!("CARGO_TARGET_TMPDIR")).join(format!("{name}.json"));
            let _ = std::fs::write(&kept, serde_json::to_string_pretty(&design).unwrap_or_default());
            return Err(TestCaseError::fail(format!(
                "seed {seed}, {vessels} vessels (design in {}): {found:#?}",
                kept.display()
            )));
        }
    }
}
