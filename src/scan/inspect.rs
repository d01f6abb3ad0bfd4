//! The whole comparison of one scan with its design: register, project, fit each
//! patch, check, and the figures a report prints.

use glam::DVec3;
use rayon::prelude::*;
use serde::Serialize;

use super::ScanError;
use super::checks::{CheckOptions, Checks, check};
use super::envelope::{Envelope, Role};
use super::fit::{FitOptions, PatchFit, Sample, fit_patch};
use super::project::{Foot, Targets};
use super::register::{RegisterOptions, Registration, register};

/// How to inspect a scan.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct InspectOptions {
    /// How to register; `None` keeps the given (plant) frame.
    pub register: Option<RegisterOptions>,
    /// How to fit.
    pub fit: FitOptions,
    /// Detection floors.
    pub checks: CheckOptions,
}

impl InspectOptions {
    /// Registered, default fit and checks.
    pub const DEFAULT: Self = Self {
        register: Some(RegisterOptions::DEFAULT),
        fit: FitOptions::DEFAULT,
        checks: CheckOptions::DEFAULT,
    };
}

/// Deviation statistics of one part.
#[derive(Clone, Debug, Serialize)]
pub struct PartStats {
    /// Part id or nozzle mark.
    pub id: String,
    /// What it is.
    pub role: Role,
    /// Points projected on it.
    pub points: usize,
    /// Mean signed deviation, mm.
    pub mean: f64,
    /// RMS deviation, mm.
    pub rms: f64,
    /// Most inward, mm.
    pub min: f64,
    /// Most outward, mm.
    pub max: f64,
}

/// Enclosed volume of the envelope, design and as built.
#[derive(Clone, Copy, Debug, Serialize)]
pub struct Volume {
    /// From the design patches, m³.
    pub design: f64,
    /// With every fitted patch in place of its design, m³.
    pub as_built: f64,
}

/// One scan against its design.
#[derive(Clone, Debug, Serialize)]
pub struct Inspection {
    /// Vessel tag.
    pub vessel: String,
    /// Points read.
    pub points: usize,
    /// Points on the envelope used for fitting.
    pub fitted: usize,
    /// Points on nozzles.
    pub on_nozzles: usize,
    /// Points farther than the search margin, or off every patch.
    pub outliers: usize,
    /// The registration.
    pub registration: Registration,
    /// Statistics per part.
    pub parts: Vec<PartStats>,
    /// The fit of each surface (by index in the envelope), if it had points.
    pub fits: Vec<Option<PatchFit>>,
    /// The code checks and findings.
    pub checks: Checks,
    /// Volumes.
    pub volume: Volume,
}

/// Inspects `points` (site frame; plant frame when the frame is kept).
///
/// # Errors
///
/// Registration and fitting errors ([`ScanError::TooFewPoints`],
/// [`ScanError::Singular`], [`ScanError::Options`]).
pub fn inspect(
    envelope: &Envelope,
    mut points: Vec<DVec3>,
    options: &InspectOptions,
) -> Result<Inspection, ScanError> {
    let registration = match &options.register {
        Some(r) => register(envelope, &points, r)?,
        None => Registration::keep_frame(envelope),
    };
    let to_vessel = registration.to_vessel;
    points
        .par_iter_mut()
        .for_each(|p| *p = to_vessel.transform_point3(*p));
    let margin = envelope.default_margin();
    let mut feet = envelope.project_all(&points, Targets::WithNozzles, margin);
    let mut outliers = 0;
    let mut on_nozzles = 0;
    for f in &mut feet {
        match f {
            Some(foot) if foot.inside && foot.deviation.abs() <= margin => {
                if envelope.parts[envelope.surfaces[foot.surface].part].role == Role::Nozzle {
                    on_nozzles += 1;
                }
            }
            _ => {
                outliers += 1;
                *f = None;
            }
        }
    }
    let mut samples: Vec<Vec<Sample>> = vec![Vec::new(); envelope.surfaces.len()];
    for (p, f) in points.iter().zip(&feet) {
        let Some(f) = f else { continue };
        let s = &envelope.surfaces[f.surface];
        if !envelope.parts[s.part].role.is_envelope() {
            continue;
        }
        samples[f.surface].push(Sample {
            u: f.u,
            v: f.v,
            offset: s.inverse.transform_vector3(*p - f.point),
            normal: s.inverse.transform_vector3(f.normal).normalize_or_zero(),
        });
    }
    let fitted = samples.iter().map(Vec::len).sum();
    let fits: Vec<Option<PatchFit>> = samples
        .par_iter()
        .enumerate()
        .map(|(i, data)| {
            let s = &envelope.surfaces[i];
            if data.len() < 16 {
                return Ok(None);
            }
            let what = format!(
                "{}/{} {}",
                envelope.tag, envelope.parts[s.part].id, s.patch.name
            );
            fit_patch(&s.patch.surface, data, &options.fit, &what).map(Some)
        })
        .collect::<Result<_, ScanError>>()?;
    let parts = part_stats(envelope, &feet);
    let checks = check(envelope, &fits, &points, &feet, &options.checks);
    let volume = volume(envelope, &fits);
    Ok(Inspection {
        vessel: envelope.tag.clone(),
        points: points.len(),
        fitted,
        on_nozzles,
        outliers,
        registration,
        parts,
        fits,
        checks,
        volume,
    })
}

fn part_stats(envelope: &Envelope, feet: &[Option<Foot>]) -> Vec<PartStats> {
    let mut acc = vec![(0usize, 0.0, 0.0, f64::INFINITY, f64::NEG_INFINITY); envelope.parts.len()];
    for f in feet.iter().flatten() {
        let a = &mut acc[envelope.surfaces[f.surface].part];
        a.0 += 1;
        a.1 += f.deviation;
        a.2 += f.deviation * f.deviation;
        a.3 = a.3.min(f.deviation);
        a.4 = a.4.max(f.deviation);
    }
    envelope
        .parts
        .iter()
        .zip(acc)
        .filter(|(_, a)| a.0 > 0)
        .map(|(p, a)| PartStats {
            id: p.id.clone(),
            role: p.role,
            points: a.0,
            mean: a.1 / a.0 as f64,
            rms: (a.2 / a.0 as f64).sqrt(),
            min: a.3,
            max: a.4,
        })
        .collect()
}

/// Divergence-theorem volume of the envelope patches, design and fitted.
fn volume(envelope: &Envelope, fits: &[Option<PatchFit>]) -> Volume {
    let (mut design, mut built) = (0.0, 0.0);
    for (s, fit) in envelope.surfaces.iter().zip(fits) {
        if !envelope.parts[s.part].role.is_envelope() {
            continue;
        }
        let placed = |surface: &crate::nurbs::NurbsSurface| {
            surface
                .transformed(&s.frame)
                .map_or(0.0, |t| t.volume_integral())
        };
        let d = placed(&s.patch.surface);
        design += d;
        built += fit.as_ref().map_or(d, |f| placed(&f.surface));
    }
    Volume {
        design: design * 1e-9,
        as_built: built * 1e-9,
    }
}
