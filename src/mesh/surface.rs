//! Facts about a patch's surface that the opening cuts, the region layout and the
//! mesher all read: whether it closes on itself in u ([`closed_in_u`]) and
//! whether it is a cross-section swept straight along part-frame Z
//! ([`Extrusion`], which lets a course's openings be marched once per placement
//! across its axis and its triangles be screened with one row evaluator).
//! A leaf of `mesh`: it uses no other mesh module.

use glam::DVec4;

use crate::nurbs::{NurbsSurface, Side};

/// How far the two rows' axial coordinates may stray from one value, relative to
/// the course's length (rounding of z·w / w).
const ROW_SLACK: f64 = 1e-12;

/// A host patch swept straight along part-frame Z: degree 1 and two control rows
/// in v, equal x·w, y·w and w in both rows, each row at one z.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Extrusion {
    /// Axial coordinate of the v0 row.
    pub(crate) z0: f64,
    /// Axial coordinate of the v1 row.
    pub(crate) z1: f64,
    /// The v-domain.
    pub(crate) v: (f64, f64),
}

impl Extrusion {
    /// The extrusion `surface` is, if it is one.
    pub(crate) fn of(surface: &NurbsSurface) -> Option<Self> {
        if surface.v_degree() != 1 || surface.v_count() != 2 {
            return None;
        }
        let points = surface.homogeneous_points();
        let z = |p: DVec4| p.z / p.w;
        let (z0, z1) = (z(points[0]), z(points[1]));
        if !(z0.is_finite() && z1.is_finite()) || z0 == z1 {
            return None;
        }
        let slack = ROW_SLACK * (z1 - z0).abs().max(z0.abs()).max(z1.abs());
        let swept = points.chunks_exact(2).all(|row| {
            let (a, b) = (row[0], row[1]);
            a.x.to_bits() == b.x.to_bits()
                && a.y.to_bits() == b.y.to_bits()
                && a.w.to_bits() == b.w.to_bits()
                && (z(a) - z0).abs() <= slack
                && (z(b) - z1).abs() <= slack
        });
        swept.then_some(Self {
            z0,
            z1,
            v: surface.v_knots().domain(),
        })
    }

    /// The axial coordinate at `v` (linear: both rows share weights), so that
    /// S(u, v) is the v0 row's point at u moved to it.
    pub(crate) fn z_at(&self, v: f64) -> f64 {
        let (v0, v1) = self.v;
        self.z0 + (v - v0) / (v1 - v0) * (self.z1 - self.z0)
    }

    /// The v at axial coordinate `z` (v is linear in z: both rows share weights).
    pub(crate) fn v_at(&self, z: f64) -> f64 {
        let (v0, v1) = self.v;
        v0 + (z - self.z0) / (self.z1 - self.z0) * (v1 - v0)
    }

    /// Whether `v` lies strictly inside the v-domain.
    pub(crate) fn holds(&self, v: f64) -> bool {
        v > self.v.0 && v < self.v.1
    }
}

/// True when the surface is closed in u: its u0 and u1 edges coincide.
pub fn closed_in_u(surface: &NurbsSurface) -> bool {
    let a = surface.boundary(Side::UMin).control_points();
    let b = surface.boundary(Side::UMax).control_points();
    let s = a.iter().fold(1.0f64, |m, p| m.max(p.abs().max_element()));
    a.len() == b.len()
        && a.iter()
            .zip(&b)
            .all(|(p, q)| (*p - *q).length() <= 1e-9 * s)
}
