//! Tank settlement by API 653 Annex B, from a fitted scan: the bottom edge's
//! elevation at (at least 8, at most 32 ft = 9.75 m apart) stations, each found
//! by maximum likelihood from the shell points just above it, fitted by a
//! cosine (the planar tilt) with its R²; each station's out-of-plane settlement
//! against B.3.2.1's allowable. Part of the checks (`checks::check`).
//!
//! Annex B fits the cosine by least squares to stations surveyed alike; a scan's
//! stations are not alike (a gap left by scaffolding can leave one a third of
//! its points), so each is weighed by 1/u² of its [`station_uncertainty`]. The
//! lowest point of a cosine is where it is flattest: its orientation is only as
//! good as u / (A·√(N/2)) radians (N stations, amplitude A), about 100 mm of arc
//! on a 6 m tank settled 40 mm when its stations are read to 3 mm (200 points/m²
//! at 1.5 mm noise), 40 mm at 1000 points/m².

use std::f64::consts::{PI, TAU};

use glam::DVec3;
use serde::Serialize;

use super::band::least_squares;
use super::envelope::{Envelope, Role};

/// The tank bottom's cosine settlement fit.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Settlement {
    /// Station orientations, degrees.
    pub stations: Vec<f64>,
    /// Measured bottom-edge elevations, mm.
    pub elevations: Vec<f64>,
    /// Cosine amplitude, mm.
    pub amplitude: f64,
    /// Orientation of the lowest point, degrees.
    pub lowest: f64,
    /// Coefficient of determination of the cosine fit.
    pub r_squared: f64,
    /// Out-of-plane settlement S_i of each station: its elevation less the
    /// cosine's, mm.
    pub deviations: Vec<f64>,
    /// Largest |S_i|, mm.
    pub out_of_plane: f64,
    /// Standard uncertainty of each station's edge elevation, mm: the mean gap
    /// between points up the shell there (1/λ, λ points per mm of height) and
    /// √(σ/λ), the noise σ over the √(λσ) points within σ of the edge (an edge
    /// is read from those only), added in quadrature.
    pub station_uncertainties: Vec<f64>,
    /// The worst station's standard uncertainty, mm. Out-of-plane settlement is
    /// reported past three of these.
    pub uncertainty: f64,
    /// Arc length L between stations, mm.
    pub spacing: f64,
    /// Tank shell height H, mm.
    pub height: f64,
    /// API 653 B.3.2.1's largest permissible out-of-plane deflection,
    /// S_max = 11·L²·Y / (2·E·H), mm; `None` without the shell's Y and E.
    pub allowable: Option<f64>,
    /// Whether the cosine represents the settlement (R² ≥ 0.9, B.2.2.4); when
    /// not, B.2.2.5's evaluation applies instead.
    pub cosine_valid: bool,
}

/// API 653 Annex B's least R² for the optimum cosine curve to stand for the
/// tank's rigid tilt.
pub const COSINE_R_SQUARED: f64 = 0.9;

/// API 653 B.3.2.1: the largest permissible out-of-plane deflection of the shell,
/// S_max = 11·L²·Y / (2·E·H) (L the arc length between stations and H the tank
/// height, mm; Y the shell's yield strength and E its modulus, MPa), mm.
pub fn allowable_out_of_plane(spacing: f64, height: f64, yield_strength: f64, modulus: f64) -> f64 {
    11.0 * spacing * spacing * yield_strength / (2.0 * modulus * height)
}

/// The standard normal distribution function (Abramowitz & Stegun 7.1.26,
/// error under 1.5e-7).
fn normal_cdf(x: f64) -> f64 {
    let z = x.abs() / std::f64::consts::SQRT_2;
    let t = 1.0 / (1.0 + 0.327_591_1 * z);
    let poly = t
        * (0.254_829_592
            + t * (-0.284_496_736
                + t * (1.421_413_741 + t * (-1.453_152_027 + t * 1.061_405_429))));
    let erf = 1.0 - poly * (-z * z).exp();
    if x >= 0.0 {
        0.5 * (1.0 + erf)
    } else {
        0.5 * (1.0 - erf)
    }
}

/// Height above an edge over which [`edge_by_likelihood`] reads points, mm.
pub const EDGE_WINDOW: f64 = 200.0;

/// The standard uncertainty (mm) of an edge read by [`edge_by_likelihood`] from
/// `count` points in the [`EDGE_WINDOW`] above it with noise `sigma`: the mean
/// gap 1/λ between points up the shell (λ = count / window, points per mm of
/// height; the edge of a sharp cut is that far below its lowest point, give or
/// take as much) and √(σ/λ) (noise σ over the √(λσ) points within σ of the
/// edge, the only ones that place it), in quadrature: within 16 % of the RMS
/// error from 30 to 3000 points by simulation, checked at 40 and 400 by
/// `tests/scan_inspect.rs`.
pub fn station_uncertainty(count: usize, sigma: f64) -> f64 {
    let gap = EDGE_WINDOW / count.max(1) as f64;
    gap.hypot((sigma * gap).sqrt())
}

/// The elevation of the edge below which a shell has no points, from heights
/// `z` (relative to the current model) near a first guess `guess`: points lie
/// uniformly above the edge, blurred by Gaussian noise `sigma`, so each has the
/// likelihood Φ((z − e)/σ) / (top − e) within a window of top `guess + 200`;
/// the edge is the maximum, searched at 0.05 mm over ±(10σ + 10) mm.
pub fn edge_by_likelihood(z: &[f64], guess: f64, sigma: f64) -> f64 {
    let top = guess + EDGE_WINDOW;
    let near: Vec<f64> = z.iter().copied().filter(|&v| v < top).collect();
    let reach = 10.0 * sigma + 10.0;
    let steps = (2.0 * reach / 0.05).ceil() as usize;
    let mut best = (f64::NEG_INFINITY, guess);
    for k in 0..=steps {
        let e = guess - reach + 0.05 * k as f64;
        let a = (top - e) / sigma;
        let mass = (top - e) * normal_cdf(a) + sigma * (-0.5 * a * a).exp() / (2.0 * PI).sqrt();
        let l: f64 = near
            .iter()
            .map(|&v| normal_cdf((v - e) / sigma).max(1e-300).ln())
            .sum::<f64>()
            - near.len() as f64 * mass.max(1e-300).ln();
        if l > best.0 {
            best = (l, e);
        }
    }
    best.1
}

/// The bottom edge of a tank's lowest course, by API 653 Annex B stations.
pub(super) fn settlement(envelope: &Envelope, points: &[DVec3], noise: f64) -> Option<Settlement> {
    let (_, part) = envelope
        .parts
        .iter()
        .enumerate()
        .filter(|(_, p)| p.role == Role::Course)
        .min_by(|a, b| a.1.span.0.total_cmp(&b.1.span.0))?;
    let d = part.diameter;
    let band = 300.0_f64.min(0.5 * (part.span.1 - part.span.0));
    const EDGE_POINTS: usize = 8;
    // Points of the shell near its bottom, by distance from the axis: those
    // below the design's bottom (the low side) project off the course.
    let edge: Vec<(f64, f64)> = points
        .iter()
        .filter(|p| {
            let r = p.x.hypot(p.y);
            (r - d / 2.0).abs() < 0.02 * d + 20.0
                && p.z < part.span.0 + 3.0 * band
                && p.z > part.span.0 - 3.0 * band
        })
        .map(|p| (p.y.atan2(p.x), p.z))
        .collect();
    let stations = ((PI * d / 9754.0).ceil() as usize).max(8);
    let mut model = [part.span.0, 0.0, 0.0];
    let at = |m: &[f64; 3], t: f64| m[0] + m[1] * t.cos() + m[2] * t.sin();
    let mut values = vec![f64::NAN; stations];
    let mut uncertainties = vec![f64::INFINITY; stations];
    let mut uncertainty: f64 = 0.0;
    for _ in 0..6 {
        uncertainty = 0.0;
        let width = TAU / stations as f64;
        for (k, (value, u)) in values.iter_mut().zip(&mut uncertainties).enumerate() {
            let centre = k as f64 * width;
            // The edge from the lowest points of the station, heights taken
            // relative to the current model: the lowest less the mean gap of
            // the next ones (points fall uniformly above an edge).
            let mut lowest: Vec<f64> = edge
                .iter()
                .filter(|(t, _)| super::defects::wrap(t - centre).abs() <= 0.5 * width)
                .map(|&(t, z)| z - at(&model, t))
                .collect();
            lowest.sort_by(f64::total_cmp);
            let k = lowest.len().min(EDGE_POINTS);
            *value = if k < 3 {
                f64::NAN
            } else {
                let guess = lowest[0] - (lowest[k - 1] - lowest[0]) / (k - 1) as f64;
                let sigma = noise.max(0.05);
                let edge = edge_by_likelihood(&lowest, guess, sigma);
                let n = lowest
                    .iter()
                    .filter(|&&z| z >= edge && z < edge + EDGE_WINDOW)
                    .count();
                *u = station_uncertainty(n, sigma);
                uncertainty = uncertainty.max(*u);
                at(&model, centre) + edge
            };
        }
        let rows: Vec<[f64; 5]> = (0..stations)
            .map(|k| {
                let t = k as f64 * width;
                [1.0, t.cos(), t.sin(), 0.0, 0.0]
            })
            .collect();
        // Each station weighed by its precision (a gap in the scan makes one
        // station's edge several times worse than the others').
        let weights: Vec<f64> = values
            .iter()
            .zip(&uncertainties)
            .map(|(v, u)| if v.is_nan() { 0.0 } else { u.powi(-2) })
            .collect();
        let clean: Vec<f64> = values
            .iter()
            .map(|v| if v.is_nan() { 0.0 } else { *v })
            .collect();
        let c = least_squares(&rows, &clean, &weights, 3)?;
        model = [c[0], c[1], c[2]];
    }
    let width = TAU / stations as f64;
    let known: Vec<(f64, f64, f64)> = values
        .iter()
        .zip(&uncertainties)
        .enumerate()
        .filter(|(_, (v, _))| !v.is_nan())
        .map(|(k, (&v, &u))| (k as f64 * width, v, u))
        .collect();
    if known.len() < 4 {
        return None;
    }
    let mean = known.iter().map(|k| k.1).sum::<f64>() / known.len() as f64;
    let total: f64 = known.iter().map(|k| (k.1 - mean).powi(2)).sum();
    let residual: f64 = known.iter().map(|k| (k.1 - at(&model, k.0)).powi(2)).sum();
    let out_of_plane = known
        .iter()
        .map(|k| (k.1 - at(&model, k.0)).abs())
        .fold(0.0, f64::max);
    let low = model[2].atan2(model[1]) + PI;
    let spacing = PI * d / stations as f64;
    let height = envelope
        .parts
        .iter()
        .filter(|p| p.role == Role::Course)
        .map(|p| p.span.1)
        .fold(part.span.0, f64::max)
        - part.span.0;
    let r_squared = if total > 0.0 {
        1.0 - residual / total
    } else {
        0.0
    };
    Some(Settlement {
        stations: known
            .iter()
            .map(|k| envelope.orientation_of(DVec3::new(k.0.cos(), k.0.sin(), 0.0)))
            .collect(),
        elevations: known.iter().map(|k| k.1).collect(),
        amplitude: model[1].hypot(model[2]),
        lowest: envelope.orientation_of(DVec3::new(low.cos(), low.sin(), 0.0)),
        r_squared,
        deviations: known.iter().map(|k| k.1 - at(&model, k.0)).collect(),
        out_of_plane,
        station_uncertainties: known.iter().map(|k| k.2).collect(),
        uncertainty,
        spacing,
        height,
        allowable: envelope
            .material
            .as_ref()
            .map(|m| allowable_out_of_plane(spacing, height, m.yield_strength, m.modulus)),
        cosine_valid: r_squared >= COSINE_R_SQUARED,
    })
}
