//! Earthquake on a vertical vessel by ASCE 7-16's equivalent lateral force
//! procedure (§12.8), as §15.4 applies it to nonbuilding structures.
//!
//! - Seismic response coefficient Cs = SDS/(R/Ie) (Eq. 12.8-2); when the design
//!   gives the period T, at most SD1/(T·R/Ie) (Eq. 12.8-3, T ≤ TL assumed); at
//!   least 0.044·SDS·Ie and 0.03 (Eq. 15.4-1). Without T the plateau is kept:
//!   12.8-3 can only lower it.
//! - Base shear V = Cs·W (Eq. 12.8-1), W the operating weight.
//! - Vertical distribution Fx = V·wx·hx^k / Σ wi·hi^k (Eqs. 12.8-11, 12.8-12);
//!   k = 1 for T ≤ 0.5 s, 2 for T ≥ 2.5 s, linear between; without T, k = 2,
//!   the largest base moment.
//!
//! The weight is given as [`Mass`]es: points (nozzles, supports) and uniform
//! segments (the walls over the stack, the liquid over its depth), whose sums
//! Σ w·h^k and moments are integrated in closed form.

use serde::Serialize;

use crate::design::SeismicDesign;

/// A mass on the vessel's height, heights above the base, mm.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub enum Mass {
    /// A mass (kg) at one height.
    Point {
        /// Height, mm.
        h: f64,
        /// Mass, kg.
        mass: f64,
    },
    /// A mass (kg) spread uniformly from `h0` to `h1` (h0 < h1).
    Uniform {
        /// Bottom, mm.
        h0: f64,
        /// Top, mm.
        h1: f64,
        /// Mass, kg.
        mass: f64,
    },
}

impl Mass {
    /// Total mass, kg.
    pub fn mass(&self) -> f64 {
        match *self {
            Mass::Point { mass, .. } | Mass::Uniform { mass, .. } => mass,
        }
    }

    /// ∫ h^k dm over the part of the mass above `level` (h ≥ level), times
    /// (h − level) when `lever`.
    fn integral(&self, k: f64, level: f64, lever: bool) -> f64 {
        match *self {
            Mass::Point { h, mass } => {
                if h < level || h <= 0.0 {
                    0.0
                } else if lever {
                    mass * h.powf(k) * (h - level)
                } else {
                    mass * h.powf(k)
                }
            }
            Mass::Uniform { h0, h1, mass } => {
                let (a, b) = (h0.max(level).max(0.0), h1);
                if b <= a || h1 <= h0 {
                    return 0.0;
                }
                let rho = mass / (h1 - h0);
                let p = |e: f64| (b.powf(e) - a.powf(e)) / e;
                if lever {
                    rho * (p(k + 2.0) - level * p(k + 1.0))
                } else {
                    rho * p(k + 1.0)
                }
            }
        }
    }
}

/// Cs with the equation that governs.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Coefficient {
    /// Cs.
    pub cs: f64,
    /// The equation that set it, e.g. `12.8-2`.
    pub equation: &'static str,
    /// The distribution exponent k.
    pub k: f64,
}

/// Cs and k of `s` (see the module documentation).
pub fn coefficient(s: &SeismicDesign) -> Coefficient {
    let ie = s.importance.unwrap_or(1.0);
    let ratio = s.response_modification / ie;
    let mut cs = s.sds / ratio;
    let mut equation = "12.8-2";
    if let Some(t) = s.period {
        let cap = s.sd1 / (t * ratio);
        if cap < cs {
            cs = cap;
            equation = "12.8-3";
        }
    }
    let floor = (0.044 * s.sds * ie).max(0.03);
    if cs < floor {
        cs = floor;
        equation = "15.4-1";
    }
    let k = match s.period {
        None => 2.0,
        Some(t) if t <= 0.5 => 1.0,
        Some(t) if t >= 2.5 => 2.0,
        Some(t) => 1.0 + (t - 0.5) / 2.0,
    };
    Coefficient { cs, equation, k }
}

/// The lateral forces Fx of base shear `shear` (N) distributed over `masses` with
/// exponent `k` (Eq. 12.8-11): the shear (N) and overturning moment (N·mm) at
/// `level` mm above the base, from the forces above it.
pub fn shear_and_moment(shear: f64, k: f64, masses: &[Mass], level: f64) -> (f64, f64) {
    let total: f64 = masses.iter().map(|m| m.integral(k, 0.0, false)).sum();
    if total <= 0.0 {
        return (0.0, 0.0);
    }
    let above: f64 = masses.iter().map(|m| m.integral(k, level, false)).sum();
    let lever: f64 = masses.iter().map(|m| m.integral(k, level, true)).sum();
    (shear * above / total, shear * lever / total)
}

/// The lateral force Fx (N) on each of `masses` (Eq. 12.8-11).
pub fn forces(shear: f64, k: f64, masses: &[Mass]) -> Vec<f64> {
    let total: f64 = masses.iter().map(|m| m.integral(k, 0.0, false)).sum();
    masses
        .iter()
        .map(|m| {
            if total > 0.0 {
                shear * m.integral(k, 0.0, false) / total
            } else {
                0.0
            }
        })
        .collect()
}
