//! The rows of a whole sphere patch without openings (a hemispherical head's
//! crown, a torispherical or F&D crown: one ring and a pole), sized by the
//! chordal bound of the whole triangle rather than by a metric at its vertices.
//!
//! It sits in the structured path (`structured::structured` asks it for a
//! sphere patch's rows before the lattice's): `layout` chooses the rows on
//! the ideal sphere, from the given ring towards the pole, each next row the
//! same count shifted by half a step or a few smaller counts, raised as far as
//! the zip of the two rows keeps every point of every triangle within the
//! tolerance (`bound`); this module finds the sphere's frame in the surface
//! and converts the rows to (u, v). Counts are not rounded (to quarter turns
//! or a slack): the patch is meshed as a whole turn, not as a `sector`.
//! Triangle counts come out 1.10–1.13× an ideal mesh of equilateral triangles
//! that just meet the tolerance (`tests/mesh_chordal.rs`), against 1.22–1.43×
//! for the metric-sized lattice.

mod bound;
mod layout;
mod row;

use std::f64::consts::{FRAC_1_SQRT_2, FRAC_PI_2, TAU};

use glam::DVec3;

use self::bound::Bound;
use self::layout::laid_out;
use self::row::{Row, Spacing};
use super::Side;
use crate::mesh::TessellationOptions;
use crate::mesh::cdt::CdtError;
use crate::mesh::cdt::patch::PatchInfo;
use crate::mesh::cdt::region::Region;
use crate::nurbs::builders::FULL_TURN_KNOTS;
use crate::parts::Analytic;

/// Largest distance of a vertex evaluated from the surface to the row's ideal
/// point, relative to the radius, for the surface's parametrization to be the
/// full turn of quarter arcs the rows are converted with.
const SAME_POINT: f64 = 1e-9;

/// Whether [`rows`] may lay out `region` (the sector path is then skipped): a
/// sphere patch closed in u by a full turn of quarter arcs, without holes,
/// with one pole, without a stretch limit.
pub(super) fn applies(info: &PatchInfo, region: &Region, options: &TessellationOptions) -> bool {
    let knots = info.surface.u_knots();
    matches!(info.analytic, Some(Analytic::Sphere { .. }))
        && region.holes.is_empty()
        && info.closed_u
        && knots.degree() == 2
        && knots.as_slice() == FULL_TURN_KNOTS
        && info.collapsed[2] != info.collapsed[3]
        && options.max_stretch.is_none()
        && options.tolerance > 0.0
}

/// A row of the lattice: its v and its u values, seam to seam.
type Parallel = (f64, Vec<f64>);

/// The rows strictly between the ring and the pole as `(v, u values)`, v
/// increasing, each running from `lo.x` to `hi.x`; `None` when the patch is not
/// one [`applies`] takes, its sides are not a ring and a pole, or no row fits.
pub(super) fn rows(
    info: &PatchInfo,
    region: &Region,
    options: &TessellationOptions,
    bottom: &Side,
    top: &Side,
    budget: usize,
) -> Result<Option<Vec<Parallel>>, CdtError> {
    let Some(Analytic::Sphere { center, radius }) = info.analytic else {
        return Ok(None);
    };
    if !applies(info, region, options) {
        return Ok(None);
    }
    let (lo, hi) = region.bounds();
    let (ring, ring_v, pole_v) = match (bottom, top) {
        (Side::Ring(u), Side::Pole) => (u, lo.y, hi.y),
        (Side::Pole, Side::Ring(u)) => (u, hi.y, lo.y),
        _ => return Ok(None),
    };
    let Some(frame) = Frame::new(info, center, radius, lo.x, ring_v, pole_v) else {
        return Ok(None);
    };
    let Some(first) = frame.ring(info, ring, ring_v) else {
        return Ok(None);
    };
    let bound = Bound::new(radius, options);
    let Some(chosen) = laid_out(&bound, first, budget)? else {
        return Ok(None);
    };
    let mut out = Vec::with_capacity(chosen.len());
    for row in &chosen {
        let v = frame.v_of(info, row.phi, ring_v, pole_v);
        let lams = Spacing::new(row.count, row.shifted).lams;
        let Some(us) = frame.us_of(info, &lams, v, (lo.x, hi.x)) else {
            return Ok(None);
        };
        out.push((v, us));
    }
    if pole_v < ring_v {
        out.reverse();
    }
    Ok(Some(out))
}

/// The sphere's frame as the surface lays it: centre, radius, the axis towards
/// the pole, the seam's direction and the direction of increasing u.
struct Frame {
    center: DVec3,
    radius: f64,
    axis: DVec3,
    e1: DVec3,
    e2: DVec3,
    /// The seam's angle in the surface's own turn (its angle at u = u0 is 0).
    seam: f64,
}

impl Frame {
    fn new(
        info: &PatchInfo,
        center: DVec3,
        radius: f64,
        seam_u: f64,
        ring_v: f64,
        pole_v: f64,
    ) -> Option<Self> {
        let s = info.surface;
        let u = info.wrap_u(seam_u);
        let axis = (s.point(u, pole_v) - center).normalize_or_zero();
        let d = s.point(u, ring_v) - center;
        let e1 = (d - axis * d.dot(axis)).normalize_or_zero();
        if axis == DVec3::ZERO || e1 == DVec3::ZERO || radius.is_nan() || radius <= 0.0 {
            return None;
        }
        let ((u0, u1), _) = s.domain();
        let seam = angle_of((u - u0) / (u1 - u0));
        let mut frame = Self {
            center,
            radius,
            axis,
            e1,
            e2: axis.cross(e1),
            seam,
        };
        // u turns the right way about the axis: a quarter turn on is +e2.
        let q = s.point(info.wrap_u(seam_u + 0.25 * (u1 - u0)), ring_v) - center;
        if q.dot(frame.e2) < 0.0 {
            frame.e2 = -frame.e2;
        }
        Some(frame)
    }

    /// The ring's row: its colatitude and longitudes, `None` unless its
    /// vertices are uniform in angle from the seam (as `edge_parameters` puts
    /// them on a circle).
    fn ring(&self, info: &PatchInfo, us: &[f64], v: f64) -> Option<Row> {
        let n = us.len().checked_sub(1).filter(|&n| n >= 3)?;
        let p = info.surface.point(info.wrap_u(us[0]), v) - self.center;
        let phi = p.normalize().dot(self.axis).clamp(-1.0, 1.0).acos();
        if phi.is_nan() || phi <= 0.0 || phi >= std::f64::consts::PI {
            return None;
        }
        let spacing = Spacing::new(n, false);
        let at = spacing.at(self.radius, phi);
        for (k, &u) in us.iter().enumerate() {
            let q = info.surface.point(info.wrap_u(u), v) - self.center;
            let local = DVec3::new(q.dot(self.e1), q.dot(self.e2), q.dot(self.axis));
            if local.distance(spacing.vertex(at, k)) > 1e-7 * self.radius {
                return None;
            }
        }
        Some(Row {
            phi,
            count: n,
            shifted: false,
        })
    }

    /// The v of colatitude `phi`, by bisection along the meridian.
    fn v_of(&self, info: &PatchInfo, phi: f64, ring_v: f64, pole_v: f64) -> f64 {
        let u = info.wrap_u(0.0);
        let colatitude = |v: f64| {
            let d = (info.surface.point(u, v) - self.center).normalize_or_zero();
            d.dot(self.axis).clamp(-1.0, 1.0).acos()
        };
        // Colatitude falls from the ring's to 0 going from `ring_v` to `pole_v`.
        let (mut a, mut b) = (ring_v, pole_v);
        for _ in 0..64 {
            let m = 0.5 * (a + b);
            if colatitude(m) > phi { a = m } else { b = m }
        }
        0.5 * (a + b)
    }

    /// The u values of longitudes `lams` from the seam on the row at `v`,
    /// increasing from `span.0` to `span.1`; `None` unless the surface puts
    /// each at its point.
    fn us_of(&self, info: &PatchInfo, lams: &[f64], v: f64, span: (f64, f64)) -> Option<Vec<f64>> {
        let ((u0, u1), _) = info.surface.domain();
        let period = u1 - u0;
        let last = lams.len() - 1;
        let mut us = Vec::with_capacity(lams.len());
        for (k, &lam) in lams.iter().enumerate() {
            let u = match k {
                0 => span.0,
                _ if k == last => span.1,
                _ => {
                    let own = u0 + period * parameter_of((self.seam + lam).rem_euclid(TAU));
                    span.0 + (own - span.0).rem_euclid(period)
                }
            };
            if us.last().is_some_and(|&p: &f64| u <= p) {
                return None;
            }
            us.push(u);
        }
        // Spot checks of the conversion: the first steps and the middle.
        let phi_point = |lam: f64| {
            let d = (info.surface.point(info.wrap_u(us[0]), v) - self.center).normalize_or_zero();
            let phi = d.dot(self.axis).clamp(-1.0, 1.0).acos();
            let (s, c) = phi.sin_cos();
            let (sl, cl) = lam.sin_cos();
            self.center + self.radius * (self.e1 * s * cl + self.e2 * s * sl + self.axis * c)
        };
        for k in [1, 2, last / 2].into_iter().filter(|&k| k < last) {
            let p = info.surface.point(info.wrap_u(us[k]), v);
            if p.distance(phi_point(lams[k])) > SAME_POINT * self.radius {
                return None;
            }
        }
        Some(us)
    }
}

/// The angle of parameter `t` ∈ [0, 1) of a full turn of four symmetric
/// rational quarter arcs (middle weight cos 45°), from its start.
fn angle_of(t: f64) -> f64 {
    let x = 4.0 * t.rem_euclid(1.0);
    let q = x.floor().min(3.0);
    let s = x - q;
    let w = FRAC_1_SQRT_2;
    q * FRAC_PI_2 + 2.0 * (w * s).atan2(1.0 - s + w * s)
}

/// The parameter in [0, 1) of angle `a` ∈ [0, 2π) on such a turn (the
/// inverse of [`angle_of`], as `layout::circles` places a circle's vertices).
fn parameter_of(a: f64) -> f64 {
    let x = a / FRAC_PI_2;
    let q = x.floor().clamp(0.0, 3.0);
    let phi = a - q * FRAC_PI_2;
    let s = (0.5 * phi).tan();
    let w = FRAC_1_SQRT_2;
    (q + s / (w + s * (1.0 - w))) / 4.0
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn parameters_and_angles_invert() {
        for k in 0..64 {
            let a = TAU * k as f64 / 64.0 + 0.01;
            assert!((angle_of(parameter_of(a)) - a).abs() < 1e-12, "{a}");
        }
    }
}
