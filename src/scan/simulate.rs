//! Synthetic scans with a known truth: points drawn uniformly by area on the
//! vessel's exact patches, moved by the [defects](super::defects), blurred by
//! scanner-like Gaussian noise, thinned by occlusion gaps and carried into a
//! site frame by a levelled scanner's transform (a turn about plant Z and a
//! shift). Deterministic by seed.
//!
//! Sampling draws (u, v) uniformly and keeps it with probability |S_u × S_v| /
//! max (rejection), so the density per area is the same on a head's crown and
//! near its pole. Nozzle points the shell hides (inside the envelope) are dropped;
//! a plane facing the ground (a tank's bottom) is not seen. Occlusion removes
//! whole 1 m cells of the unrolled surface, as scaffolding and pipes do.

use glam::{DAffine3, DMat3, DVec3};
use serde::Serialize;

use super::ScanError;
use super::defects::{Defect, normal_displacement, rigid_motion, vertical_displacement};
use super::envelope::{Envelope, Role};
use super::project::Targets;
use super::random::{Random, cell_hash};
use crate::parts::Analytic;

/// Occlusion cell size on the unrolled surface, mm.
pub const OCCLUSION_CELL: f64 = 1000.0;

/// A levelled scanner's pose: plant → site is a turn about Z then a shift.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct SiteTransform {
    /// Turn about plant Z, degrees (counter-clockwise seen from above).
    pub yaw: f64,
    /// Shift, mm.
    pub shift: [f64; 3],
}

impl SiteTransform {
    /// Plant → site.
    pub fn affine(&self) -> DAffine3 {
        DAffine3::from_mat3_translation(
            DMat3::from_rotation_z(self.yaw.to_radians()),
            DVec3::from(self.shift),
        )
    }

    /// A pose drawn from a seed: any yaw, a shift of up to 50 m in plan, 5 m up.
    pub fn from_seed(seed: u64) -> Self {
        let mut r = Random::new(seed ^ 0xA5A5_5A5A);
        Self {
            yaw: 360.0 * r.uniform(),
            shift: [
                100_000.0 * (r.uniform() - 0.5),
                100_000.0 * (r.uniform() - 0.5),
                10_000.0 * (r.uniform() - 0.5),
            ],
        }
    }
}

/// What a simulated scan is drawn with.
#[derive(Clone, Debug, PartialEq)]
pub struct SimulateOptions {
    /// Points per m² of surface.
    pub density: f64,
    /// Standard deviation of the noise per coordinate, mm.
    pub noise: f64,
    /// Fraction of the surface hidden, 0 to 0.9.
    pub occlusion: f64,
    /// Seed of every random choice.
    pub seed: u64,
    /// The scanner's pose; `None` keeps plant coordinates.
    pub site: Option<SiteTransform>,
    /// Defects.
    pub defects: Vec<Defect>,
}

/// A simulated scan and its truth.
#[derive(Clone, Debug, Serialize)]
pub struct SimulatedScan {
    /// Points, site frame (plant frame without a site transform), mm.
    #[serde(skip)]
    pub points: Vec<DVec3>,
    /// The truth the points were drawn with.
    pub truth: Truth,
}

/// What a simulated scan was drawn with, for tests and demos (`scan.truth.json`).
#[derive(Clone, Debug, Serialize)]
pub struct Truth {
    /// Vessel tag.
    pub vessel: String,
    /// The scanner pose (plant → site), if any.
    pub site: Option<SiteTransform>,
    /// The defects.
    pub defects: Vec<Defect>,
    /// Noise, mm.
    pub noise: f64,
    /// Density, points/m².
    pub density: f64,
    /// Occlusion fraction.
    pub occlusion: f64,
    /// Seed.
    pub seed: u64,
    /// Points drawn.
    pub points: usize,
}

fn check(field: &'static str, value: f64, ok: bool, rule: &'static str) -> Result<(), ScanError> {
    if ok && value.is_finite() {
        Ok(())
    } else {
        Err(ScanError::Options { field, value, rule })
    }
}

/// Draws a scan of `envelope` with `options`.
///
/// # Errors
///
/// [`ScanError::Options`] for a density not in (0, 10⁶] points/m², a negative
/// noise or an occlusion outside [0, 0.9].
pub fn simulate(
    envelope: &Envelope,
    options: &SimulateOptions,
) -> Result<SimulatedScan, ScanError> {
    check(
        "--density",
        options.density,
        options.density > 0.0 && options.density <= 1e6,
        "must be in (0, 10^6] points/m²",
    )?;
    check(
        "--noise",
        options.noise,
        options.noise >= 0.0 && options.noise <= 1000.0,
        "must be in [0, 1000] mm",
    )?;
    check(
        "--occlusion",
        options.occlusion,
        (0.0..=0.9).contains(&options.occlusion),
        "must be in [0, 0.9]",
    )?;
    let mut random = Random::new(options.seed);
    let motion = rigid_motion(envelope, &options.defects);
    let to_site = options.site.map_or(DAffine3::IDENTITY, |s| s.affine()) * envelope.frame;
    let radius = envelope
        .parts
        .iter()
        .filter(|p| p.role.is_envelope())
        .map(|p| p.diameter / 2.0)
        .fold(1.0, f64::max);
    let margin = envelope.default_margin();
    let mut points = Vec::new();
    for s in &envelope.surfaces {
        let role = envelope.parts[s.part].role;
        if !(role.is_envelope() || role == Role::Nozzle) {
            continue;
        }
        if let Analytic::Plane { normal, .. } = s.patch.analytic {
            let world = (envelope.frame.matrix3 * (s.frame.matrix3 * normal)).normalize();
            if world.z < -0.99 {
                continue;
            }
        }
        let surface = &s.patch.surface;
        let ((u0, u1), (v0, v1)) = surface.domain();
        let grid = 48;
        let (mut area, mut jmax) = (0.0, 0.0f64);
        for i in 0..grid {
            for j in 0..grid {
                let u = u0 + (u1 - u0) * (i as f64 + 0.5) / grid as f64;
                let v = v0 + (v1 - v0) * (j as f64 + 0.5) / grid as f64;
                let d = surface.first_derivatives(u, v);
                let jac = d.du.cross(d.dv).length();
                area += jac;
                jmax = jmax.max(jac);
            }
        }
        area *= (u1 - u0) * (v1 - v0) / (grid * grid) as f64;
        let expected = area * 1e-6 * options.density;
        let mut count = expected.floor() as usize;
        if random.uniform() < expected - expected.floor() {
            count += 1;
        }
        let ceiling = 1.25 * jmax;
        let mut drawn = 0;
        while drawn < count {
            let u = u0 + (u1 - u0) * random.uniform();
            let v = v0 + (v1 - v0) * random.uniform();
            let d = surface.first_derivatives(u, v);
            let n = d.du.cross(d.dv);
            if random.uniform() * ceiling > n.length() {
                continue;
            }
            drawn += 1;
            let p = s.frame.transform_point3(d.point);
            let normal = s.frame.transform_vector3(n).normalize_or_zero();
            if role == Role::Nozzle {
                let hidden = envelope
                    .project(p, Targets::Envelope, margin)
                    .is_some_and(|f| f.inside && f.deviation < -1.0);
                if hidden {
                    continue;
                }
            }
            let theta = p.y.atan2(p.x);
            let cell = (
                (theta * radius / OCCLUSION_CELL).floor() as i64,
                (p.z / OCCLUSION_CELL).floor() as i64,
            );
            let moved = p + normal * normal_displacement(envelope, &options.defects, s.part, p)
                - envelope.up * vertical_displacement(envelope, &options.defects, s.part, p);
            let noisy = moved
                + DVec3::new(random.normal(), random.normal(), random.normal()) * options.noise;
            if options.occlusion > 0.0
                && cell_hash(options.seed, cell.0, cell.1) < options.occlusion
            {
                continue;
            }
            points.push(to_site.transform_point3(motion.transform_point3(noisy)));
        }
    }
    let truth = Truth {
        vessel: envelope.tag.clone(),
        site: options.site,
        defects: options.defects.clone(),
        noise: options.noise,
        density: options.density,
        occlusion: options.occlusion,
        seed: options.seed,
        points: points.len(),
    };
    Ok(SimulatedScan { points, truth })
}
