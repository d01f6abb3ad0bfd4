//! Whether a patch region is a whole surface of revolution that repeats every
//! quarter turn about Z, and the exact quarter turn itself.
//!
//! The sector path's test (see `plan` and `structured::sector`): [`quarter`] gives
//! the first quarter of a region — the whole parameter rectangle of a patch
//! closed in u, without holes — when the surface's control points are the first
//! quarter's turned by multiples of 90° and the rings' vertices are spaced alike
//! in every quarter; [`turn`] is the turn ((x, y) → (−y, x): no rounding). A leaf
//! of the mesher, so the decision table reads it without the structured path.

use glam::{DVec2, DVec3, DVec4};

use super::patch::PatchInfo;
use super::region::{Region, UvLoop};
use crate::nurbs::builders::FULL_TURN_KNOTS;

/// Quarters of the turn.
pub(in crate::mesh::cdt) const QUARTERS: usize = 4;
/// Largest difference, relative to the surface's size, between a quarter's
/// control points and the first quarter's turned, and between the rings' spacing
/// in different quarters (relative to the period).
const SYMMETRY: f64 = 1e-12;

/// The first quarter of `region` — the patch's whole parameter rectangle, closed
/// in u, without holes — when the patch and its rings repeat every quarter turn
/// about Z; `None` otherwise.
pub(in crate::mesh::cdt) fn quarter(info: &PatchInfo, region: &Region) -> Option<Region> {
    if !info.closed_u || !region.holes.is_empty() || !quarter_turned(info) {
        return None;
    }
    let ((u0, u1), _) = info.surface.domain();
    let (lo, hi) = region.bounds();
    if lo.x != u0 || hi.x != u1 {
        return None;
    }
    let width = (u1 - u0) / QUARTERS as f64;
    let eps = SYMMETRY * (u1 - u0);
    let pts = &region.outer.uv;
    // Every loop vertex on the rectangle; the two rings' u values.
    let on = |a: f64, b: f64| (a - b).abs() <= eps;
    if !pts
        .iter()
        .all(|p| p.y == lo.y || p.y == hi.y || on(p.x, lo.x) || on(p.x, hi.x))
    {
        return None;
    }
    let ring = |v: f64| {
        let mut u: Vec<f64> = pts.iter().filter(|p| p.y == v).map(|p| p.x).collect();
        u.sort_by(f64::total_cmp);
        u.dedup();
        u
    };
    let first = |u: &[f64]| -> Option<Vec<f64>> {
        // A pole: its two corners only.
        if u.len() == 2 {
            return Some(vec![u0, u0 + width]);
        }
        let n = u.len() - 1;
        if !n.is_multiple_of(QUARTERS) || !on(u[0], u0) || !on(u[n], u1) {
            return None;
        }
        let m = n / QUARTERS;
        let repeats =
            (1..QUARTERS).all(|q| (0..=m).all(|k| on(u[q * m + k], u[k] + q as f64 * width)));
        if !repeats {
            return None;
        }
        let mut part = u[..=m].to_vec();
        part[0] = u0;
        part[m] = u0 + width;
        Some(part)
    };
    let bottom = first(&ring(lo.y))?;
    let top = first(&ring(hi.y))?;
    // The quarter's rectangle: the bottom ring left to right, the top ring back.
    let mut outer: Vec<DVec2> = bottom.iter().map(|&u| DVec2::new(u, lo.y)).collect();
    outer.extend(top.iter().rev().map(|&u| DVec2::new(u, hi.y)));
    Some(Region::new(UvLoop::new(outer)))
}

/// Whether the surface is a full turn about Z in four quarter spans, each
/// quarter's control points the first quarter's turned by its multiple of 90°.
fn quarter_turned(info: &PatchInfo) -> bool {
    let s = info.surface;
    let knots = s.u_knots();
    if knots.degree() != 2 || knots.as_slice() != FULL_TURN_KNOTS {
        return false;
    }
    let points = s.homogeneous_points();
    let nu = 2 * QUARTERS + 1;
    if !points.len().is_multiple_of(nu) {
        return false;
    }
    let nv = points.len() / nu;
    let size = points
        .iter()
        .map(|p| p.truncate().length())
        .fold(0.0f64, f64::max)
        .max(1.0);
    let eps = SYMMETRY * size;
    // Column c is column c mod 2 of the first quarter turned c / 2 times (the
    // last, c = 8, closes the turn onto the first).
    (2..nu).all(|c| {
        (0..nv).all(|j| {
            let turned = turn_h(points[(c % 2) * nv + j], c / 2);
            (turned - points[c * nv + j]).abs().max_element() <= eps
        })
    })
}

/// `p` turned by `q` quarter turns about Z, exactly.
pub(in crate::mesh::cdt) fn turn(p: DVec3, q: usize) -> DVec3 {
    // Adding 0.0 turns a −0.0 into 0.0, so that points on the axis stay bitwise
    // the same.
    match q % QUARTERS {
        0 => p,
        1 => DVec3::new(-p.y + 0.0, p.x, p.z),
        2 => DVec3::new(-p.x + 0.0, -p.y + 0.0, p.z),
        _ => DVec3::new(p.y, -p.x + 0.0, p.z),
    }
}

/// [`turn`] of a homogeneous point.
fn turn_h(p: DVec4, q: usize) -> DVec4 {
    turn(p.truncate(), q).extend(p.w)
}
