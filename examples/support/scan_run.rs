//! What the scan examples share: CPU time of the process, timing a step, and
//! the simulated scan of the test drum (`tests/common/scan.rs`).

use std::time::Instant;

use glam::DVec3;
use vesselcad::scan::Envelope;
use vesselcad::scan::simulate::{SimulateOptions, simulate};

/// CPU seconds of this process so far (user + system), from /proc: on a
/// shared, loaded machine the wall clock measures the queue.
pub fn cpu() -> f64 {
    let stat = std::fs::read_to_string("/proc/self/stat").unwrap_or_default();
    let after = stat.rsplit(')').next().unwrap_or("");
    let fields: Vec<&str> = after.split_whitespace().collect();
    let ticks = |i: usize| {
        fields
            .get(i)
            .and_then(|s| s.parse::<f64>().ok())
            .unwrap_or(0.0)
    };
    (ticks(11) + ticks(12)) / 100.0
}

/// Wall and CPU seconds of `f`.
pub fn timed<T>(f: impl FnOnce() -> T) -> (T, f64, f64) {
    let (t, c) = (Instant::now(), cpu());
    let out = f();
    (out, t.elapsed().as_secs_f64(), cpu() - c)
}

/// A defect-free scan of `env` at `density` points per m², noise 1 mm, no
/// gaps, seed 5, plant frame.
pub fn points(env: &Envelope, density: f64) -> Vec<DVec3> {
    let options = SimulateOptions {
        density,
        noise: 1.0,
        occlusion: 0.0,
        seed: 5,
        site: None,
        defects: Vec::new(),
    };
    simulate(env, &options).expect("simulates").points
}
