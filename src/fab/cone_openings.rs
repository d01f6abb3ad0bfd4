//! Nozzle openings on cones — concentric ones and eccentric reducers'
//! oblique ones — developed onto the cone's plates.
//!
//! A cone's mid-surface is the surface of circles of radius `ρ(z) = r₀ +
//! k·(z − z₀)` about the centres `c(z) = l·(z − z₀)` ([`ConeSurface`]; `l`
//! is zero on a concentric cone, and on an eccentric reducer moves the
//! centres towards the flat side as the radius shrinks). For every angle φ
//! about the neck axis, the line `a + s·b` of the cutting cylinder (radius
//! ρ_c) at φ meets that cone where `|a_xy − c(a_z) + s·(b_xy − l·b_z)|² =
//! (ρ(a_z) + k·b_z·s)²`, a quadratic in the
//! distance `s` along the neck axis: solved exactly, the outer crossing (the
//! larger root on the cone's own nappe, as [`NeckAxis::crossing`]
//! takes on a course) is the point of the opening. The cutting cylinder is
//! the course's: the neck's outside plus the bevel allowance (set-in) or
//! its bore (set-on); a pad's footprint is its cylinder on the cone's
//! outside surface; the neck's end (its saddle) is where the neck's
//! mid-surface meets the cone's inside (set-in) or outside (set-on).
//!
//! A point `(θ, z)` of the cone develops onto its plate by the same map as the
//! sector ([`super::develop::Rolled::outline`]): slant distance from the apex
//! `ρ(z)/sin α`, sector angle `(θ − θ_mid)·sin α` from the plate's bisector
//! (laid along +y, apex at the origin), seen from outside ([`develop_point`]).
//! The map is an isometry, so the developed opening is the exact curve
//! unrolled. On an eccentric reducer a point is `(φ, z)`, φ about its
//! circle's centre, and develops by the oblique plate's own development
//! ([`super::oblique_openings`]); its pad's mid-surface, and the wall's
//! inside the neck meets, are offset in the planes of the circles as the
//! reducer's mid-surface is ([`super::oblique`]).

use std::f64::consts::TAU;

use glam::{DVec2, DVec3};

use super::cut::{NozzleCut, PadPiece, saddle};
use super::develop::{Developments, Rolled, RolledKind};
use super::neck_axis::{NeckAxis, SurfaceLoop, samples, theta_near};
use super::oblique_openings::develop_about;
use super::shop::{Attachment, Shop};
use crate::constraints::ResolvedVessel;
use crate::format::RuleViolation;
use crate::parts::tables::pipe;

/// A cone of circles in the planes of constant local z: radius `r0 + k·(z −
/// z0)` about the centre `lean·(z − z0)` — about local +Z for a concentric
/// cone (`lean` zero), leaning towards the flat side for an eccentric
/// reducer's oblique cone.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ConeSurface {
    /// Radius at `z0`, mm.
    pub r0: f64,
    /// Reference height, mm.
    pub z0: f64,
    /// dr/dz.
    pub k: f64,
    /// How far the circles' centres move (part-local x, y) per mm of
    /// height from the axis at `z0`.
    pub lean: DVec2,
}

impl ConeSurface {
    /// A rolled cone's mid-surface.
    pub fn mid(rolled: &Rolled) -> Self {
        ConeSurface {
            r0: rolled.radius.0,
            z0: rolled.z.0,
            k: rolled.taper(),
            lean: Self::lean_of(rolled),
        }
    }

    /// A rolled cone's outside surface.
    pub fn outside(rolled: &Rolled) -> Self {
        ConeSurface {
            r0: rolled.outside.0,
            z0: rolled.z.0,
            k: (rolled.outside.1 - rolled.outside.0) / (rolled.z.1 - rolled.z.0),
            lean: Self::lean_of(rolled),
        }
    }

    /// The lean of a rolled cone's circles: an eccentric reducer's centres
    /// move towards its flat side by as much as the radius shrinks
    /// ([`Rolled::centre_at`]), on the axis at its large end (`z.0 = 0`).
    fn lean_of(rolled: &Rolled) -> DVec2 {
        match rolled.flat_side {
            Some(f) => DVec2::from_angle(f) * -rolled.taper(),
            None => DVec2::ZERO,
        }
    }

    /// The surface `d` mm outside this one (inside for negative `d`): the
    /// offset measured along the normal on a surface of revolution, and in
    /// the planes of constant z on an oblique cone, as its mid-surface is
    /// ([`super::oblique`]).
    pub fn offset(&self, d: f64) -> Self {
        let dr = if self.lean == DVec2::ZERO {
            d * self.k.hypot(1.0)
        } else {
            d
        };
        ConeSurface {
            r0: self.r0 + dr,
            ..*self
        }
    }

    /// Radius at height `z`, mm.
    pub fn radius(&self, z: f64) -> f64 {
        self.r0 + self.k * (z - self.z0)
    }

    /// The centre of the circle at height `z`, part-local x, y.
    pub fn centre(&self, z: f64) -> DVec2 {
        self.lean * (z - self.z0)
    }

    /// The angle of `p` about the centre of its circle, unwrapped to
    /// within π of `about`.
    pub fn angle_near(&self, p: DVec3, about: f64) -> f64 {
        theta_near(p - self.centre(p.z).extend(0.0), about)
    }

    /// The point at angle `phi` of the cylinder of radius `rho` about `neck`
    /// that lies on the cone (the larger root on the cone's own nappe), and
    /// its distance along the axis; `None` where that line misses the cone.
    pub fn crossing(&self, neck: &NeckAxis, rho: f64, phi: f64) -> Option<(DVec3, f64)> {
        let a = neck.origin + rho * (phi.cos() * neck.e1 + phi.sin() * neck.e2);
        let b = neck.axis;
        // From the centre of the circle at each point's height: `u + s·v`.
        let u = a.truncate() - self.lean * (a.z - self.z0);
        let v = b.truncate() - self.lean * b.z;
        let c = self.radius(a.z);
        let kb = self.k * b.z;
        let qa = v.length_squared() - kb * kb;
        let qb = 2.0 * (u.dot(v) - c * kb);
        let qc = u.length_squared() - c * c;
        let roots: Vec<f64> = if qa.abs() <= 1e-14 {
            // The line runs along a generator's direction: one crossing.
            if qb == 0.0 { vec![] } else { vec![-qc / qb] }
        } else {
            let disc = qb * qb - 4.0 * qa * qc;
            if disc < 0.0 {
                return None;
            }
            // Both roots without cancellation.
            let q = -0.5 * (qb + qb.signum() * disc.sqrt());
            if q == 0.0 {
                vec![0.0]
            } else {
                vec![q / qa, qc / q]
            }
        };
        let s = roots
            .into_iter()
            .filter(|&s| c + kb * s >= 0.0)
            .max_by(f64::total_cmp)?;
        Some((a + s * b, s))
    }

    /// The loop where the cylinder of radius `rho` about `neck` meets the
    /// cone, `n` points in surface coordinates `(θ, z)` about `centre_theta`;
    /// `None` where part of it misses.
    pub fn surface_loop(
        &self,
        neck: &NeckAxis,
        rho: f64,
        centre_theta: f64,
        n: usize,
    ) -> Option<SurfaceLoop> {
        (0..n)
            .map(|i| {
                let phi = TAU * i as f64 / n as f64;
                self.crossing(neck, rho, phi)
                    .map(|(p, _)| DVec2::new(self.angle_near(p, centre_theta), p.z))
            })
            .collect()
    }
}

/// The development of the point `(θ, z)` of cone `surface` on the plate
/// whose bisector is at angle `theta_mid`: apex at the origin, bisector
/// along +y, seen from the cone's outside (x runs with θ where the cone
/// widens with z, against it where it narrows), mm.
pub fn develop_point(surface: &ConeSurface, theta_mid: f64, p: DVec2) -> DVec2 {
    let sin = surface.k.abs() / surface.k.hypot(1.0);
    let rho = surface.radius(p.y) / sin;
    let a = -surface.k.signum() * (p.x - theta_mid) * sin;
    DVec2::new(-rho * a.sin(), rho * a.cos())
}

/// The index in `developments.rolled` of the cone (concentric or an
/// eccentric reducer's oblique one) nozzle `index` of `resolved` is cut
/// into, if its host is one.
pub fn host_cone(
    resolved: &ResolvedVessel,
    developments: &Developments,
    index: usize,
) -> Option<usize> {
    let host = resolved.nozzles[index].host;
    developments
        .rolled
        .iter()
        .position(|r| r.part == host && r.kind == RolledKind::Cone && !r.is_cylinder())
}

/// Develops the opening (and pad footprint) of nozzle `index` of
/// `resolved` on cone `rolled_index` of `developments` (concentric or
/// oblique).
///
/// # Errors
///
/// A violation naming the nozzle when its pipe schedule is not listed or
/// its axis, opening or pad misses the cone.
pub fn cut_cone_nozzle(
    vessel_index: usize,
    resolved: &ResolvedVessel,
    developments: &Developments,
    shop: &Shop,
    index: usize,
    rolled_index: usize,
) -> Result<NozzleCut, RuleViolation> {
    let nozzle = &resolved.nozzles[index];
    let path = format!("vessels[{vessel_index}].nozzles[{index}]");
    let cone = &developments.rolled[rolled_index];
    let bad = |field: &str, value: String, rule: String| RuleViolation {
        path: format!("{path}.{field}"),
        entity: format!("{}/{}", resolved.tag, nozzle.mark),
        field: field.into(),
        value,
        rule,
    };
    let g = &nozzle.geometry;
    let dims = pipe(g.nps);
    let wall = dims
        .wall(g.schedule)
        .map_err(|e| bad("schedule", g.schedule.label().into(), e.to_string()))?;
    let od = dims.outside_diameter;
    let cut_radius = shop.cut_radius(od, wall);
    let misses = |what: &str| {
        bad(
            "elevation",
            "-".into(),
            format!(
                "the {what} must lie wholly on cone {}/{} to be developed",
                resolved.tag, cone.id
            ),
        )
    };
    let neck = NeckAxis::new(cone.frame, nozzle.frame);
    let mid = ConeSurface::mid(cone);
    let Some((centre, _)) = mid.crossing(&neck, 0.0, 0.0) else {
        return Err(misses("nozzle axis"));
    };
    let theta = mid.angle_near(centre, 0.0);
    let n = samples(cut_radius, shop.chord_tolerance);
    let Some(hole) = mid.surface_loop(&neck, cut_radius, theta, n) else {
        return Err(misses("opening"));
    };
    let pad = match nozzle.pad {
        None => None,
        Some((pad_od, pad_t)) => {
            let n_pad = samples(0.5 * pad_od, shop.chord_tolerance);
            let outside = ConeSurface::outside(cone);
            let pad_mid = outside.offset(0.5 * pad_t);
            // The developed apex and loop of radius `rho` on the pad's own
            // mid-surface, centred on the nozzle axis.
            let developed = |rho: f64, n: usize| -> Option<(DVec2, Vec<DVec2>)> {
                let (c, _) = pad_mid.crossing(&neck, 0.0, 0.0)?;
                let curve = pad_mid.surface_loop(&neck, rho, theta, n)?;
                if let Some(mid) = cone.oblique() {
                    // On its own oblique cone, as the reducer's wall.
                    let own = mid.offset(pad_mid.r0 - mid.large);
                    let c = DVec2::new(pad_mid.angle_near(c, theta), c.z);
                    return Some(develop_about(&own, c, &curve));
                }
                let origin = develop_point(&pad_mid, theta, DVec2::new(theta, c.z));
                Some((
                    -origin,
                    curve
                        .iter()
                        .map(|&q| develop_point(&pad_mid, theta, q) - origin)
                        .collect(),
                ))
            };
            let footprint = outside.surface_loop(&neck, 0.5 * pad_od, theta, n_pad);
            let outline = developed(0.5 * pad_od, n_pad);
            let pad_hole = developed(0.5 * od + shop.bevel_allowance, n);
            let (Some(footprint), Some((apex, outline)), Some((_, hole))) =
                (footprint, outline, pad_hole)
            else {
                return Err(misses("pad"));
            };
            Some(PadPiece {
                od: pad_od,
                thickness: pad_t,
                footprint,
                outline,
                hole,
                apex: Some(apex),
            })
        }
    };
    let outside = ConeSurface::outside(cone);
    let meets = match shop.attachment {
        Attachment::SetIn => outside.offset(-cone.thickness),
        Attachment::SetOn => outside,
    };
    let neck_mid = 0.5 * (od - wall);
    let back = g.projection - g.flange_length().unwrap_or(0.0);
    let saddle = saddle(n, neck_mid, back, |phi| {
        meets.crossing(&neck, neck_mid, phi).map(|(_, s)| s)
    });
    let Some(saddle) = saddle else {
        return Err(misses("neck"));
    };
    Ok(NozzleCut {
        nozzle: index,
        mark: nozzle.mark.clone(),
        path,
        rolled: rolled_index,
        neck,
        cut_radius,
        centre: DVec2::new(theta, centre.z),
        hole,
        pad,
        saddle,
    })
}
