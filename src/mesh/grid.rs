//! Curvature-sized grid tessellation of one patch.
//!
//! Each parameter direction gets its own samples: the density of segments along u
//! at a point is |S_u| / h, where h = 2√(δ(2ρ − δ)) is the chord whose sagitta on a
//! circle of the isocurve's radius of curvature ρ equals the tolerance δ (and h is
//! further limited by the angle tolerance and the maximum edge length). The density
//! is maximised across the other direction, integrated, and inverted so every
//! segment carries the same share. The grid is evaluated with the kernel's batched
//! evaluator and split into triangles; triangles collapsed at a pole are dropped.
//!
//! This bounds the chordal error along the isocurves; the error-bounded
//! constrained-Delaunay mesher (a later stage) bounds it everywhere.

use glam::DVec3;

use super::{Mesh, TessellationOptions};
use crate::nurbs::NurbsSurface;

/// Samples per Bézier span used to estimate lengths and curvatures.
const SAMPLES_PER_SPAN: usize = 8;
/// Share of the tolerance given to the isocurve sagitta (the rest covers the
/// diagonal of each grid cell).
const SAGITTA_SHARE: f64 = 0.7;
/// Most segments along one direction of one patch.
const MAX_SEGMENTS: usize = 4096;

/// Parameters of the estimation samples along one knot vector.
fn sample_params(spans: &[(f64, f64)]) -> Vec<f64> {
    let mut out = Vec::with_capacity(spans.len() * SAMPLES_PER_SPAN + 1);
    for &(a, b) in spans {
        for k in 0..SAMPLES_PER_SPAN {
            out.push(a + (b - a) * k as f64 / SAMPLES_PER_SPAN as f64);
        }
    }
    if let Some(&(_, b)) = spans.last() {
        out.push(b);
    }
    out
}

/// Longest chord allowed on a curve of curvature `kappa` (1/mm).
fn allowed_chord(kappa: f64, options: &TessellationOptions) -> f64 {
    let delta = options.tolerance * SAGITTA_SHARE;
    let mut h = if kappa * delta < 1e-12 {
        f64::INFINITY
    } else {
        let rho = 1.0 / kappa;
        if delta >= rho {
            2.0 * rho
        } else {
            2.0 * (delta * (2.0 * rho - delta)).sqrt()
        }
    };
    if let Some(angle) = options.angle_tolerance
        && kappa > 0.0
    {
        h = h.min(angle.to_radians() / kappa);
    }
    if let Some(max) = options.max_edge_length {
        h = h.min(max);
    }
    h
}

/// Grid parameters along one direction from sampled densities (segments per unit
/// parameter) at `params`.
fn place(params: &[f64], density: &[f64], min_segments: usize) -> Vec<f64> {
    let mut cumulative = vec![0.0; params.len()];
    for k in 1..params.len() {
        cumulative[k] =
            cumulative[k - 1] + 0.5 * (density[k] + density[k - 1]) * (params[k] - params[k - 1]);
    }
    let total = cumulative[params.len() - 1];
    let n = if total.is_finite() {
        (total.ceil() as usize).clamp(min_segments.max(1), MAX_SEGMENTS)
    } else {
        MAX_SEGMENTS
    };
    let (first, last) = (params[0], params[params.len() - 1]);
    if !(total > 0.0 && total.is_finite()) {
        return (0..=n)
            .map(|k| first + (last - first) * k as f64 / n as f64)
            .collect();
    }
    let mut out = Vec::with_capacity(n + 1);
    out.push(first);
    let mut seg = 1;
    for k in 1..n {
        let target = total * k as f64 / n as f64;
        while seg < params.len() - 1 && cumulative[seg] < target {
            seg += 1;
        }
        let (c0, c1) = (cumulative[seg - 1], cumulative[seg]);
        let t = if c1 > c0 {
            (target - c0) / (c1 - c0)
        } else {
            0.0
        };
        out.push(params[seg - 1] + t * (params[seg] - params[seg - 1]));
    }
    out.push(last);
    out
}

/// Meshes one surface to the chordal tolerance of `options` (assumed validated).
pub fn tessellate(surface: &NurbsSurface, options: &TessellationOptions) -> Mesh {
    let us = sample_params(&surface.u_knots().spans());
    let vs = sample_params(&surface.v_knots().spans());
    let mut du = vec![0.0f64; us.len()];
    let mut dv = vec![0.0f64; vs.len()];
    for (i, &u) in us.iter().enumerate() {
        for (j, &v) in vs.iter().enumerate() {
            let d = surface.derivatives(u, v);
            let su = d.du.length();
            if su > 0.0 {
                let kappa = d.du.cross(d.duu).length() / (su * su * su);
                du[i] = du[i].max(su / allowed_chord(kappa, options));
            }
            let sv = d.dv.length();
            if sv > 0.0 {
                let kappa = d.dv.cross(d.dvv).length() / (sv * sv * sv);
                dv[j] = dv[j].max(sv / allowed_chord(kappa, options));
            }
        }
    }
    let grid_u = place(&us, &du, surface.u_knots().spans().len());
    let grid_v = place(&vs, &dv, 1);
    let mut positions = Vec::new();
    let mut normals = Vec::new();
    surface.evaluate_grid_with_normals(&grid_u, &grid_v, &mut positions, &mut normals);
    let nv = grid_v.len();
    let scale = positions
        .iter()
        .fold(0.0f64, |m, p| m.max(p.abs().max_element()))
        .max(1.0);
    let same = |a: DVec3, b: DVec3| (a - b).length() <= 1e-12 * scale;
    let mut indices = Vec::with_capacity((grid_u.len() - 1) * (nv - 1) * 6);
    for i in 0..grid_u.len() - 1 {
        for j in 0..nv - 1 {
            let a = (i * nv + j) as u32;
            let b = ((i + 1) * nv + j) as u32;
            let c = ((i + 1) * nv + j + 1) as u32;
            let d = (i * nv + j + 1) as u32;
            for tri in [[a, b, c], [a, c, d]] {
                let [p, q, r] = tri.map(|k| positions[k as usize]);
                if !(same(p, q) || same(q, r) || same(p, r)) {
                    indices.extend_from_slice(&tri);
                }
            }
        }
    }
    Mesh {
        positions,
        normals,
        indices,
    }
}
