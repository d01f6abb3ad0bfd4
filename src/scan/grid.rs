//! Exact interpolation of an ordered grid of points (a CMM's rows and columns)
//! by a tensor-product B-spline surface: the seed's equation (12),
//! `P_s = Σ_i Σ_j d_ij N_i,p(u_s) N_j,q(v_s)`, done as its digest asks.
//!
//! Parameters by chord length (or centripetally), averaged over the rows and
//! over the columns; clamped knots by averaging the parameters (Piegl & Tiller
//! eq. 9.8), which keeps each data parameter in the support of its basis
//! function; the Schoenberg–Whitney condition `N_k(ū_k) > 0` is checked and a
//! grid breaking it refused. The Kronecker system separates: curve
//! interpolations along u for each column of points, then along v through the
//! intermediate poles. Each curve system is banded (within `p` of its
//! diagonal) and totally positive, so it is solved by elimination without
//! pivoting in band storage. Interpolation reproduces the data exactly, noise
//! included: for scans, use the least-squares [fit](super::fit).

use glam::{DVec3, DVec4};

use super::ScanError;
use crate::nurbs::{KnotVector, MAX_DEGREE, NurbsSurface, basis_functions};

/// How data parameters are spaced.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Parametrization {
    /// By chord length (distance between consecutive points).
    ChordLength,
    /// By the square root of chord length (better for sharp turns).
    Centripetal,
    /// Equally spaced, as the seed's paper does.
    Uniform,
}

/// A grid's interpolating surface and the data parameters it passes through.
#[derive(Clone, Debug)]
pub struct GridFit {
    /// The surface: `surface.point(u[i], v[j]) = points[i * nv + j]`.
    pub surface: NurbsSurface,
    /// Parameters of the grid's rows along u.
    pub u: Vec<f64>,
    /// Parameters of the grid's columns along v.
    pub v: Vec<f64>,
}

/// The B-spline surface of degrees `(p, q)` through the `nu × nv` grid
/// `points` (`points[i * nv + j]`, `i` along u), with the parameters
/// `parametrization` gives.
///
/// # Errors
///
/// [`ScanError::Options`] for a degree outside 1..=[`MAX_DEGREE`] or not below
/// the grid's point count in its direction, or a point not finite;
/// [`ScanError::Singular`] when the parameters break the Schoenberg–Whitney
/// condition (coincident rows or columns).
pub fn interpolate_grid(
    points: &[DVec3],
    (nu, nv): (usize, usize),
    (p, q): (usize, usize),
    parametrization: Parametrization,
) -> Result<GridFit, ScanError> {
    for (degree, count, field) in [(p, nu, "degree u"), (q, nv, "degree v")] {
        if degree == 0 || degree > MAX_DEGREE || degree >= count {
            return Err(ScanError::Options {
                field,
                value: degree as f64,
                rule: "must be at least 1, at most 12, and below the grid's points in its direction",
            });
        }
    }
    if points.len() != nu * nv {
        return Err(ScanError::Options {
            field: "grid",
            value: points.len() as f64,
            rule: "points must number rows × columns",
        });
    }
    if points.iter().any(|p| !p.is_finite()) {
        return Err(ScanError::Options {
            field: "grid",
            value: f64::NAN,
            rule: "every point must be finite",
        });
    }
    let at = |i: usize, j: usize| points[i * nv + j];
    let u_params = parameters(nu, nv, at, parametrization);
    let v_params = parameters(nv, nu, |k, line| at(line, k), parametrization);
    let u_knots = averaged_knots(&u_params, p)?;
    let v_knots = averaged_knots(&v_params, q)?;
    // Along u for each column j, then along v for each row i of those poles.
    let mut poles = vec![DVec3::ZERO; nu * nv];
    for j in 0..nv {
        let data: Vec<DVec3> = (0..nu).map(|i| at(i, j)).collect();
        let solved = interpolate_curve(&data, &u_params, &u_knots, "u")?;
        for (i, d) in solved.into_iter().enumerate() {
            poles[i * nv + j] = d;
        }
    }
    for i in 0..nu {
        let data: Vec<DVec3> = poles[i * nv..(i + 1) * nv].to_vec();
        let solved = interpolate_curve(&data, &v_params, &v_knots, "v")?;
        poles[i * nv..(i + 1) * nv].copy_from_slice(&solved);
    }
    let homogeneous = poles.into_iter().map(|d| DVec4::from((d, 1.0))).collect();
    let surface =
        NurbsSurface::try_new(u_knots, v_knots, homogeneous).map_err(|e| ScanError::Singular {
            what: "grid interpolation".into(),
            rule: e.to_string(),
        })?;
    Ok(GridFit {
        surface,
        u: u_params,
        v: v_params,
    })
}

/// Parameters in [0, 1] of `count` points along each of `lines` lines
/// (`point(k, line)`), averaged over the lines that have any length.
fn parameters(
    count: usize,
    lines: usize,
    point: impl Fn(usize, usize) -> DVec3,
    parametrization: Parametrization,
) -> Vec<f64> {
    let uniform: Vec<f64> = (0..count).map(|k| k as f64 / (count - 1) as f64).collect();
    if parametrization == Parametrization::Uniform {
        return uniform;
    }
    let mut sum = vec![0.0; count];
    let mut used = 0;
    for line in 0..lines {
        let steps: Vec<f64> = (1..count)
            .map(|k| {
                let d = (point(k, line) - point(k - 1, line)).length();
                match parametrization {
                    Parametrization::Centripetal => d.sqrt(),
                    _ => d,
                }
            })
            .collect();
        let total: f64 = steps.iter().sum();
        if total <= 0.0 {
            // A pole: every point of the line coincides.
            continue;
        }
        used += 1;
        let mut run = 0.0;
        for (k, s) in steps.iter().enumerate() {
            run += s;
            sum[k + 1] += run / total;
        }
    }
    if used == 0 {
        return uniform;
    }
    let mut out: Vec<f64> = sum.into_iter().map(|s| s / used as f64).collect();
    out[count - 1] = 1.0;
    out
}

/// Clamped knots of degree `p` by averaging `params` (Piegl & Tiller eq. 9.8).
fn averaged_knots(params: &[f64], p: usize) -> Result<KnotVector, ScanError> {
    let n = params.len() - 1;
    let mut knots = vec![0.0; p + 1];
    for j in 1..=n - p {
        knots.push(params[j..j + p].iter().sum::<f64>() / p as f64);
    }
    knots.extend(std::iter::repeat_n(1.0, p + 1));
    KnotVector::try_new(p, knots).map_err(|e| ScanError::Singular {
        what: "grid interpolation: knots by averaging".into(),
        rule: e.to_string(),
    })
}

/// The control points of the degree-`knots.degree()` curve through `data` at
/// `params`: the collocation system, banded, solved without pivoting.
fn interpolate_curve(
    data: &[DVec3],
    params: &[f64],
    knots: &KnotVector,
    direction: &str,
) -> Result<Vec<DVec3>, ScanError> {
    let n = data.len();
    let p = knots.degree();
    // Band storage: row k holds columns k − p ..= k + p at offsets 0 ..= 2p.
    let width = 2 * p + 1;
    let mut band = vec![0.0; n * width];
    let col = |k: usize, c: usize| c + p - k;
    for (k, &t) in params.iter().enumerate() {
        let span = knots.find_span(t);
        let values = basis_functions(knots.as_slice(), span, t, p);
        for (a, &value) in values.iter().take(p + 1).enumerate() {
            let c = span - p + a;
            if c + p < k || c > k + p {
                continue;
            }
            band[k * width + col(k, c)] = value;
        }
        // Schoenberg–Whitney: the k-th basis function is non-zero at ū_k.
        if !(span - p..=span).contains(&k) || band[k * width + p] <= 0.0 {
            return Err(ScanError::Singular {
                what: format!("grid interpolation along {direction}"),
                rule: format!(
                    "basis function {k} is zero at its data parameter {t:.6} \
                     (Schoenberg–Whitney); rows or columns coincide"
                ),
            });
        }
    }
    let mut rhs = data.to_vec();
    for k in 0..n {
        let pivot = band[k * width + p];
        if pivot.abs() < 1e-14 {
            return Err(ScanError::Singular {
                what: format!("grid interpolation along {direction}"),
                rule: format!("zero pivot at row {k} of {n}"),
            });
        }
        for r in k + 1..(k + p + 1).min(n) {
            let factor = band[r * width + col(r, k)] / pivot;
            if factor == 0.0 {
                continue;
            }
            for c in k..(k + p + 1).min(n) {
                band[r * width + col(r, c)] -= factor * band[k * width + col(k, c)];
            }
            let above = rhs[k];
            rhs[r] -= factor * above;
        }
    }
    for k in (0..n).rev() {
        let mut sum = rhs[k];
        for c in k + 1..(k + p + 1).min(n) {
            sum -= band[k * width + col(k, c)] * rhs[c];
        }
        rhs[k] = sum / band[k * width + p];
    }
    Ok(rhs)
}
