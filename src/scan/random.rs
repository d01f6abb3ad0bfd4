//! The deterministic random numbers of `scan simulate`: the plant generator's
//! SplitMix64 ([`crate::plant::rng`]), with normal deviates by the Box–Muller
//! transform: the same seed gives the same scan on every platform and release.

use crate::plant::rng::SplitMix64;

/// The plant generator's SplitMix64 with normal deviates.
#[derive(Clone, Debug)]
pub struct Random {
    bits: SplitMix64,
    spare: Option<f64>,
}

impl Random {
    /// A generator from a seed.
    pub fn new(seed: u64) -> Self {
        Self {
            bits: SplitMix64::new(seed ^ 0x5DEE_CE66_D1CE_4E5B),
            spare: None,
        }
    }

    /// The next 64 random bits.
    pub fn next_u64(&mut self) -> u64 {
        self.bits.next_u64()
    }

    /// A uniform double in [0, 1).
    pub fn uniform(&mut self) -> f64 {
        self.bits.unit()
    }

    /// A standard normal deviate (Box–Muller, the second of each pair kept).
    pub fn normal(&mut self) -> f64 {
        if let Some(z) = self.spare.take() {
            return z;
        }
        let u1 = 1.0 - self.uniform();
        let u2 = self.uniform();
        let r = (-2.0 * u1.ln()).sqrt();
        let (s, c) = (std::f64::consts::TAU * u2).sin_cos();
        self.spare = Some(r * s);
        r * c
    }
}

/// A hash of a cell index and a seed to [0, 1): occlusion masks that do not
/// depend on the order points are drawn in.
pub fn cell_hash(seed: u64, i: i64, j: i64) -> f64 {
    let mut r = Random::new(
        seed ^ (i as u64).wrapping_mul(0x9E37_79B9_7F4A_7C15)
            ^ (j as u64).wrapping_mul(0xC2B2_AE3D_27D4_EB4F),
    );
    r.next_u64();
    r.uniform()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn same_seed_same_numbers_and_normal_moments() {
        let mut a = Random::new(7);
        let mut b = Random::new(7);
        assert_eq!(a.next_u64(), b.next_u64());
        let n = 100_000;
        let xs: Vec<f64> = (0..n).map(|_| a.normal()).collect();
        let mean = xs.iter().sum::<f64>() / n as f64;
        let var = xs.iter().map(|x| (x - mean).powi(2)).sum::<f64>() / n as f64;
        assert!(mean.abs() < 0.02, "{mean}");
        assert!((var - 1.0).abs() < 0.02, "{var}");
    }
}
