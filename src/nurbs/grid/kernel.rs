//! The inner loops of grid evaluation: the per-row contraction along u and the point
//! kernels along v, with the lane helpers the normal kernels share.
//!
//! Per grid row the caller contracts the control net with the u basis into
//! homogeneous isocurve control points ([`contract_rows`]). The v kernels then run
//! over the row run by run: inside a run the `q + 1` isocurve points are loop
//! invariants and the v basis values are contiguous streams. Points are computed
//! [`LANES`] at a time in structure-of-arrays form, so that the contraction, the
//! reciprocal of `w` and the projective division compile to packed SIMD operations
//! even on the baseline target; only the final store interleaves x, y, z. Orders 2, 3
//! and 4 (degrees 1–3) are compiled as fixed-size loops; higher degrees take a loop
//! over the runtime order.

use std::array;

use glam::{DVec3, DVec4};

use super::basis::{GridBasis, Run};

/// Grid points computed together in structure-of-arrays form.
pub(super) const LANES: usize = 4;

/// `out[l] = Σ_k basis[k * len + i] · net[(first + k) * stride + l]`: the homogeneous
/// control points of the isocurve at grid parameter `i` of a direction whose basis
/// values are `basis` (`order` functions, `len` parameters).
pub(super) fn contract_rows(
    net: &[DVec4],
    stride: usize,
    run: &Run,
    basis: &[f64],
    order: usize,
    i: usize,
    out: &mut [DVec4],
) {
    let len = basis.len() / order;
    let out = &mut out[..stride];
    for k in 0..order {
        let b = basis[k * len + i];
        let row = &net[(run.first + k) * stride..][..stride];
        if k == 0 {
            for (o, &c) in out.iter_mut().zip(row) {
                *o = c * b;
            }
        } else {
            for (o, &c) in out.iter_mut().zip(row) {
                *o += c * b;
            }
        }
    }
}

/// The `N` control points of a run as arrays.
#[inline(always)]
pub(super) fn run_points<const N: usize>(iso: &[DVec4], run: &Run) -> [[f64; 4]; N] {
    array::from_fn(|k| iso[run.first + k].to_array())
}

/// The `N` basis streams of a run, each as long as the run.
#[inline(always)]
pub(super) fn streams<'a, const N: usize>(
    basis: &'a [f64],
    total: usize,
    run: &Run,
) -> [&'a [f64]; N] {
    let len = run.end - run.start;
    array::from_fn(|k| &basis[k * total + run.start..][..len])
}

/// Lanes `base..base + count` of every stream; missing lanes repeat the last one.
#[inline(always)]
pub(super) fn lanes<const N: usize>(
    streams: &[&[f64]; N],
    base: usize,
    count: usize,
) -> [[f64; LANES]; N] {
    array::from_fn(|k| array::from_fn(|l| streams[k][base + l.min(count - 1)]))
}

/// `Σ_k c[k] · b[k]` per lane, per homogeneous coordinate.
#[inline(always)]
pub(super) fn contract<const N: usize>(
    c: &[[f64; 4]; N],
    b: &[[f64; LANES]; N],
) -> [[f64; LANES]; 4] {
    let mut h = [[0.0; LANES]; 4];
    for d in 0..4 {
        for l in 0..LANES {
            h[d][l] = c[0][d] * b[0][l];
        }
    }
    for k in 1..N {
        for d in 0..4 {
            for l in 0..LANES {
                h[d][l] += c[k][d] * b[k][l];
            }
        }
    }
    h
}

/// Points of one grid row from its isocurve control points `iso`.
pub(super) fn points_row(iso: &[DVec4], v: &GridBasis, out: &mut [DVec3]) {
    match v.order() {
        2 => points_row_fixed::<2>(iso, v, out),
        3 => points_row_fixed::<3>(iso, v, out),
        4 => points_row_fixed::<4>(iso, v, out),
        _ => points_row_dynamic(iso, v, out),
    }
}

/// Euclidean coordinates of [`LANES`] homogeneous points.
#[inline(always)]
fn project(h: &[[f64; LANES]; 4]) -> [[f64; LANES]; 3] {
    let mut p = [[0.0; LANES]; 3];
    for l in 0..LANES {
        let inv = 1.0 / h[3][l];
        for d in 0..3 {
            p[d][l] = h[d][l] * inv;
        }
    }
    p
}

#[inline(always)]
fn points_row_fixed<const N: usize>(iso: &[DVec4], v: &GridBasis, out: &mut [DVec3]) {
    let total = v.len();
    for run in v.runs() {
        let c = run_points::<N>(iso, run);
        let b = streams::<N>(v.values(), total, run);
        let out = &mut out[run.start..run.end];
        let mut chunks = out.chunks_exact_mut(LANES);
        let mut base = 0;
        for chunk in &mut chunks {
            let p = project(&contract(&c, &lanes(&b, base, LANES)));
            for (l, o) in chunk.iter_mut().enumerate() {
                *o = DVec3::new(p[0][l], p[1][l], p[2][l]);
            }
            base += LANES;
        }
        let tail = chunks.into_remainder();
        if !tail.is_empty() {
            let p = project(&contract(&c, &lanes(&b, base, tail.len())));
            for (l, o) in tail.iter_mut().enumerate() {
                *o = DVec3::new(p[0][l], p[1][l], p[2][l]);
            }
        }
    }
}

fn points_row_dynamic(iso: &[DVec4], v: &GridBasis, out: &mut [DVec3]) {
    let total = v.len();
    let values = v.values();
    for run in v.runs() {
        let c = &iso[run.first..run.first + v.order()];
        for j in run.start..run.end {
            let mut h = DVec4::ZERO;
            for (k, &ck) in c.iter().enumerate() {
                h += ck * values[k * total + j];
            }
            out[j] = h.truncate() * (1.0 / h.w);
        }
    }
}
