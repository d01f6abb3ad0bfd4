//! Wind on a vertical vessel by ASCE 7-16: the velocity pressure
//! qz = 0.613·Kz·Kzt·Kd·I·V² (Pa, V in m/s; Eq. 26.10-1 with the design's
//! importance factor, 1.0 unless given) and the force qz·G·Cf on the projected
//! area (Eq. 29.4-1), integrated exactly over the vessel's height.
//!
//! Kz = 2.01·(z/zg)^(2/α) for 15 ft ≤ z ≤ zg and Kz(15 ft) below (Table
//! 26.10-1, footnote; α and zg of Table 26.11-1: B 7.0 and 1200 ft, C 9.5 and
//! 900 ft, D 11.5 and 700 ft). z is the height above grade: the vessel's
//! lowest point stands at the design's `base_elevation` (default 0, at grade).
//!
//! The vessel's outline is a stack of [`Band`]s of constant projected width
//! (the design's `area_factor` times the outside diameter: a head counts as its
//! outside diameter over its depth, a reducer as its larger end — each the safe
//! side of its silhouette). Over a band, the force and its moment about a level
//! are ∫ qz·G·Cf·w dz and ∫ qz·G·Cf·w·(z − level) dz, in closed form since qz is a
//! power of z.

use serde::Serialize;

use crate::design::{Exposure, WindDesign};

/// 15 ft in mm: below it, Kz is taken at 15 ft.
pub const Z_MIN: f64 = 4572.0;

/// Default directionality factor Kd: round chimneys and tanks (Table 26.6-1).
pub const DEFAULT_KD: f64 = 0.95;
/// Default gust-effect factor G: rigid structure (§26.11.1).
pub const DEFAULT_G: f64 = 0.85;
/// Default force coefficient Cf: round, moderately smooth, h/D = 25 (Fig. 29.4-1).
pub const DEFAULT_CF: f64 = 0.7;

/// α and zg (mm) of an exposure category (ASCE 7-16 Table 26.11-1).
pub fn terrain(exposure: Exposure) -> (f64, f64) {
    const FT: f64 = 304.8;
    match exposure {
        Exposure::B => (7.0, 1200.0 * FT),
        Exposure::C => (9.5, 900.0 * FT),
        Exposure::D => (11.5, 700.0 * FT),
    }
}

/// The velocity pressure exposure coefficient Kz at `z` mm above grade.
pub fn kz(exposure: Exposure, z: f64) -> f64 {
    let (alpha, zg) = terrain(exposure);
    2.01 * (z.clamp(Z_MIN, zg) / zg).powf(2.0 / alpha)
}

/// The design's wind factors with their defaults filled in.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct WindFactors {
    /// Basic wind speed, m/s.
    pub speed: f64,
    /// Exposure category.
    pub exposure: Exposure,
    /// Importance factor on qz.
    pub importance: f64,
    /// Kzt.
    pub kzt: f64,
    /// Kd.
    pub kd: f64,
    /// G.
    pub gust: f64,
    /// Cf.
    pub cf: f64,
    /// Factor on the projected width.
    pub area_factor: f64,
}

impl WindFactors {
    /// The factors of `w`, defaults where it gives none.
    pub fn of(w: &WindDesign) -> WindFactors {
        WindFactors {
            speed: w.speed,
            exposure: w.exposure,
            importance: w.importance.unwrap_or(1.0),
            kzt: w.topographic_factor.unwrap_or(1.0),
            kd: w.directionality_factor.unwrap_or(DEFAULT_KD),
            gust: w.gust_factor.unwrap_or(DEFAULT_G),
            cf: w.force_coefficient.unwrap_or(DEFAULT_CF),
            area_factor: w.area_factor.unwrap_or(1.0),
        }
    }

    /// qz at `z` mm above grade, Pa (N/m²).
    pub fn qz(&self, z: f64) -> f64 {
        0.613 * kz(self.exposure, z) * self.kzt * self.kd * self.importance * self.speed.powi(2)
    }

    /// The force per unit area, qz·G·Cf, at `z` mm above grade, Pa.
    pub fn pressure(&self, z: f64) -> f64 {
        self.qz(z) * self.gust * self.cf
    }
}

/// A horizontal band of the vessel's outline, heights above grade, mm.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Band {
    /// What it is, e.g. `C-201/S1`.
    #[serde(skip)]
    pub id: &'static str,
    /// Bottom, mm above grade.
    pub bottom: f64,
    /// Top, mm above grade.
    pub top: f64,
    /// Projected width (before the area factor), mm.
    pub width: f64,
}

/// The wind's shear (N) and moment (N·mm) about the horizontal plane at `level`
/// mm above grade, from the part of every band above it.
pub fn shear_and_moment(f: &WindFactors, bands: &[Band], level: f64) -> (f64, f64) {
    let (alpha, zg) = terrain(f.exposure);
    let p = 2.0 / alpha;
    // Force per unit area = c·z^p above Z_MIN (z ≤ zg), constant below.
    let c =
        0.613 * 2.01 * f.kzt * f.kd * f.importance * f.speed.powi(2) * f.gust * f.cf / zg.powf(p);
    let low = f.pressure(Z_MIN);
    let mut shear = 0.0;
    let mut moment = 0.0;
    for b in bands {
        let w = b.width * f.area_factor * 1e-6; // N per (Pa·mm)
        let (z0, z1) = (b.bottom.max(level).max(0.0), b.top.min(zg));
        if z1 <= z0 {
            continue;
        }
        // Constant part, below Z_MIN.
        let (a0, a1) = (z0, z1.min(Z_MIN));
        if a1 > a0 {
            shear += low * w * (a1 - a0);
            moment += low * w * ((a1 - level).powi(2) - (a0 - level).powi(2)) / 2.0;
        }
        // Power part: ∫ c z^p dz and ∫ c z^p (z − level) dz.
        let (b0, b1) = (z0.max(Z_MIN), z1);
        if b1 > b0 {
            let int = |k: f64| (b1.powf(p + k) - b0.powf(p + k)) / (p + k);
            shear += c * w * int(1.0);
            moment += c * w * (int(2.0) - level * int(1.0));
        }
    }
    (shear, moment)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A band split anywhere gives the same force and moment (the integrals add).
    #[test]
    fn split_bands_add_up() {
        let f = WindFactors::of(&WindDesign {
            speed: 45.0,
            exposure: Exposure::C,
            importance: None,
            topographic_factor: None,
            directionality_factor: None,
            gust_factor: None,
            force_coefficient: None,
            area_factor: Some(1.2),
            base_elevation: None,
        });
        let whole = [Band {
            id: "a",
            bottom: 1000.0,
            top: 40000.0,
            width: 2000.0,
        }];
        let split = [
            Band {
                top: 7000.0,
                ..whole[0]
            },
            Band {
                bottom: 7000.0,
                ..whole[0]
            },
        ];
        for level in [0.0, 3000.0, 12000.0] {
            let (a, b) = (
                shear_and_moment(&f, &whole, level),
                shear_and_moment(&f, &split, level),
            );
            assert!((a.0 - b.0).abs() < 1e-9 * a.0 && (a.1 - b.1).abs() < 1e-9 * a.1);
        }
        // Numerical check of the closed form: midpoint rule, 200 000 steps.
        let n = 200_000;
        let (mut v, mut m) = (0.0, 0.0);
        for i in 0..n {
            let dz = 39000.0 / n as f64;
            let z = 1000.0 + (i as f64 + 0.5) * dz;
            let q = f.pressure(z) * 2000.0 * 1.2 * 1e-6 * dz;
            v += q;
            m += q * z;
        }
        let (s, mo) = shear_and_moment(&f, &whole, 0.0);
        assert!((s - v).abs() < 1e-6 * v, "{s} {v}");
        assert!((mo - m).abs() < 1e-6 * m, "{mo} {m}");
    }
}
