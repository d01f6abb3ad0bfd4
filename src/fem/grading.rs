//! Graded layers across a span: the positions of element rows between two
//! edges whose neighbours have given sizes (a nozzle's intersection curve and
//! its window's boundary, a cap's inner grid and its rim). The size field is
//! `h(x) = min(cap, first + GROWTH·(x − first)⁺, last + GROWTH·(span − x − last)⁺)`,
//! so the row at either edge takes that edge's neighbour size and rows grow
//! away from it by at most
//! [`GROWTH`] of their own size per row; the row count is ∫ dx/h rounded up
//! and the rows equidistribute that integral, so every row is at most its
//! field size and at least `(∫/count)` of it. Sizes measured as √area then
//! differ from their neighbours' (across either edge and within the span) by
//! well under the mesh's 1.5.

/// Growth of the size field per unit length (h grows by this per mm).
pub const GROWTH: f64 = 0.5;

/// The growth of a nozzle's ring ([`super::nozzle`]) where its window has room
/// for it: the ring's elements grow along the ring and across it at once, so
/// at [`GROWTH`] neighbours across a layer differed by up to 1.6–1.8 (√area) on
/// the example drum and column; at 0.35 by at most 1.46 on the column and
/// 1.52 on the drum.
pub const RING_GROWTH: f64 = 0.35;

/// Samples of the integral.
const SAMPLES: usize = 256;

/// Row positions 0 = `x₀` < … < `x_count` = 1, as fractions of `span`, for a
/// span whose neighbour at 0 has size `first`, at 1 size `last`, and rows no
/// larger than `cap` (all in mm). A span not wider than 1.5 of its edges'
/// sizes is one row.
pub fn layers(span: f64, first: f64, last: f64, cap: f64) -> Vec<f64> {
    layers_at(span, first, last, cap, GROWTH)
}

/// [`layers`] with the size field growing by `growth` (per mm) instead of
/// [`GROWTH`].
pub fn layers_at(span: f64, first: f64, last: f64, cap: f64, growth: f64) -> Vec<f64> {
    let floor = 1e-9 * span.abs().max(1.0);
    let (first, last) = (first.max(floor), last.max(floor));
    let cap = cap.max(first.min(last));
    if span.is_nan() || span <= 1.5 * first.min(last) {
        return vec![0.0, 1.0];
    }
    let h = |x: f64| {
        (first + growth * (x - first).max(0.0))
            .min(last + growth * (span - x - last).max(0.0))
            .min(cap)
    };
    let mut cum = Vec::with_capacity(SAMPLES + 1);
    cum.push(0.0);
    for k in 0..SAMPLES {
        let x = span * (k as f64 + 0.5) / SAMPLES as f64;
        let prev = cum[k];
        cum.push(prev + span / SAMPLES as f64 / h(x));
    }
    let total = cum[SAMPLES];
    let count = (total - 1e-6).ceil().max(1.0) as usize;
    let mut out = Vec::with_capacity(count + 1);
    out.push(0.0);
    for i in 1..count {
        let target = total * i as f64 / count as f64;
        let j = cum.partition_point(|&c| c < target).clamp(1, SAMPLES);
        let f = (target - cum[j - 1]) / (cum[j] - cum[j - 1]).max(f64::MIN_POSITIVE);
        out.push(((j - 1) as f64 + f) / SAMPLES as f64);
    }
    out.push(1.0);
    out
}
