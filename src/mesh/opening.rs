//! Cutting an opening: a nozzle's neck (or a boot's shell, which is cut the same
//! way) placed in its host part's frame, intersected with the host's patches until
//! one holds the whole loop.
//!
//! Shared by the ECS Geometry stage (`systems::cut_openings`) and the direct full
//! build (`export::build_scene`), so both trim exactly alike. A loop that goes
//! round the host's pole (a nozzle centred on a head) gets an extra sample exactly
//! on the host's seam angle, shared by the neck, so the host can be cut there.

use std::f64::consts::TAU;

use glam::{DAffine3, DVec2, DVec3};

use crate::nurbs::builders::{line, revolve};

use crate::nurbs::NurbsSurface;
use crate::nurbs::intersect::{IntersectionLoop, intersect_generator, neck_host_intersection};
use crate::parts::Patch;

/// Bisection steps placing the seam sample.
const SEAM_STEPS: usize = 80;

/// A nozzle's cut in its host, in the host part's frame.
#[derive(Clone, Debug, PartialEq)]
pub struct Cut {
    /// Index of the host patch the opening lies in.
    pub host_patch: usize,
    /// Where the neck meets the host.
    pub neck: IntersectionLoop,
    /// Where the reinforcing pad's outside edge meets the host, if it has a pad.
    pub pad: Option<IntersectionLoop>,
}

/// One loop against one host patch, with a seam sample if it goes round the pole.
fn loop_on(
    neck: &NurbsSurface,
    host: &NurbsSurface,
    tolerance: f64,
) -> Result<IntersectionLoop, String> {
    let mut curve = neck_host_intersection(neck, host, tolerance).map_err(|e| e.to_string())?;
    if curve.host_turns(host) != 0 {
        add_seam_sample(neck, host, &mut curve)?;
    }
    Ok(curve)
}

/// The opening of a nozzle in its host: the host patch it lies in, the neck–host
/// loop and, with a pad of outside diameter `pad_od`, the pad's outer loop, all in
/// the host part's frame. `nozzle_frame` and `host_frame` map the nozzle's and the
/// host's local frames into one common frame (the vessel's).
pub fn cut_opening(
    neck: &Patch,
    pad_od: Option<f64>,
    nozzle_frame: &DAffine3,
    host_frame: &DAffine3,
    host_patches: &[&Patch],
    tolerance: f64,
) -> Result<Cut, String> {
    let relative = host_frame.inverse() * *nozzle_frame;
    let place = |s: &NurbsSurface| {
        s.transformed(&relative)
            .map_err(|e| format!("cannot place the nozzle in its host's frame: {e}"))
    };
    // The pad's outside cylinder spans the neck's height (in the nozzle frame).
    let top = neck
        .surface
        .control_points()
        .iter()
        .fold(0.0f64, |m, p| m.max(p.z))
        .max(1.0);
    let neck = place(&neck.surface)?;
    let pad = match pad_od {
        None => None,
        Some(od) => {
            let generator = line(
                DVec3::new(od / 2.0, 0.0, 0.0),
                DVec3::new(od / 2.0, 0.0, top),
            )
            .map_err(|e| e.to_string())?;
            let cylinder =
                revolve(&generator, DVec3::ZERO, DVec3::Z, TAU).map_err(|e| e.to_string())?;
            Some(place(&cylinder)?)
        }
    };
    let mut last = String::from("the host has no patch");
    for (k, patch) in host_patches.iter().enumerate() {
        let result = loop_on(&neck, &patch.surface, tolerance).and_then(|neck_loop| {
            let pad_loop = match &pad {
                Some(p) => {
                    Some(loop_on(p, &patch.surface, tolerance).map_err(|e| format!("pad: {e}"))?)
                }
                None => None,
            };
            Ok(Cut {
                host_patch: k,
                neck: neck_loop,
                pad: pad_loop,
            })
        });
        match result {
            Ok(cut) => return Ok(cut),
            Err(e) => {
                last = format!(
                    "the opening does not lie within host patch {:?}: {e}",
                    patch.name
                )
            }
        }
    }
    Err(last)
}

/// Inserts a sample of the loop exactly at the host's seam angle u0 (mod period).
fn add_seam_sample(
    neck: &NurbsSurface,
    host: &NurbsSurface,
    curve: &mut IntersectionLoop,
) -> Result<(), String> {
    let ((u0, u1), _) = host.domain();
    let (nu0, nu1) = neck.domain().0;
    let (period, neck_period) = (u1 - u0, nu1 - nu0);
    let n = curve.host_uv.len();
    let turns = f64::from(curve.host_turns(host));
    for i in 0..n {
        let j = (i + 1) % n;
        let (a, mut b) = (curve.host_uv[i].x, curve.host_uv[j].x);
        let (na, mut nb) = (curve.neck_uv[i].x, curve.neck_uv[j].x);
        if j == 0 {
            b += turns * period;
            nb += neck_period;
        }
        let lo = a.min(b);
        let target = u0 + ((lo - u0) / period).ceil() * period;
        if (a - target).abs() <= 1e-12 * period {
            return Ok(()); // already on the seam
        }
        if !(target > lo && target < a.max(b)) {
            continue;
        }
        let (mut x0, mut x1) = (na, nb);
        let mut hit = None;
        for _ in 0..SEAM_STEPS {
            let mid = 0.5 * (x0 + x1);
            let h =
                intersect_generator(neck, host, mid).map_err(|e| format!("seam sample: {e}"))?;
            let expected = a + (b - a) * (mid - na) / (nb - na);
            let hu = h.host_uv.x + period * ((expected - h.host_uv.x) / period).round();
            if (hu < target) == (a < target) {
                x0 = mid;
            } else {
                x1 = mid;
            }
            hit = Some((mid, h));
            if (hu - target).abs() <= 1e-13 * period {
                break;
            }
        }
        let Some((nu, h)) = hit else {
            return Err("seam sample not found".into());
        };
        let at = i + 1;
        curve.points.insert(at, h.point);
        curve.neck_uv.insert(at, DVec2::new(nu, h.neck_v));
        curve.host_uv.insert(at, DVec2::new(target, h.host_uv.y));
        return Ok(());
    }
    Err("the loop round the pole does not cross the host's seam".into())
}

/// Name of the reinforcing pad's patch.
pub const PAD_PATCH: &str = "reinforcing pad";

/// The reinforcing pad's patch: the host patch's surface moved into the nozzle's
/// frame (its (u, v) unchanged, so the pad's loops trim it directly). The pad lies on
/// the host's outside surface; its thickness is carried, not modelled.
pub fn pad_patch(
    host: &Patch,
    nozzle_frame: &DAffine3,
    host_frame: &DAffine3,
) -> Result<Patch, String> {
    let relative = nozzle_frame.inverse() * *host_frame;
    let surface = host
        .surface
        .transformed(&relative)
        .map_err(|e| format!("pad: {e}"))?;
    Ok(Patch::new(
        PAD_PATCH,
        surface,
        host.analytic.transformed(&relative),
    ))
}
