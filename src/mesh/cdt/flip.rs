//! The flip criterion: Delaunay in the surface's size metric, so that the
//! triangulation is shaped by the curvature of the surface and not by its
//! parametrization.
//!
//! An interior edge is flipped when the quad around it is strictly convex in (u, v)
//! (so the (u, v) triangulation stays valid) and the opposite vertex lies inside the
//! circumcircle of the triangle, both measured in the mean metric of the quad's four
//! vertices (the same for both diagonals, so one quad cannot flip back and forth).
//! At a collapsed side a pole vertex's u is arbitrary, so it is taken as the u of the
//! quad's other vertices clamped: a fan triangle around the pole is then judged by
//! the sector it covers. An edge joining two pole vertices is never created.

use glam::DVec2;

use super::metric::Metric;
use super::trimesh::TriMesh;

/// Relative size of an incircle determinant treated as zero (cocircular).
const COCIRCULAR: f64 = 1e-10;
/// Relative twice-area below which a (u, v) triangle counts as not strictly convex.
const STRICT: f64 = 1e-12;

/// Twice the signed area of `(a, b, c)`.
pub(super) fn orient(a: DVec2, b: DVec2, c: DVec2) -> f64 {
    (b - a).perp_dot(c - a)
}

/// Whether `(a, b, c)` is counter-clockwise with a margin relative to its size.
pub(super) fn strictly_ccw(a: DVec2, b: DVec2, c: DVec2) -> bool {
    let scale = (b - a).length_squared().max((c - a).length_squared());
    orient(a, b, c) > STRICT * scale
}

/// Parameters of vertex `k` for metric measures: a pole vertex's u is clamped to
/// the range of the non-pole vertices in `group`.
pub(super) fn effective_uv(mesh: &TriMesh, k: u32, group: &[u32]) -> DVec2 {
    let v = &mesh.verts[k as usize];
    if !v.pole {
        return v.uv;
    }
    let (lo, hi) = group
        .iter()
        .map(|&g| &mesh.verts[g as usize])
        .filter(|w| !w.pole)
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), w| {
            (lo.min(w.uv.x), hi.max(w.uv.x))
        });
    if lo <= hi {
        DVec2::new(v.uv.x.clamp(lo, hi), v.uv.y)
    } else {
        v.uv
    }
}

/// Whether edge `i` of triangle `t` should be flipped.
pub(super) fn should_flip(mesh: &TriMesh, t: u32, i: usize) -> bool {
    let Some((quad, _)) = mesh.quad(t, i) else {
        return false;
    };
    let [_, _, c, d] = quad;
    let vert = |k: u32| &mesh.verts[k as usize];
    if vert(c).pole && vert(d).pole {
        return false;
    }
    let [pa, pb, pc, pd] = quad.map(|k| vert(k).uv);
    // The flipped triangles (c, a, d) and (d, b, c) must be valid in (u, v).
    if !(strictly_ccw(pc, pa, pd) && strictly_ccw(pd, pb, pc)) {
        return false;
    }
    let metric = Metric::mean(&quad.map(|k| vert(k).metric));
    let [ea, eb, ec, ed] = quad.map(|k| effective_uv(mesh, k, &quad));
    let centre = (ea + eb + ec + ed) * 0.25;
    let [qa, qb, qc, qd] = [ea, eb, ec, ed].map(|p| metric.chart(p - centre));
    let current_ok = strictly_ccw(qa, qb, qc) && strictly_ccw(qb, qa, qd);
    let flipped_ok = strictly_ccw(qc, qa, qd) && strictly_ccw(qd, qb, qc);
    if current_ok != flipped_ok {
        return flipped_ok;
    }
    incircle(qa, qb, qc, qd)
}

/// Whether `d` lies strictly inside the circumcircle of the counter-clockwise
/// triangle `(a, b, c)`, beyond rounding.
pub(super) fn incircle(a: DVec2, b: DVec2, c: DVec2, d: DVec2) -> bool {
    let (ad, bd, cd) = (a - d, b - d, c - d);
    let (la, lb, lc) = (
        ad.length_squared(),
        bd.length_squared(),
        cd.length_squared(),
    );
    let det = la * bd.perp_dot(cd) + lb * cd.perp_dot(ad) + lc * ad.perp_dot(bd);
    let scale = la.max(lb).max(lc);
    det > COCIRCULAR * scale * scale
}
