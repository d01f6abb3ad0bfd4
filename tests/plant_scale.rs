//! Plant scale: the generator gives valid, deterministic, varied plants; the
//! streaming GLB writer gives the same bytes as the in-memory one; a simulation is
//! deterministic and leaves the incremental model equal to a full build; the
//! plant commands run end to end.

mod common;

use std::collections::BTreeSet;
use std::process::Command;

use vesselcad::design::{HeadShape, PartDesign, VesselKind, to_canonical_json, validate};
use vesselcad::export::{build_scene, stream_glb, write_glb};
use vesselcad::mesh::TessellationOptions;
use vesselcad::model::{Edit, Model};
use vesselcad::plant::rng::SplitMix64;
use vesselcad::plant::{
    BenchRow, PLOT_PITCH, Simulation, build_plant, draw_edit, format_markdown, generate_plant,
};

fn options() -> TessellationOptions {
    TessellationOptions::chord(5.0)
}

/// How many reducers of the plant are eccentric and how many concentric.
fn reducers(design: &vesselcad::design::Design) -> (usize, usize) {
    let all = design.vessels.iter().flat_map(|v| &v.parts);
    let (mut eccentric, mut concentric) = (0, 0);
    for p in all {
        if let PartDesign::Reducer(r) = p {
            match r.eccentric {
                Some(_) => eccentric += 1,
                None => concentric += 1,
            }
        }
    }
    (eccentric, concentric)
}

#[test]
fn generated_plants_are_valid_varied_and_deterministic() {
    let a = generate_plant(60, 7).unwrap();
    let b = generate_plant(60, 7).unwrap();
    assert_eq!(to_canonical_json(&a), to_canonical_json(&b));
    assert_ne!(
        to_canonical_json(&a),
        to_canonical_json(&generate_plant(60, 8).unwrap())
    );
    validate(&a).unwrap();
    let kinds: BTreeSet<String> = a.vessels.iter().map(|v| format!("{:?}", v.kind)).collect();
    assert_eq!(kinds.len(), 3, "{kinds:?}");
    let shapes: BTreeSet<String> = a
        .vessels
        .iter()
        .flat_map(|v| &v.parts)
        .filter_map(|p| match p {
            PartDesign::Head(h) => Some(format!("{:?}", h.shape)),
            _ => None,
        })
        .collect();
    assert_eq!(shapes.len(), 6, "every head kind: {shapes:?}");
    assert!(a.vessels.iter().any(|v| v.kind == VesselKind::Vertical
        && v.parts.iter().filter(|p| p.kind() == "shell").count() >= 2
        && v.parts.iter().any(|p| p.kind() == "reducer")));
    // Columns with eccentric reducers (courses on an offset axis) and concentric ones.
    let (eccentric, concentric) = reducers(&a);
    assert!(eccentric > 0 && concentric > 0, "{eccentric} {concentric}");
    for v in &a.vessels {
        assert!(
            (4..=20).contains(&v.nozzles.len()),
            "{}: {}",
            v.tag,
            v.nozzles.len()
        );
        assert!(
            v.nozzles.iter().any(|n| n.mark.starts_with('M')),
            "{}: manway",
            v.tag
        );
        assert!(!v.notes.is_empty());
        assert!(v.operating.is_some());
    }
    // Footprints apart: datums at least one plot pitch apart.
    for (i, v) in a.vessels.iter().enumerate() {
        for w in &a.vessels[i + 1..] {
            let [x, y, _] = v.placement.position;
            let [p, q, _] = w.placement.position;
            assert!((x - p).abs() >= PLOT_PITCH - 1e-9 || (y - q).abs() >= PLOT_PITCH - 1e-9);
        }
    }
    let _ = HeadShape::Flat;
}

#[test]
fn generated_plant_builds_without_failures_and_chunked_build_matches() {
    let design = generate_plant(12, 3).unwrap();
    assert!(reducers(&design).0 > 0, "no eccentric reducer to build");
    let mut calls = Vec::new();
    let chunked = build_plant(&design, options(), &mut |done, total| {
        calls.push((done, total))
    })
    .unwrap();
    assert!(chunked.errors().0.is_empty(), "{:?}", chunked.errors().0);
    assert_eq!(calls.last(), Some(&(12, 12)));
    let whole = Model::from_design(&design, options()).unwrap();
    let a = write_glb(&chunked.scene()).unwrap();
    assert_eq!(a, write_glb(&whole.scene()).unwrap());
    // The streaming writer's bytes are the in-memory writer's.
    let mut streamed = Vec::new();
    let n = stream_glb(&whole.scene(), &mut streamed, std::path::Path::new("mem")).unwrap();
    assert_eq!(n as usize, streamed.len());
    assert!(streamed == a, "streamed GLB differs from write_glb");
}

#[test]
fn streaming_writer_matches_on_the_example_plant() {
    let design = common::examples::example("small-plant");
    let scene = build_scene(&design, &options()).unwrap();
    let mut streamed = Vec::new();
    stream_glb(&scene, &mut streamed, std::path::Path::new("mem")).unwrap();
    assert!(streamed == write_glb(&scene).unwrap());
}

#[test]
fn simulation_is_deterministic_and_incremental_equals_full_build() {
    let design = generate_plant(8, 11).unwrap();
    assert!(reducers(&design).0 > 0, "no eccentric reducer to simulate");
    let run = || {
        let model = Model::from_design(&design, options()).unwrap();
        let mut sim = Simulation::new(model, &design, 5);
        let mut masses = Vec::new();
        for _ in 0..4 {
            let r = sim.tick(5, 3);
            assert_eq!(r.edits, 5, "{r:?}");
            masses.push(sim.total_operating_mass());
        }
        (sim, masses)
    };
    let (a, masses_a) = run();
    let (b, masses_b) = run();
    assert_eq!(masses_a, masses_b);
    assert_eq!(a.model().design(), b.model().design());
    assert_ne!(a.model().design(), design, "the ticks changed the plant");
    // After the ticks the incremental model is what a full build of its design gives.
    common::full_build::assert_matches_full_build(a.model(), &options());
    // Its operating mass is the sum of the vessels' figures from scratch.
    let fresh = Model::from_design(&a.model().design(), options()).unwrap();
    let fresh_sim = Simulation::new(fresh, &a.model().design(), 0);
    let (x, y) = (a.total_operating_mass(), fresh_sim.total_operating_mass());
    assert!((x - y).abs() <= 1e-9 * y, "{x} vs {y}");
}

#[test]
fn an_update_with_nothing_to_do_does_no_work() {
    let design = generate_plant(5, 2).unwrap();
    let mut model = Model::from_design(&design, options()).unwrap();
    let c = model.update();
    assert_eq!(c, Default::default());
}

#[test]
fn an_edit_to_the_values_a_vessel_has_writes_nothing() {
    let design = generate_plant(5, 2).unwrap();
    let mut model = Model::from_design(&design, options()).unwrap();
    model.update();
    // Each part and nozzle of the first vessel set to what it is, in one batch
    // and one by one: staged as unchanged, nothing to resolve or mesh.
    let v = &design.vessels[0];
    let edits: Vec<Edit> = v
        .parts
        .iter()
        .map(|p| Edit::SetPart {
            vessel: v.tag.clone(),
            part: p.clone(),
        })
        .chain(v.nozzles.iter().map(|n| Edit::SetNozzle {
            vessel: v.tag.clone(),
            nozzle: n.clone(),
        }))
        .collect();
    model.apply(Edit::Batch(edits.clone())).unwrap();
    for edit in edits {
        model.apply(edit).unwrap();
    }
    assert_eq!(model.update(), Default::default());
    // A real change is still staged after a read of the same vessel.
    let i = (v.parts.iter())
        .position(|p| matches!(p, PartDesign::Shell(_)))
        .expect("a course");
    let mut part = v.parts[i].clone();
    let same = Edit::SetPart {
        vessel: v.tag.clone(),
        part: part.clone(),
    };
    if let PartDesign::Shell(s) = &mut part {
        s.length += 100.0;
    }
    let changed = Edit::SetPart {
        vessel: v.tag.clone(),
        part: part.clone(),
    };
    model.apply(Edit::Batch(vec![same, changed])).unwrap();
    assert!(model.update().shapes_rebuilt > 0);
    assert_eq!(model.design().vessels[0].parts[i], part);
}

#[test]
fn edits_applied_together_match_edits_applied_one_by_one() {
    let design = generate_plant(6, 3).unwrap();
    let mut rng = SplitMix64::new(9);
    let mut edits: Vec<Edit> = (0..40)
        .filter_map(|_| {
            let i = rng.int(0, design.vessels.len() as u64 - 1) as usize;
            draw_edit(&mut rng, &design.vessels[i])
        })
        .collect();
    let v = &design.vessels[1];
    // Refused edits among them (a course of negative length, a nozzle that is
    // not there), a move, and edits that do not name one vessel (which end a
    // run checked together).
    let mut bad = (v.parts.iter())
        .find(|p| matches!(p, PartDesign::Shell(_)))
        .expect("a course")
        .clone();
    if let PartDesign::Shell(s) = &mut bad {
        s.length = -5.0;
    }
    edits.insert(
        3,
        Edit::SetPart {
            vessel: v.tag.clone(),
            part: bad,
        },
    );
    edits.insert(
        9,
        Edit::RemoveNozzle {
            vessel: v.tag.clone(),
            mark: "no such nozzle".into(),
        },
    );
    let mut moved = design.vessels[2].placement;
    moved.position[0] += 1000.0;
    edits.insert(
        14,
        Edit::MoveVessel {
            tag: design.vessels[2].tag.clone(),
            placement: moved,
        },
    );
    let mut renamed = design.vessels[4].clone();
    renamed.drawing.title = Some("Set whole".into());
    edits.insert(20, Edit::SetVessel(renamed));
    edits.insert(26, Edit::Batch(edits[0..2].to_vec()));
    let mut together = Model::from_design(&design, options()).unwrap();
    let mut one_by_one = Model::from_design(&design, options()).unwrap();
    let a: Vec<bool> = together
        .apply_each(edits.clone())
        .iter()
        .map(Result::is_ok)
        .collect();
    let b: Vec<bool> = edits
        .into_iter()
        .map(|e| one_by_one.apply(e).is_ok())
        .collect();
    assert_eq!(a, b);
    assert!(a.iter().filter(|ok| !**ok).count() >= 2, "{a:?}");
    assert!(a.iter().filter(|ok| **ok).count() >= 30, "{a:?}");
    assert_eq!(together.design(), one_by_one.design());
    assert_eq!(together.update(), one_by_one.update());
    assert!(write_glb(&together.scene()).unwrap() == write_glb(&one_by_one.scene()).unwrap());
}

fn vesselcad(args: &[&str]) -> std::process::Output {
    Command::new(env!("CARGO_BIN_EXE_vesselcad"))
        .args(args)
        .output()
        .expect("runs")
}

#[test]
fn plant_commands_run_end_to_end() {
    let dir = std::env::temp_dir().join(format!("vesselcad-plant-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let plant = dir.join("plant.json");
    let plant = plant.to_str().unwrap();
    let o = vesselcad(&[
        "plant",
        "generate",
        "--vessels",
        "3",
        "--seed",
        "4",
        "-o",
        plant,
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert!(vesselcad(&["check", plant]).status.success());
    let o = vesselcad(&["info", plant, "--memory", "--tolerance", "5"]);
    let out = String::from_utf8_lossy(&o.stdout);
    assert!(
        o.status.success() && out.contains("memory per vessel") && out.contains("operating mass"),
        "{out}"
    );
    let o = vesselcad(&[
        "simulate",
        plant,
        "--ticks",
        "2",
        "--edits-per-tick",
        "2",
        "--seed",
        "9",
        "--levels",
        "--tolerance",
        "5",
    ]);
    let out = String::from_utf8_lossy(&o.stdout);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert!(
        out.contains("p50") && out.contains("p99") && out.contains("operating mass"),
        "{out}"
    );
    let glb = dir.join("plant.glb");
    let o = vesselcad(&[
        "build",
        plant,
        "-o",
        glb.to_str().unwrap(),
        "--tolerance",
        "5",
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert!(o.stderr.is_empty(), "no progress bar off a terminal");
    let o = vesselcad(&[
        "bench",
        "--vessels",
        "2",
        "--edits",
        "3",
        "--ticks",
        "1",
        "--tolerance",
        "5",
    ]);
    let out = String::from_utf8_lossy(&o.stdout);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    for figure in [
        "vessels/s",
        "speed-up",
        "(pairs: ",
        "p99",
        "tick of 100 edits",
        "memory per vessel",
        "MB/s",
    ] {
        assert!(out.contains(figure), "{figure} missing:\n{out}");
    }
    std::fs::remove_dir_all(&dir).ok();
}

/// `vesselcad bench --markdown`: the table as BENCHMARKS.md holds it, with the bars
/// inside a cell escaped so that every row keeps the header's four cells.
#[test]
fn bench_table_as_markdown() {
    let row = |name: &str, value: &str, target: &str, met| BenchRow {
        name: name.into(),
        value: value.into(),
        target: target.into(),
        met,
    };
    let rows = [
        row(
            "tick of 100 edits: p50 (max)",
            "18.60 ms (25.10 ms)",
            "≤ 20 ms",
            Some(true),
        ),
        row(
            "  edit, mean: Geometry | Tessellate",
            "0.1 | 0.2 ms",
            "",
            None,
        ),
        row("speed-up, 2 threads over 1", "1.70×", "≥ 1.8×", Some(false)),
    ];
    let table = format_markdown(&rows);
    let lines: Vec<&str> = table.lines().collect();
    assert_eq!(
        lines,
        [
            "| Figure | Value | Target | Met |",
            "|---|---|---|---|",
            "| tick of 100 edits: p50 (max) | 18.60 ms (25.10 ms) | ≤ 20 ms | met |",
            r"| ↳ edit, mean: Geometry \| Tessellate | 0.1 \| 0.2 ms |  |  |",
            "| speed-up, 2 threads over 1 | 1.70× | ≥ 1.8× | **not met** |",
        ]
    );
    for line in &lines {
        assert_eq!(line.replace(r"\|", "").matches('|').count(), 5, "{line}");
    }
}
