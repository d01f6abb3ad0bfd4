//! Where an edit's time goes, by kind of edit: draws random valid edits as
//! `vesselcad simulate` does, applies each with its own update (drawing views off,
//! as in `vesselcad bench`) and prints, per kind, the mean and 99th-percentile update time, each
//! stage's share and the work counters. Run under `perf record` to profile edits.
//!
//! `cargo run --release --example tick_profile -- [vessels] [edits]`; `ONLY=<kind>`
//! (e.g. `ONLY="nozzle elevation"`) applies only edits of that kind; `SLOWEST=<n>`
//! lists the n slowest edits, what they changed and the work they did;
//! `DUMP_SLOW=<ms>` writes the design of each vessel whose edit took longer to
//! `/tmp/slow-<tag>.json`.

use std::collections::BTreeMap;
use std::time::Instant;

use vesselcad::design::{PartDesign, VesselDesign};
use vesselcad::mesh::TessellationOptions;
use vesselcad::model::{Edit, Model, Views};
use vesselcad::plant::rng::SplitMix64;
use vesselcad::plant::{after_edit, draw_edit, generate_plant};

/// Totals for one kind of edit.
#[derive(Default)]
struct Totals {
    count: usize,
    ms: f64,
    /// Every update's time, for the percentiles.
    times: Vec<f64>,
    stages: [f64; 6],
    meshes: u64,
    triangles: u64,
    cuts: u64,
    placed: u64,
}

/// A name for the kind of `edit` made to `old`.
fn kind(old: &VesselDesign, edit: &Edit) -> &'static str {
    match edit {
        Edit::SetPart { part, .. } => {
            match (old.parts.iter().find(|p| p.id() == part.id()), part) {
                (Some(PartDesign::Shell(a)), PartDesign::Shell(b)) if a.od != b.od => "shell od",
                (_, PartDesign::Shell(_)) => "shell length",
                _ => "head swap",
            }
        }
        Edit::SetNozzle { nozzle, .. } => {
            match old.nozzles.iter().find(|n| n.mark == nozzle.mark) {
                Some(n) if n.elevation != nozzle.elevation => "nozzle elevation",
                Some(n) if n.orientation != nozzle.orientation => "nozzle orientation",
                _ => "nozzle projection",
            }
        }
        _ => "other",
    }
}

/// The binary's allocator, configured as its batch commands configure it
/// (`src/cli/alloc.rs`), so that the times are the binary's.
#[global_allocator]
static GLOBAL: mimalloc::MiMalloc = mimalloc::MiMalloc;

fn main() {
    // Freed memory kept, as `vesselcad bench` keeps it.
    vesselcad::allocator::hold_freed_memory();
    let mut args = std::env::args().skip(1);
    let vessels: usize = args.next().and_then(|a| a.parse().ok()).unwrap_or(300);
    let edits: usize = args.next().and_then(|a| a.parse().ok()).unwrap_or(600);
    let design = generate_plant(vessels, 1).expect("generated");
    let mut model = Model::from_design_with(&design, TessellationOptions::chord(1.0), Views::Off)
        .expect("valid");
    let mut designs = design.vessels.clone();
    let mut rng = SplitMix64::new(7);
    let mut stats: BTreeMap<&'static str, Totals> = BTreeMap::new();
    let only = std::env::var("ONLY").ok();
    let dump: Option<f64> = std::env::var("DUMP_SLOW").ok().and_then(|s| s.parse().ok());
    let listed: usize = std::env::var("SLOWEST")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(0);
    // Every edit's time, with what it was, for the slowest ones' listing (only
    // when asked for: the labels would count in a profile of the edits).
    let mut slowest: Vec<(f64, String)> = Vec::new();
    edits_begin();
    for _ in 0..edits {
        let i = rng.int(0, designs.len() as u64 - 1) as usize;
        let Some(edit) = draw_edit(&mut rng, &designs[i]) else {
            continue;
        };
        let mut after = designs[i].clone();
        after_edit(&mut after, &edit);
        let what = kind(&designs[i], &edit);
        if only.as_deref().is_some_and(|o| o != what) {
            continue;
        }
        let label = (listed > 0).then(|| describe(&designs[i], &edit));
        if model.apply(edit).is_err() {
            continue;
        }
        let start = Instant::now();
        let c = model.update();
        let ms = start.elapsed().as_secs_f64() * 1e3;
        let t = stats.entry(what).or_default();
        t.count += 1;
        t.ms += ms;
        t.times.push(ms);
        for (total, stage) in t.stages.iter_mut().zip(model.stage_times()) {
            *total += stage.as_secs_f64() * 1e3;
        }
        t.meshes += c.meshes_rebuilt;
        t.triangles += c.triangles_meshed;
        t.cuts += c.openings_cut;
        t.placed += c.openings_placed;
        if dump.is_some_and(|limit| ms > limit) {
            let path = format!("/tmp/slow-{}.json", after.tag);
            let one = vesselcad::design::Design {
                vessels: vec![after.clone()],
                ..design.clone()
            };
            if let Ok(text) = serde_json::to_string_pretty(&one) {
                let _ = std::fs::write(&path, text);
                eprintln!("{ms:.1} ms: wrote {path}");
            }
        }
        designs[i] = after;
        let Some(label) = label else {
            continue;
        };
        slowest.push((
            ms,
            format!(
                "{what:18} {label} | meshes {} shared {} tris {} cuts {} | stages {:?} ms",
                c.meshes_rebuilt,
                c.meshes_shared,
                c.triangles_meshed,
                c.openings_cut,
                model
                    .stage_times()
                    .map(|d| (d.as_secs_f64() * 1e4).round() / 10.0)
            ),
        ));
    }
    let mut all = 0.0;
    let mut count = 0;
    let mut every = Vec::new();
    for (what, mut t) in stats {
        let n = t.count as f64;
        t.times.sort_by(f64::total_cmp);
        let p99 = percentile(&t.times, 0.99);
        every.extend_from_slice(&t.times);
        let s = t.stages.map(|x| x / n);
        all += t.ms;
        count += t.count;
        println!(
            "{what:18} n={:4} mean {:.3} p99 {p99:.3} ms | V {:.3} C {:.3} G {:.3} T {:.3} P {:.3} E {:.3} | meshes {:.1} tris {:.0} cuts {:.1} (placed {:.1})",
            t.count,
            t.ms / n,
            s[0],
            s[1],
            s[2],
            s[3],
            s[4],
            s[5],
            t.meshes as f64 / n,
            t.triangles as f64 / n,
            t.cuts as f64 / n,
            t.placed as f64 / n
        );
    }
    every.sort_by(f64::total_cmp);
    slowest.sort_by(|a, b| b.0.total_cmp(&a.0));
    for (ms, what) in slowest.iter().take(listed) {
        println!("  {ms:7.3} ms  {what}");
    }
    println!(
        "all                n={count:4} mean {:.3} p50 {:.3} p99 {:.3} ms",
        all / count.max(1) as f64,
        percentile(&every, 0.5),
        percentile(&every, 0.99)
    );
}

/// The vessel an edit is made to, and the part or nozzle it changes.
fn describe(old: &VesselDesign, edit: &Edit) -> String {
    let shape = old
        .parts
        .iter()
        .map(|p| match p {
            PartDesign::Shell(s) => format!("S{:.0}x{:.0}", s.od, s.length),
            PartDesign::Head(h) => format!("{:?}", h.shape),
            other => other.id().to_string(),
        })
        .collect::<Vec<_>>()
        .join(",");
    let target = match edit {
        Edit::SetPart { part, .. } => part.id().to_string(),
        Edit::SetNozzle { nozzle, .. } => format!("{} on {}", nozzle.mark, nozzle.host),
        _ => String::new(),
    };
    format!(
        "{} {target} [{} nozzles; {shape}]",
        old.tag,
        old.nozzles.len()
    )
}

/// Marks the end of the build: `valgrind --tool=callgrind
/// --dump-before='*edits_begin*'` writes the build's counts to a first file and
/// the edits' alone to a second.
#[inline(never)]
fn edits_begin() {
    std::hint::black_box(());
}

/// The `q` quantile of sorted `times` (nearest rank), 0 when empty.
fn percentile(times: &[f64], q: f64) -> f64 {
    if times.is_empty() {
        return 0.0;
    }
    let k = ((times.len() as f64 * q).ceil() as usize).clamp(1, times.len()) - 1;
    times[k]
}
