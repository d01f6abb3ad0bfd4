//! Random designs near the examples for the check-agrees-with-build property
//! (issue 30 §1): several numeric fields of an example design set at once to
//! values across their allowed ranges — lengths scaled from a tenth to four
//! times, angles anywhere round the circle, ellipsoidal ratios over their whole
//! range, sizes and ratings from their tables, zero positions moved off zero.
//! Shared by `tests/design_build_fuzz.rs` (a few hundred cases in CI) and
//! `examples/check_build_fuzz.rs` (thousands).

use serde_json::Value;

/// SplitMix64: a fixed-seed generator, so that a case is its seed.
pub struct Rng(pub u64);

impl Rng {
    pub fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        z ^ (z >> 31)
    }

    /// Uniform in [0, 1).
    pub fn unit(&mut self) -> f64 {
        (self.next_u64() >> 11) as f64 / (1u64 << 53) as f64
    }

    /// Uniform in [lo, hi).
    pub fn range(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * self.unit()
    }

    /// One of `items`.
    pub fn pick<'a, T>(&mut self, items: &'a [T]) -> &'a T {
        &items[(self.next_u64() % items.len() as u64) as usize]
    }
}

const SIZES: [f64; 16] = [
    0.5, 0.75, 1.0, 1.5, 2.0, 3.0, 4.0, 6.0, 8.0, 10.0, 12.0, 14.0, 16.0, 18.0, 20.0, 24.0,
];
const RATINGS: [f64; 4] = [150.0, 300.0, 600.0, 900.0];

/// Every numeric leaf of `value` as (JSON pointer, key, value).
fn leaves(value: &Value, here: String, key: &str, out: &mut Vec<(String, String, f64)>) {
    match value {
        Value::Object(map) => {
            for (k, v) in map {
                leaves(v, format!("{here}/{k}"), k, out);
            }
        }
        Value::Array(items) => {
            for (i, v) in items.iter().enumerate() {
                leaves(v, format!("{here}/{i}"), key, out);
            }
        }
        Value::Number(n) => out.push((here, key.to_string(), n.as_f64().unwrap_or(0.0))),
        _ => {}
    }
}

/// A new value for a field named `key` that held `x`, across its range.
fn perturbed_value(rng: &mut Rng, key: &str, x: f64) -> f64 {
    match key {
        "orientation" | "rotation" => rng.range(0.0, 360.0).round(),
        "size" => *rng.pick(&SIZES),
        "rating" => *rng.pick(&RATINGS),
        "ratio" => rng.range(1.0, 3.0),
        "half_angle" => rng.range(1.0, 89.0),
        _ if x == 0.0 => rng.range(0.0, 2000.0).round(),
        _ => {
            let f = rng.range(0.1f64.ln(), 4.0f64.ln()).exp();
            // Whole millimetres most of the time, as designers write them.
            if rng.unit() < 0.8 {
                (x * f).round()
            } else {
                x * f
            }
        }
    }
}

/// `design` with one to four numeric fields perturbed; returns the edits made
/// (pointer, old, new) for messages.
pub fn perturb(design: &mut Value, rng: &mut Rng) -> Vec<(String, f64, f64)> {
    let mut all = Vec::new();
    leaves(design, String::new(), "", &mut all);
    let count = 1 + (rng.next_u64() % 4) as usize;
    let mut made = Vec::new();
    for _ in 0..count {
        let (pointer, key, old) = rng.pick(&all).clone();
        let new = perturbed_value(rng, &key, old);
        if let Some(slot) = design.pointer_mut(&pointer) {
            *slot = if new.fract() == 0.0 && new.abs() < 1e15 {
                Value::from(new as i64)
            } else {
                Value::from(new)
            };
            made.push((pointer, old, new));
        }
    }
    made
}
