//! Fitting: per patch, the as-built surface as a NURBS like the design's, by least
//! squares with a smoothing term over the parameters of each point's projection.
//!
//! The design patch is refined by knot insertion (every span split evenly to a
//! target control spacing), which leaves it unchanged; the unknowns are the
//! displacements D_ij of its control points, so the fit is
//! `X(u, v) = S(u, v) + Σ R_ij(u, v) D_ij` with the design's weights (R_ij the
//! rational basis) — a noise-free scan of the design fits it exactly, and the
//! fitted patch is a NURBS that exports and meshes like any other. The normal
//! equations are banded (unknowns v-major) and solved by Cholesky; the smoothing
//! term penalizes second differences of D along u and v (wrapping across a
//! closed patch's seam, whose two columns are tied, as are the displacements of
//! a pole's coincident points). The knots are the design's, refined evenly, so
//! each data parameter lies in the span its neighbours do (the averaging rule's
//! aim); basis functions without data (the Schoenberg–Whitney condition) are
//! counted, and refused when there is no smoothing to fill them. The net grows
//! (spacing halved) until the residual is at the scanner's noise overall and in
//! every knot cell, with no more residuals past 4 sigmas than noise gives, or the
//! spacing reaches its floor.

use glam::{DVec3, DVec4};
use serde::Serialize;

use super::ScanError;
use super::cells::{NormalEquations, Sorted};
pub use super::sample::Sample;
use crate::nurbs::{KnotVector, NurbsSurface};

/// How to fit.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FitOptions {
    /// The scanner's noise (standard deviation), mm: the residual the net grows to.
    pub noise: f64,
    /// Weight of the smoothing term, relative to the data's mean diagonal.
    pub smoothing: f64,
    /// Smallest control spacing, mm.
    pub min_spacing: f64,
    /// Largest number of control points per patch.
    pub max_controls: usize,
}

impl FitOptions {
    /// Noise 1 mm, smoothing 0.05, spacing down to 60 mm, at most 40,000 controls.
    pub const DEFAULT: Self = Self {
        noise: 1.0,
        smoothing: 0.05,
        min_spacing: 60.0,
        max_controls: 40_000,
    };
}

/// The fit of one patch.
#[derive(Clone, Debug, Serialize)]
pub struct PatchFit {
    /// The fitted surface, local frame.
    #[serde(skip)]
    pub surface: NurbsSurface,
    /// Control spacing reached, mm.
    pub spacing: f64,
    /// Control net size (u, v).
    pub net: (usize, usize),
    /// Points fitted.
    pub points: usize,
    /// RMS of the normal residuals, mm.
    pub rms: f64,
    /// Largest normal residual, mm.
    pub max: f64,
    /// Basis functions with no data in their support.
    pub unsupported: usize,
    /// Nets tried.
    pub rounds: usize,
}

/// Longest control-polygon length along u (rows of the net) and along v.
fn net_lengths(surface: &NurbsSurface) -> (f64, f64) {
    let (nu, nv) = (surface.u_count(), surface.v_count());
    let p = surface.control_points();
    let along_u = (0..nv)
        .map(|j| {
            (1..nu)
                .map(|i| (p[i * nv + j] - p[(i - 1) * nv + j]).length())
                .sum::<f64>()
        })
        .fold(0.0, f64::max);
    let along_v = (0..nu)
        .map(|i| {
            (1..nv)
                .map(|j| (p[i * nv + j] - p[i * nv + j - 1]).length())
                .sum::<f64>()
        })
        .fold(0.0, f64::max);
    (along_u, along_v)
}

/// Knots splitting every span of `knots` into `parts` equal pieces.
fn splits(knots: &KnotVector, parts: usize) -> Vec<f64> {
    let mut out = Vec::new();
    for (a, b) in knots.spans() {
        for k in 1..parts {
            out.push(a + (b - a) * k as f64 / parts as f64);
        }
    }
    out
}

/// The design refined to a control spacing of about `spacing` mm.
fn refined(design: &NurbsSurface, spacing: f64) -> Result<NurbsSurface, ScanError> {
    let (lu, lv) = net_lengths(design);
    let su = design.u_knots().spans().len().max(1);
    let sv = design.v_knots().spans().len().max(1);
    let pu = ((lu / spacing / su as f64).ceil() as usize).max(1);
    let pv = ((lv / spacing / sv as f64).ceil() as usize).max(1);
    let singular = |e: crate::nurbs::NurbsError| ScanError::Singular {
        what: "refining the design patch".into(),
        rule: e.to_string(),
    };
    let s = design
        .refine_knots_u(&splits(design.u_knots(), pu))
        .map_err(singular)?;
    s.refine_knots_v(&splits(design.v_knots(), pv))
        .map_err(singular)
}

/// Fits `samples` on the patch `design` (local frame).
///
/// # Errors
///
/// [`ScanError::TooFewPoints`] under 16 samples, [`ScanError::Singular`] when
/// the normal equations are not positive definite (or, without smoothing,
/// a basis function has no data).
pub fn fit_patch(
    design: &NurbsSurface,
    samples: &[Sample],
    options: &FitOptions,
    what: &str,
) -> Result<PatchFit, ScanError> {
    if samples.len() < 16 {
        return Err(ScanError::TooFewPoints {
            what: what.to_string(),
            found: samples.len(),
            needed: 16,
        });
    }
    // At least quadratic both ways (a course is linear along its axis), so the
    // fitted deviation is smooth; elevation leaves the design unchanged.
    let elevated;
    let design = if design.v_degree() < 2 {
        elevated = design
            .elevate_degree_v(2 - design.v_degree())
            .map_err(|e| ScanError::Singular {
                what: what.to_string(),
                rule: e.to_string(),
            })?;
        &elevated
    } else {
        design
    };
    let (lu, lv) = net_lengths(design);
    let mut spacing = (lu.max(lv) / 8.0).max(options.min_spacing);
    let mut rounds = 0;
    let mut base = refined(design, spacing)?;
    loop {
        rounds += 1;
        let (fit, cells_ok) = solve(&base, samples, options, what)?;
        let next = spacing / 2.0;
        let (nu, nv) = (base.u_count(), base.v_count());
        let grown = refined(design, next);
        let can_grow = next >= options.min_spacing
            && grown
                .as_ref()
                .is_ok_and(|s| s.u_count() * s.v_count() <= options.max_controls)
            && nu * nv < samples.len();
        if (fit.rms <= options.noise && cells_ok) || !can_grow {
            return Ok(PatchFit {
                spacing,
                rounds,
                ..fit
            });
        }
        spacing = next;
        base = grown?;
    }
}

/// One least-squares solve on the refined net `base`; whether every knot cell's
/// residual is at the noise.
fn solve(
    base: &NurbsSurface,
    samples: &[Sample],
    options: &FitOptions,
    what: &str,
) -> Result<(PatchFit, bool), ScanError> {
    let (nu, nv) = (base.u_count(), base.v_count());
    let (p, q) = (base.u_degree(), base.v_degree());
    let size = nu * nv;
    let index = |i: usize, j: usize| j * nu + i;
    let width = (q * nu + p).max(2 * nu);
    let sorted = Sorted::new(base, samples);
    let NormalEquations {
        mut matrix,
        mut rhs,
        support,
    } = sorted.normal_equations(base, width);
    let unsupported = support.iter().filter(|&&s| s <= 0.0).count();
    if options.smoothing <= 0.0 && unsupported > 0 {
        return Err(ScanError::Singular {
            what: what.to_string(),
            rule: format!(
                "{unsupported} of {size} basis functions have no data in their support \
                 (Schoenberg–Whitney); add smoothing or points"
            ),
        });
    }
    let mean_diagonal = (0..size).map(|i| matrix.diagonal(i)).sum::<f64>() / size as f64;
    let lambda = options.smoothing * mean_diagonal.max(1e-12);
    let points = base.control_points();
    let same =
        |a: usize, b: usize| (points[a] - points[b]).length() <= 1e-9 * (1.0 + points[a].length());
    // Closed in u: column 0 and column nu − 1 coincide.
    let closed = (0..nv).all(|j| same(j, (nu - 1) * nv + j));
    let mut penalty = |entries: &[(usize, f64)], weight: f64| {
        for &(a, ca) in entries {
            for &(b, cb) in entries {
                if b <= a {
                    matrix.add(a, b, weight * ca * cb);
                }
            }
        }
    };
    let columns = if closed { nu - 1 } else { nu };
    for j in 0..nv {
        for i in 0..columns {
            let (prev, next) = if closed {
                ((i + columns - 1) % columns, (i + 1) % columns)
            } else if i == 0 || i + 1 == nu {
                continue;
            } else {
                (i - 1, i + 1)
            };
            penalty(
                &[
                    (index(prev, j), 1.0),
                    (index(i, j), -2.0),
                    (index(next, j), 1.0),
                ],
                lambda,
            );
        }
        if closed {
            penalty(
                &[(index(0, j), 1.0), (index(nu - 1, j), -1.0)],
                1e3 * mean_diagonal.max(1e-12),
            );
        }
    }
    for i in 0..nu {
        for j in 1..nv.saturating_sub(1) {
            penalty(
                &[
                    (index(i, j - 1), 1.0),
                    (index(i, j), -2.0),
                    (index(i, j + 1), 1.0),
                ],
                lambda,
            );
        }
    }
    for j in [0, nv - 1] {
        let pole = (1..nu).all(|i| same(j, i * nv + j));
        if pole {
            for i in 1..nu {
                penalty(
                    &[(index(0, j), 1.0), (index(i, j), -1.0)],
                    1e3 * mean_diagonal.max(1e-12),
                );
            }
        }
    }
    if let Err(pivot) = matrix.solve(&mut rhs) {
        return Err(ScanError::Singular {
            what: what.to_string(),
            rule: format!("normal equations not positive definite at unknown {pivot} of {size}"),
        });
    }
    let mut homogeneous: Vec<DVec4> = base.homogeneous_points().to_vec();
    for i in 0..nu {
        for j in 0..nv {
            let k = index(i, j);
            let d = DVec3::new(rhs[0][k], rhs[1][k], rhs[2][k]);
            let h = &mut homogeneous[i * nv + j];
            *h += DVec4::from((d * h.w, 0.0));
        }
    }
    let surface =
        NurbsSurface::try_new(base.u_knots().clone(), base.v_knots().clone(), homogeneous)
            .map_err(|e| ScanError::Singular {
                what: what.to_string(),
                rule: e.to_string(),
            })?;
    // Residuals, overall and per knot cell.
    let per_cell = sorted.residuals(base, &rhs, 4.0 * options.noise);
    let sum: f64 = per_cell.iter().map(|c| c.squares).sum();
    let max = per_cell.iter().map(|c| c.max).fold(0.0, f64::max);
    // Past 4 sigmas: 6·10⁻⁵ of Gaussian residuals; more means a shape the net
    // cannot follow yet (a dent between its control points).
    let far: usize = per_cell.iter().map(|c| c.far).sum();
    let cells_ok = far as f64 <= 2.0 + 1e-3 * samples.len() as f64
        && per_cell.iter().all(|c| {
            let n = c.points as f64;
            c.points < 8 || (c.squares / n).sqrt() <= options.noise * (1.0 + 4.0 / (2.0 * n).sqrt())
        });
    Ok((
        PatchFit {
            surface,
            spacing: 0.0,
            net: (nu, nv),
            points: samples.len(),
            rms: (sum / samples.len() as f64).sqrt(),
            max,
            unsupported,
            rounds: 0,
        },
        cells_ok,
    ))
}

/// Normal deviation of the fitted surface from the design at (u, v): (X − S)·n.
pub fn deviation_at(design: &NurbsSurface, fitted: &NurbsSurface, u: f64, v: f64) -> f64 {
    (fitted.point(u, v) - design.point(u, v)).dot(design.normal(u, v))
}
