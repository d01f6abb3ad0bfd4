//! How far a flat triangle departs from the surface at one probe: the measures
//! refinement holds every triangle to.
//!
//! A probe is a 3D point of the triangle (its centroid, an edge midpoint) with the
//! parameters where the surface should be nearest (the parametric centroid or
//! midpoint). Two distances are taken and the larger counts: from S at those
//! parameters to the triangle's plane (the chordal deviation of the seed reports,
//! cheap and exact for the normal offset), and from the 3D point to the surface,
//! found by Gauss–Newton steps from those parameters until they converge (the orthogonal distance of a
//! point inversion, which is what a check of the finished mesh measures). The
//! Gauss–Newton distance is that of a surface point actually reached, so it never
//! understates the true distance. When the patch's analytic surface is known (a
//! plane, cylinder, cone, sphere, torus or spheroid, on which the NURBS lies to
//! rounding), the second distance is that surface's closed-form distance and the
//! first needs only S, not its derivatives: the cheap path the mesher takes for
//! every vessel patch. The probes of an edge (its midpoint, towards a pole along
//! the other end's meridian) and the normals at its ends are here too, shared by
//! refinement and the screen.

use glam::{DVec2, DVec3};

use crate::mesh::cdt::patch::{PatchInfo, Vertex};

/// Most Gauss–Newton steps per probe (two are usual).
const MAX_STEPS: usize = 8;
/// A step shorter than this share of the distance has converged: the distance
/// found then exceeds the true one by at most half its square, 5·10⁻⁵.
const CONVERGED: f64 = 1e-2;

/// The deviation at a probe: `point` on the triangle, `uv` its parameters, and
/// the triangle's plane through `origin` with unit normal `unit`.
pub(in crate::mesh::cdt) fn deviation(
    info: &PatchInfo,
    point: DVec3,
    uv: DVec2,
    origin: DVec3,
    unit: DVec3,
) -> f64 {
    deviation_and_height(info, point, uv, origin, unit).0
}

/// [`deviation`] and the signed height of S at `uv` over the plane (along
/// `unit`): what the triangle's quadratic model is built from (`peak`).
pub(in crate::mesh::cdt) fn deviation_and_height(
    info: &PatchInfo,
    point: DVec3,
    uv: DVec2,
    origin: DVec3,
    unit: DVec3,
) -> (f64, f64) {
    if let Some(analytic) = &info.analytic {
        let s = info.surface.point(info.wrap_u(uv.x), uv.y);
        let height = (s - origin).dot(unit);
        return (analytic.distance(point).max(height.abs()), height);
    }
    let ((u0, u1), (v0, v1)) = info.surface.domain();
    let mut at = uv;
    let mut height = None;
    let mut nearest = f64::INFINITY;
    for _ in 0..MAX_STEPS {
        let d = info.surface.derivatives(info.wrap_u(at.x), at.y);
        let r = d.point - point;
        let distance = r.length();
        nearest = nearest.min(distance);
        height.get_or_insert_with(|| (d.point - origin).dot(unit));
        let (e, f, g) = (d.du.dot(d.du), d.du.dot(d.dv), d.dv.dot(d.dv));
        let det = e * g - f * f;
        if det.is_nan() || det <= 1e-12 * e * g {
            break;
        }
        let (a, b) = (r.dot(d.du), r.dot(d.dv));
        let step = -DVec2::new(g * a - f * b, e * b - f * a) / det;
        if (d.du * step.x + d.dv * step.y).length() <= CONVERGED * distance {
            break;
        }
        at += step;
        at.y = at.y.clamp(v0, v1);
        if !info.closed_u {
            at.x = at.x.clamp(u0, u1);
        }
    }
    let height = height.unwrap_or(0.0);
    (nearest.max(height.abs()), height)
}

/// The normal at vertex `w` of an edge whose other end is at `other`: at a pole,
/// the limit along the edge's meridian.
pub(in crate::mesh::cdt) fn end_normal(info: &PatchInfo, w: &Vertex, other: DVec2) -> DVec3 {
    if w.pole {
        info.normal(DVec2::new(other.x, w.uv.y))
    } else {
        w.normal
    }
}

/// The parameters probed on the edge between `x` and `y`: the midpoint, except
/// that towards a pole the edge follows the meridian of its other end.
pub(in crate::mesh::cdt) fn edge_probe_uv(x: &Vertex, y: &Vertex) -> DVec2 {
    edge_uv_at(x, y, 0.5)
}

/// The parameters at share `s` of the way from `x` to `y` along the edge, as
/// [`edge_probe_uv`] takes them.
pub(in crate::mesh::cdt) fn edge_uv_at(x: &Vertex, y: &Vertex, s: f64) -> DVec2 {
    let (mut ux, mut uy) = (x.uv, y.uv);
    if x.pole && !y.pole {
        ux.x = uy.x;
    } else if y.pole && !x.pole {
        uy.x = ux.x;
    }
    if s == 0.5 {
        0.5 * (ux + uy)
    } else {
        ux + (uy - ux) * s
    }
}
