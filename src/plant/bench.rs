//! `vesselcad bench`: the plant-scale figures measured in one run on this machine,
//! each beside its target.
//!
//! Generates a plant, builds it fully with a one-thread and a two-thread rayon pool
//! (after an untimed warm-up build, two back-to-back pairs of builds; the
//! speed-up is the ratio of their summed times), then on the last
//! two-thread model measures one-parameter edits (apply + incremental update of
//! model and meshes), ticks of 100 edits, memory per vessel and GLB export
//! throughput. Heap figures come from the caller (the binary's counting
//! allocator), so the library needs no global allocator.

use std::path::Path;
use std::time::{Duration, Instant};

use rayon::ThreadPoolBuilder;

use super::generate::{GenerateError, generate_plant};
use super::simulate::{Simulation, TickReport, quantile};
use crate::design::Design;
use crate::export::{ExportError, stream_glb_to};
use crate::mesh::TessellationOptions;
use crate::model::{Model, ModelError, Views};
use crate::systems::STAGES;

/// Back-to-back pairs of full builds (1 thread, then 2) timed for the speed-up.
const BUILD_PAIRS: usize = 2;

/// What to measure.
#[derive(Clone, Debug)]
pub struct BenchConfig {
    /// Vessels in the plant (the figure is 10 000).
    pub vessels: usize,
    /// Plant seed.
    pub seed: u64,
    /// Chordal tolerance, mm (the figure is at 1 mm).
    pub tolerance: f64,
    /// One-parameter edits measured.
    pub edits: usize,
    /// Ticks of [`BenchConfig::tick_edits`] edits measured.
    pub ticks: usize,
    /// Edits per tick.
    pub tick_edits: usize,
}

impl Default for BenchConfig {
    fn default() -> Self {
        Self {
            vessels: 10_000,
            seed: 1,
            tolerance: 1.0,
            // Enough that ten edits lie above the p99 (two did of 200): one
            // slow edit moves it less.
            edits: 1000,
            ticks: 50,
            tick_edits: 100,
        }
    }
}

/// Why the bench could not run.
#[derive(Debug, thiserror::Error)]
pub enum BenchError {
    /// The plant could not be generated.
    #[error(transparent)]
    Generate(#[from] GenerateError),
    /// The model refused the plant.
    #[error(transparent)]
    Model(#[from] ModelError),
    /// The GLB could not be written.
    #[error(transparent)]
    Export(#[from] ExportError),
    /// A rayon pool could not be built.
    #[error("cannot build a rayon pool of {threads} thread(s): {message}")]
    Pool {
        /// Threads asked for.
        threads: usize,
        /// rayon's message.
        message: String,
    },
}

/// One figure of the table.
#[derive(Clone, Debug, PartialEq)]
pub struct BenchRow {
    /// What was measured.
    pub name: String,
    /// The figure, formatted with its unit.
    pub value: String,
    /// The target, or empty.
    pub target: String,
    /// Whether the target is met; `None` without a target.
    pub met: Option<bool>,
}

fn row(name: &str, value: String, target: &str, met: Option<bool>) -> BenchRow {
    BenchRow {
        name: name.to_string(),
        value,
        target: target.to_string(),
        met,
    }
}

/// Where ticks' time went, summed over ticks: drawing, checking and writing the
/// edits, then each stage of the update.
#[derive(Default)]
struct StageSums {
    apply: Duration,
    stages: [Duration; STAGES],
}

impl StageSums {
    fn add(&mut self, report: &TickReport) {
        self.apply += report.latency.saturating_sub(report.update);
        for (total, stage) in self.stages.iter_mut().zip(report.stages) {
            *total += stage;
        }
    }

    /// Means over `count` ticks, ms: the edits first, then the stages in order.
    fn means(&self, count: usize) -> [f64; STAGES + 1] {
        let n = count.max(1) as f64;
        let mut out = [ms(self.apply) / n; STAGES + 1];
        for (m, stage) in out[1..].iter_mut().zip(self.stages) {
            *m = ms(stage) / n;
        }
        out
    }
}

fn ms(d: Duration) -> f64 {
    d.as_secs_f64() * 1e3
}

/// Runs the bench. `heap` returns the bytes currently allocated (or `None` when
/// not counted); `progress` hears what is being measured; `scratch` is a directory
/// for the GLB.
///
/// # Errors
///
/// [`BenchError`] when generating, building or exporting fails.
pub fn run_bench(
    config: &BenchConfig,
    heap: &dyn Fn() -> Option<usize>,
    progress: &mut dyn FnMut(&str),
    scratch: &Path,
) -> Result<Vec<BenchRow>, BenchError> {
    let pool = |threads: usize| {
        ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .map_err(|e| BenchError::Pool {
                threads,
                message: e.to_string(),
            })
    };
    let (one, two) = (pool(1)?, pool(2)?);
    let options = TessellationOptions::chord(config.tolerance);
    progress(&format!("generating a plant of {} vessels", config.vessels));
    let design: Design = generate_plant(config.vessels, config.seed)?;
    let n = config.vessels as f64;
    let mut rows = Vec::new();

    // An untimed build first, so that both timed builds find the memory
    // already mapped: the first build of a process pays the page faults, and
    // timing it first (1 thread) flattered the speed-up.
    progress("full build, warm-up");
    drop(two.install(|| Model::from_design_with(&design, options, Views::Off))?);
    // Two back-to-back pairs (1 thread, then 2), each build starting with the
    // one before it dropped: the speed-up is the ratio of the summed times, so
    // one noisy build moves it half as much. The last two-thread model is the
    // one measured below.
    let build = |pool: &rayon::ThreadPool| {
        let start = Instant::now();
        let model = pool.install(|| Model::from_design_with(&design, options, Views::Off))?;
        Ok::<_, BenchError>((model, start.elapsed()))
    };
    let mut heap_model = None;
    let (mut t1, mut t2) = (Duration::ZERO, Duration::ZERO);
    let mut pairs = Vec::with_capacity(BUILD_PAIRS);
    let mut timed_pair = |pair: usize| {
        progress(&format!("full build, 1 thread ({pair} of {BUILD_PAIRS})"));
        let heap_before = heap();
        let (one_model, one_time) = build(&one)?;
        if pair == 1 {
            heap_model = heap().zip(heap_before).map(|(a, b)| a.saturating_sub(b));
        }
        drop(one_model);
        progress(&format!("full build, 2 threads ({pair} of {BUILD_PAIRS})"));
        let (two_model, two_time) = build(&two)?;
        pairs.push(one_time.as_secs_f64() / two_time.as_secs_f64());
        t1 += one_time;
        t2 += two_time;
        Ok::<_, BenchError>(two_model)
    };
    for pair in 1..BUILD_PAIRS {
        drop(timed_pair(pair)?);
    }
    let model = timed_pair(BUILD_PAIRS)?;
    let (t1, t2) = (t1 / BUILD_PAIRS as u32, t2 / BUILD_PAIRS as u32);
    let speedup = t1.as_secs_f64() / t2.as_secs_f64();
    rows.push(row(
        &format!(
            "full build, {} vessels at {} mm, 1 thread (mean of {BUILD_PAIRS})",
            config.vessels, config.tolerance
        ),
        format!(
            "{:.0} vessels/s ({:.1} s)",
            n / t1.as_secs_f64(),
            t1.as_secs_f64()
        ),
        "",
        None,
    ));
    rows.push(row(
        &format!(
            "full build, {} vessels at {} mm, 2 threads (mean of {BUILD_PAIRS})",
            config.vessels, config.tolerance
        ),
        format!(
            "{:.0} vessels/s ({:.1} s)",
            n / t2.as_secs_f64(),
            t2.as_secs_f64()
        ),
        "",
        None,
    ));
    rows.push(row(
        "speed-up, 2 threads over 1",
        format!(
            "{speedup:.2}× (pairs: {})",
            pairs
                .iter()
                .map(|r| format!("{r:.2}"))
                .collect::<Vec<_>>()
                .join(", ")
        ),
        "≥ 1.8×",
        Some(speedup >= 1.8),
    ));
    // A patch that failed to mesh is work not done: the figures above and below
    // only count if nothing did.
    let failed = model.errors().0.len();
    rows.push(row(
        "  patches or openings that failed (model errors)",
        format!("{failed}"),
        "0",
        Some(failed == 0),
    ));

    let mut sim = Simulation::new(model, &design, config.seed ^ 0x5EED);
    progress(&format!("{} one-parameter edits", config.edits));
    // Each edit's time and the triangles it meshed (the latter for the slow
    // edits' row).
    let mut meshed: Vec<(Duration, u64)> = Vec::with_capacity(config.edits);
    // Where an edit's time goes (summed over the edits).
    let mut sums = StageSums::default();
    two.install(|| {
        for _ in 0..config.edits {
            let report = sim.tick(1, 0);
            meshed.push((report.latency, report.counters.triangles_meshed));
            sums.add(&report);
        }
    });
    let mean = sums.means(config.edits);
    let mut samples: Vec<Duration> = meshed.iter().map(|&(t, _)| t).collect();
    let p50 = quantile(&mut samples, 0.5);
    let p99 = quantile(&mut samples, 0.99);
    rows.push(row(
        "one-parameter edit, model + meshes: p50",
        format!("{:.3} ms", ms(p50)),
        "",
        None,
    ));
    rows.push(row(
        "one-parameter edit, model + meshes: p99",
        format!("{:.3} ms", ms(p99)),
        "≤ 2 ms",
        Some(ms(p99) <= 2.0),
    ));
    // What the slow edits are: how much they mesh, against the others.
    let (slow, quick): (Vec<_>, Vec<_>) = meshed.iter().partition(|(t, _)| ms(*t) > 2.0);
    // "–" for none (a mean of nothing; the float sum of nothing is −0).
    let triangles = |edits: &[&(Duration, u64)]| match edits.len() {
        0 => "–".to_string(),
        n => format!(
            "{:.0}",
            edits.iter().map(|(_, t)| *t as f64).sum::<f64>() / n as f64
        ),
    };
    rows.push(row(
        "  edits over 2 ms: count, mean triangles meshed (others)",
        format!(
            "{} of {}, {} ({})",
            slow.len(),
            meshed.len(),
            triangles(&slow),
            triangles(&quick)
        ),
        "",
        None,
    ));
    rows.push(row(
        "  edit, mean: draw+check+write | Validate | Constrain",
        format!("{:.3} | {:.3} | {:.3} ms", mean[0], mean[1], mean[2]),
        "",
        None,
    ));
    rows.push(row(
        "  edit, mean: Geometry | Tessellate | Project | Export",
        format!(
            "{:.3} | {:.3} | {:.3} | {:.3} ms",
            mean[3], mean[4], mean[5], mean[6]
        ),
        "",
        None,
    ));
    let mut idle: Vec<Duration> = (0..20)
        .map(|_| {
            let start = Instant::now();
            sim.model_mut().update();
            start.elapsed()
        })
        .collect();
    rows.push(row(
        "  update with nothing to do (p50)",
        format!("{:.3} ms", ms(quantile(&mut idle, 0.5))),
        "",
        None,
    ));
    let ratio = t2.as_secs_f64() / p50.as_secs_f64();
    rows.push(row(
        "full build (2 threads) / edit (p50)",
        format!("{ratio:.0}"),
        "≥ 1000",
        Some(ratio >= 1000.0),
    ));

    progress(&format!(
        "{} ticks of {} edits",
        config.ticks, config.tick_edits
    ));
    let mut ticks = Vec::with_capacity(config.ticks);
    let mut tick_sums = StageSums::default();
    two.install(|| {
        for _ in 0..config.ticks {
            let report = sim.tick(config.tick_edits, 0);
            ticks.push(report.latency);
            tick_sums.add(&report);
        }
    });
    let tick50 = quantile(&mut ticks, 0.5);
    let tick_max = quantile(&mut ticks, 1.0);
    rows.push(row(
        &format!("tick of {} edits: p50 (max)", config.tick_edits),
        format!("{:.2} ms ({:.2} ms)", ms(tick50), ms(tick_max)),
        "≤ 20 ms",
        Some(ms(tick50) <= 20.0),
    ));
    rows.push(row(
        "  tick, mean: draw+check+write | V | C | G | T | P | E",
        tick_sums
            .means(config.ticks)
            .map(|m| format!("{m:.1}"))
            .join(" | ")
            + " ms",
        "",
        None,
    ));

    let memory = sim.model().memory();
    if let Some(bytes) = heap_model {
        let per = bytes as f64 / n / 1024.0;
        rows.push(row(
            &format!(
                "memory per vessel (whole model at {} mm, heap)",
                config.tolerance
            ),
            format!("{per:.0} KB"),
            "≤ 500 KB",
            Some(per <= 500.0),
        ));
    }
    let kb = |bytes: usize| format!("{:.0} KB", bytes as f64 / n / 1024.0);
    rows.push(row(
        "  of which meshes",
        format!(
            "{} ({:.0} triangles, {:.0} vertices/vessel; {:.0} % of patches share a mesh)",
            kb(memory.meshes),
            memory.triangles as f64 / n,
            memory.vertices as f64 / n,
            100.0 * memory.patches.saturating_sub(memory.distinct_meshes) as f64
                / memory.patches.max(1) as f64
        ),
        "",
        None,
    ));
    rows.push(row(
        "  of which surfaces, regions, openings, cavities",
        format!(
            "{}, {}, {}, {} ({:.0} patches/vessel)",
            kb(memory.surfaces),
            kb(memory.regions),
            kb(memory.openings),
            kb(memory.cavities),
            memory.patches as f64 / n
        ),
        "",
        None,
    ));

    progress("GLB export");
    let path = scratch.join(format!("vesselcad-bench-{}.glb", std::process::id()));
    let start = Instant::now();
    let scene = sim.model().scene();
    let bytes = stream_glb_to(&scene, &path)?;
    let t = start.elapsed();
    drop(scene);
    let _ = std::fs::remove_file(&path);
    rows.push(row(
        "GLB export (streamed to a file)",
        format!(
            "{:.0} MB/s ({:.0} MB in {:.2} s)",
            bytes as f64 / 1e6 / t.as_secs_f64(),
            bytes as f64 / 1e6,
            t.as_secs_f64()
        ),
        "",
        None,
    ));
    Ok(rows)
}

/// The rows as a text table: figure, target, ✓/✗.
pub fn format_table(rows: &[BenchRow]) -> String {
    let w0 = rows
        .iter()
        .map(|r| r.name.chars().count())
        .max()
        .unwrap_or(0);
    let w1 = rows
        .iter()
        .map(|r| r.value.chars().count())
        .max()
        .unwrap_or(0);
    let mut out = String::new();
    for r in rows {
        let mark = match r.met {
            Some(true) => "met",
            Some(false) => "NOT met",
            None => "",
        };
        let pad0 = w0 - r.name.chars().count();
        let pad1 = w1 - r.value.chars().count();
        out.push_str(&format!(
            "{}{}  {}{}  {:<8} {}\n",
            r.name,
            " ".repeat(pad0),
            r.value,
            " ".repeat(pad1),
            r.target,
            mark
        ));
    }
    out
}

/// The rows as a Markdown table (figure | value | target | met), for BENCHMARKS.md:
/// `vesselcad bench --markdown`. A `|` inside a cell is escaped so that it does not
/// split the cell.
pub fn format_markdown(rows: &[BenchRow]) -> String {
    let cell = |s: &str| s.trim().replace('|', "\\|");
    let mut out = String::from("| Figure | Value | Target | Met |\n|---|---|---|---|\n");
    for r in rows {
        let mark = match r.met {
            Some(true) => "met",
            Some(false) => "**not met**",
            None => "",
        };
        let indent = if r.name.starts_with(' ') { "↳ " } else { "" };
        out.push_str(&format!(
            "| {indent}{} | {} | {} | {mark} |\n",
            cell(&r.name),
            cell(&r.value),
            cell(&r.target)
        ));
    }
    out
}
