//! Registration: the rigid motion that brings a scan from its site frame into the
//! vessel frame, by ICP with point-to-surface distances on the exact NURBS.
//!
//! Each iteration projects the moved points on the design (courses, heads, cones
//! and nozzles: on a body of revolution only the nozzles fix the turn about its
//! axis), keeps the [`RegisterOptions::keep`] fraction with the smallest distance
//! (trimmed ICP: nozzle stubs, scaffolding and other objects are outliers), and
//! solves the point-to-plane least squares linearized about the kept points'
//! centroid; the inlier distance shrinks from 150 mm to 2.5 robust sigmas. A levelled scanner (the default, as terrestrial scanners with a
//! tilt compensator are) leaves four unknowns: the turn about plant up and the
//! shift; `levelled: false` frees all six (a tilted vessel is then turned
//! upright, so do not use it to measure plumbness).
//!
//! The turn about plant up is searched (see [`register`]); the last ICP runs on
//! up to [`MAX_POINTS`] points.

use glam::{DAffine3, DMat3, DVec3};
use rayon::prelude::*;
use serde::Serialize;

use super::ScanError;
use super::band::solve_dense;
use super::envelope::Envelope;
use super::features::off_envelope;
use super::project::Targets;
use super::simulate::{SimulateOptions, simulate};

/// Points used by the final ICP (an even stride of the scan).
pub const MAX_POINTS: usize = 40_000;

/// Fewest points a registration runs on.
pub const MIN_POINTS: usize = 50;

/// Fewest features (points off the envelope) the turns are ranked on.
const MIN_FEATURES: usize = 10;

/// How to register.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RegisterOptions {
    /// Only a turn about plant up and a shift (a levelled scanner).
    pub levelled: bool,
    /// Fraction of points kept each iteration (the rest are outliers), 0.5 to 1.
    pub keep: f64,
    /// Iterations of the final ICP.
    pub iterations: usize,
}

impl RegisterOptions {
    /// Levelled, 90 % kept, 60 iterations.
    pub const DEFAULT: Self = Self {
        levelled: true,
        keep: 0.9,
        iterations: 60,
    };
}

/// The registration found.
#[derive(Clone, Copy, Debug, Serialize)]
pub struct Registration {
    /// Site → vessel frame.
    #[serde(skip)]
    pub to_vessel: DAffine3,
    /// Site → plant, as a row-major 3×4 matrix (mm).
    pub site_to_plant: [[f64; 4]; 3],
    /// Turn of site → plant about plant up, degrees (levelled).
    pub yaw: f64,
    /// RMS of the kept points' distances, mm.
    pub rms: f64,
    /// Points used, and kept in the last iteration.
    pub used: usize,
    /// Points kept.
    pub kept: usize,
    /// Iterations run.
    pub iterations: usize,
    /// Whether the given frame was kept (no registration run).
    pub kept_frame: bool,
}

impl Registration {
    /// The identity registration of a scan already in plant coordinates.
    pub fn keep_frame(envelope: &Envelope) -> Self {
        Self::from_vessel(envelope.frame.inverse(), envelope, 0.0, 0, 0, 0, true)
    }

    fn from_vessel(
        to_vessel: DAffine3,
        envelope: &Envelope,
        rms: f64,
        used: usize,
        kept: usize,
        iterations: usize,
        kept_frame: bool,
    ) -> Self {
        let plant = envelope.frame * to_vessel;
        let m = plant.matrix3;
        let t = plant.translation;
        let x = m * DVec3::X;
        Self {
            to_vessel,
            site_to_plant: [
                [m.x_axis.x, m.y_axis.x, m.z_axis.x, t.x],
                [m.x_axis.y, m.y_axis.y, m.z_axis.y, t.y],
                [m.x_axis.z, m.y_axis.z, m.z_axis.z, t.z],
            ],
            yaw: x.y.atan2(x.x).to_degrees(),
            rms,
            used,
            kept,
            iterations,
            kept_frame,
        }
    }
}

/// One ICP run's state.
struct Run {
    to_vessel: DAffine3,
    rms: f64,
    kept: usize,
    iterations: usize,
}

/// Truncation of the candidate score, mm.
const SCORE_CUTOFF: f64 = 50.0;

/// Smallest inlier distance of an ICP iteration, mm.
const MIN_CUTOFF: f64 = 5.0;

/// Inlier distance of the first ICP iteration, mm.
const START_CUTOFF: f64 = 150.0;

/// Residuals (signed point-to-plane distances) of `points` moved by `to_vessel`,
/// with the moved points and normals; points off every patch are left out.
fn residuals(
    envelope: &Envelope,
    points: &[DVec3],
    to_vessel: DAffine3,
    margin: f64,
) -> Vec<(f64, DVec3, DVec3)> {
    let moved: Vec<DVec3> = points
        .iter()
        .map(|&p| to_vessel.transform_point3(p))
        .collect();
    let feet = envelope.project_all(&moved, Targets::WithNozzles, margin);
    moved
        .iter()
        .zip(&feet)
        .filter_map(|(&x, f)| f.map(|f| ((x - f.point).dot(f.normal), x, f.normal)))
        .collect()
}

/// Mean truncated squared residual: what a candidate start is ranked by.
fn score(envelope: &Envelope, points: &[DVec3], to_vessel: DAffine3, margin: f64) -> f64 {
    let r = residuals(envelope, points, to_vessel, margin);
    let missing = points.len() - r.len();
    (r.iter()
        .map(|p| p.0 * p.0)
        .map(|x| x.min(SCORE_CUTOFF * SCORE_CUTOFF))
        .sum::<f64>()
        + missing as f64 * SCORE_CUTOFF * SCORE_CUTOFF)
        / points.len().max(1) as f64
}

/// ICP from `start`: inliers within a distance that shrinks from `cutoffs.0`
/// to 2.5 robust sigmas (at least `cutoffs.1`), of which the `keep` fraction
/// nearest is used.
fn icp(
    envelope: &Envelope,
    points: &[DVec3],
    start: DAffine3,
    options: &RegisterOptions,
    iterations: usize,
    margin: f64,
    cutoffs: (f64, f64),
) -> Run {
    let mut to_vessel = start;
    let mut run = Run {
        to_vessel,
        rms: f64::INFINITY,
        kept: 0,
        iterations: 0,
    };
    let up = envelope.up;
    let mut cutoff = cutoffs.0;
    for iteration in 0..iterations {
        let mut pairs = residuals(envelope, points, to_vessel, margin);
        pairs.retain(|p| p.0.abs() <= cutoff);
        if pairs.len() < MIN_POINTS {
            return run;
        }
        pairs.sort_by(|a, b| a.0.abs().total_cmp(&b.0.abs()));
        let sigma = 1.4826 * pairs[pairs.len() / 2].0.abs();
        cutoff = (2.5 * sigma).max(cutoffs.1).min(cutoff);
        let kept =
            ((pairs.len() as f64 * options.keep).ceil() as usize).clamp(MIN_POINTS, pairs.len());
        let pairs = &pairs[..kept];
        let rms = (pairs.iter().map(|p| p.0 * p.0).sum::<f64>() / kept as f64).sqrt();
        run = Run {
            to_vessel,
            rms,
            kept,
            iterations: iteration,
        };
        let centre = pairs.iter().map(|p| p.1).sum::<DVec3>() / kept as f64;
        let n = if options.levelled { 4 } else { 6 };
        let mut a = vec![vec![0.0; n]; n];
        let mut b = vec![0.0; n];
        for &(r, x, normal) in pairs {
            let lever = (x - centre).cross(normal);
            let row: [f64; 6] = if options.levelled {
                [up.dot(lever), normal.x, normal.y, normal.z, 0.0, 0.0]
            } else {
                [lever.x, lever.y, lever.z, normal.x, normal.y, normal.z]
            };
            for i in 0..n {
                for j in 0..n {
                    a[i][j] += row[i] * row[j];
                }
                b[i] -= row[i] * r;
            }
        }
        let Some(x) = solve_dense(a, b) else {
            return run;
        };
        let (omega, shift) = if options.levelled {
            (up * x[0], DVec3::new(x[1], x[2], x[3]))
        } else {
            (DVec3::new(x[0], x[1], x[2]), DVec3::new(x[3], x[4], x[5]))
        };
        let angle = omega.length();
        let turn = if angle > 0.0 {
            DMat3::from_axis_angle(omega / angle, angle)
        } else {
            DMat3::IDENTITY
        };
        let step = DAffine3::from_translation(centre + shift)
            * DAffine3::from_mat3(turn)
            * DAffine3::from_translation(-centre);
        to_vessel = step * to_vessel;
        if angle < 1e-10 && shift.length() < 1e-7 {
            run.to_vessel = to_vessel;
            run.iterations = iteration + 1;
            return run;
        }
    }
    run.to_vessel = to_vessel;
    run.iterations = iterations;
    run
}

/// An even stride of at most `n` points.
fn stride(points: &[DVec3], n: usize) -> Vec<DVec3> {
    let step = points.len().div_ceil(n.max(1)).max(1);
    points.iter().step_by(step).copied().collect()
}

/// Registers `points` (site frame) on the design.
///
/// The start: the scan's centroid on the design's area centroid, the site's Z
/// taken as plant up; ICP on the envelope settles the shift. Then turns about
/// plant up through the vessel's middle, every 2°, are ranked by their mean
/// truncated squared residual, once on an even subsample and once on the
/// points off the envelope (only what is not symmetric about the axis — the
/// nozzles — tells the turns apart; see `features`); the best three of each
/// run to convergence on a subsample, the one with the least truncated
/// residual on the subsample and the features wins and runs on all points.
///
/// # Errors
///
/// [`ScanError::TooFewPoints`] with fewer than [`MIN_POINTS`] points,
/// [`ScanError::Options`] for a `keep` outside [0.5, 1].
pub fn register(
    envelope: &Envelope,
    points: &[DVec3],
    options: &RegisterOptions,
) -> Result<Registration, ScanError> {
    if points.len() < MIN_POINTS {
        return Err(ScanError::TooFewPoints {
            what: "registration".into(),
            found: points.len(),
            needed: MIN_POINTS,
        });
    }
    if !(0.5..=1.0).contains(&options.keep) {
        return Err(ScanError::Options {
            field: "keep",
            value: options.keep,
            rule: "must be in [0.5, 1]",
        });
    }
    // The design's area centroid, from a noise-free draw of its surfaces.
    let design = simulate(
        envelope,
        &SimulateOptions {
            density: 4000.0 / envelope_area_m2(envelope),
            noise: 0.0,
            occlusion: 0.0,
            seed: 1,
            site: None,
            defects: Vec::new(),
        },
    )?;
    let target = envelope
        .frame
        .inverse()
        .transform_point3(mean(&design.points));
    let scan_centre = mean(points);
    let margin = 2.0 * envelope.default_margin();
    let up = envelope.up;
    let linear = envelope.frame.inverse().matrix3;
    let start = DAffine3::from_mat3_translation(linear, target - linear * scan_centre);
    let coarse = stride(points, 2000);
    // The shift, settled with every point within a quarter of the margin: the
    // courses fix it across the axis, the heads (a fraction of the points)
    // along it. Trimmed to the robust sigma from the start, the heads of a
    // scan whose centroid sits 200 mm off the design's (a gap, a missing
    // bottom) were dropped as outliers for good, and the rest registered a
    // tank 196 mm low and turned 127° wrong (seed 15).
    let settle = RegisterOptions {
        keep: 1.0,
        ..*options
    };
    let settled = icp(
        envelope,
        &coarse,
        start,
        &settle,
        20,
        margin,
        (margin, 0.25 * margin),
    )
    .to_vessel;
    let (lo, hi) = envelope
        .parts
        .iter()
        .filter(|p| p.role.is_envelope())
        .fold((f64::INFINITY, f64::NEG_INFINITY), |m, p| {
            (m.0.min(p.span.0), m.1.max(p.span.1))
        });
    let pivot = DVec3::new(0.0, 0.0, 0.5 * (lo + hi));
    let turned = |yaw: f64| {
        DAffine3::from_translation(pivot)
            * DAffine3::from_mat3(DMat3::from_axis_angle(up, yaw))
            * DAffine3::from_translation(-pivot)
            * settled
    };
    // Turns every 2°, ranked on the whole (coarse) scan and on its features
    // alone; the best three distinct turns of each run to convergence.
    let features = off_envelope(envelope, points, settled, margin);
    let rank = |sample: &[DVec3]| -> Vec<f64> {
        let mut ranked: Vec<(f64, f64)> = (0..180)
            .into_par_iter()
            .map(|k| {
                let yaw = (2.0 * k as f64).to_radians();
                (score(envelope, sample, turned(yaw), margin), yaw)
            })
            .collect();
        ranked.sort_by(|a, b| a.0.total_cmp(&b.0));
        ranked.into_iter().map(|(_, yaw)| yaw).collect()
    };
    let mut starts: Vec<f64> = Vec::new();
    let mut candidates = vec![rank(&coarse)];
    if features.len() >= MIN_FEATURES {
        candidates.push(rank(&features));
    }
    for ranked in candidates {
        let before = starts.len();
        for yaw in ranked {
            if starts
                .iter()
                .all(|s| super::defects::wrap(yaw - s).abs() > 5f64.to_radians())
            {
                starts.push(yaw);
            }
            if starts.len() == before + 3 {
                break;
            }
        }
    }
    // Each run is judged by its truncated residual on a subsample and on the
    // features together (the features are a few per cent of the subsample).
    let medium = stride(points, 8000);
    let judged: Vec<DVec3> = medium.iter().chain(&features).copied().collect();
    let best = starts
        .par_iter()
        .map(|&yaw| {
            let run = icp(
                envelope,
                &medium,
                turned(yaw),
                options,
                25,
                margin,
                (START_CUTOFF, MIN_CUTOFF),
            );
            (score(envelope, &judged, run.to_vessel, margin), run)
        })
        .min_by(|a, b| a.0.total_cmp(&b.0))
        .map(|(_, run)| run.to_vessel)
        .unwrap_or(settled);
    let all = stride(points, MAX_POINTS);
    let last = icp(
        envelope,
        &all,
        best,
        options,
        options.iterations,
        envelope.default_margin(),
        (START_CUTOFF, MIN_CUTOFF),
    );
    Ok(Registration::from_vessel(
        last.to_vessel,
        envelope,
        last.rms,
        all.len(),
        last.kept,
        last.iterations,
        false,
    ))
}

fn mean(points: &[DVec3]) -> DVec3 {
    points.iter().sum::<DVec3>() / points.len().max(1) as f64
}

/// Area of the envelope and nozzle patches, m² (control-net estimate is enough
/// for a sampling density).
fn envelope_area_m2(envelope: &Envelope) -> f64 {
    envelope
        .surfaces
        .iter()
        .filter(|s| envelope.parts[s.part].role.is_envelope())
        .map(|s| s.patch.surface.area())
        .sum::<f64>()
        .max(1.0)
        * 1e-6
}
