//! The size field of the mesher as a metric on the parameter plane.
//!
//! At each (u, v) the surface's principal curvatures κ₁, κ₂ (from the first and
//! second fundamental forms) give a target edge length per principal direction:
//! h = √3·√(δ(2ρ − δ)) with ρ = 1/|κ|, the side of the equilateral triangle whose
//! circumscribed circle has sagitta δ on a sphere of radius ρ, so an equilateral
//! triangle of side h deviates from the surface by δ at its centroid (an edge of
//! that length has sagitta only ¾ δ at its midpoint). The angle tolerance and the
//! maximum edge length shorten h further, a cap (the size of the region) keeps
//! flat directions finite, and no direction may be more than
//! [`max_stretch`](TessellationOptions::max_stretch) times longer than the other (no needles along straight
//! generators). The result is stored as a symmetric 2×2 [`Metric`] in
//! (u, v): a parameter step d has length √(dᵀ M d) in units of the target size, so
//! the seed lattice is equilateral and the flip criterion is Delaunay in it.

use glam::{DVec2, DVec3};

use crate::mesh::TessellationOptions;
use crate::nurbs::SurfaceDerivatives;

/// Ratio of |S_u|² and |S_v|² beyond which the first fundamental form counts as
/// singular (the point is at a pole).
const SINGULAR: f64 = 1e-18;

/// A symmetric positive-definite 2×2 metric `[[uu, uv], [uv, vv]]` on (u, v).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct Metric {
    /// Entry of u·u.
    pub uu: f64,
    /// Entry of u·v.
    pub uv: f64,
    /// Entry of v·v.
    pub vv: f64,
}

impl Metric {
    /// A metric not computed yet (NaN entries): the structured path's vertices
    /// carry it until refinement, the only reader, fills theirs in.
    pub const UNSET: Metric = Metric {
        uu: f64::NAN,
        uv: f64::NAN,
        vv: f64::NAN,
    };

    /// Squared length of a parameter step.
    pub fn length_sq(&self, d: DVec2) -> f64 {
        self.uu * d.x * d.x + 2.0 * self.uv * d.x * d.y + self.vv * d.y * d.y
    }

    /// Determinant.
    pub fn det(&self) -> f64 {
        self.uu * self.vv - self.uv * self.uv
    }

    /// The mean of several metrics.
    pub fn mean(metrics: &[Metric]) -> Metric {
        let n = metrics.len().max(1) as f64;
        let (uu, uv, vv) = metrics.iter().fold((0.0, 0.0, 0.0), |(a, b, c), m| {
            (a + m.uu, b + m.uv, c + m.vv)
        });
        Metric {
            uu: uu / n,
            uv: uv / n,
            vv: vv / n,
        }
    }

    /// A Euclidean image of a parameter step: `Lᵀ d` for the Cholesky factor
    /// `M = L Lᵀ`, so that `|chart(d)|² = dᵀ M d`. Orientation-preserving.
    pub fn chart(&self, d: DVec2) -> DVec2 {
        let l11 = self.uu.max(0.0).sqrt();
        if l11 <= 0.0 {
            return DVec2::new(0.0, self.vv.max(0.0).sqrt() * d.y);
        }
        let l21 = self.uv / l11;
        let l22 = (self.vv - l21 * l21).max(0.0).sqrt();
        DVec2::new(l11 * d.x + l21 * d.y, l22 * d.y)
    }

    /// Metric length per unit u of a step along u.
    pub fn along_u(&self) -> f64 {
        self.uu.max(0.0).sqrt()
    }

    /// Metric distance per unit v between two lines of constant v.
    pub fn across_v(&self) -> f64 {
        if self.uu > 0.0 {
            (self.det().max(0.0) / self.uu).sqrt()
        } else {
            self.vv.max(0.0).sqrt()
        }
    }

    /// Half-widths in u and v of the parameter box holding the metric ball of
    /// radius `r`.
    pub fn ball_extent(&self, r: f64) -> DVec2 {
        let det = self.det();
        if det.is_nan() || det <= 0.0 {
            return DVec2::splat(f64::INFINITY);
        }
        DVec2::new(r * (self.vv / det).sqrt(), r * (self.uu / det).sqrt())
    }
}

/// Target sizes from curvature and the tessellation options.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct Sizing {
    /// Deviation δ the sizes aim at, mm (a share of the tolerance).
    pub deviation: f64,
    /// Angle tolerance, radians.
    pub angle: Option<f64>,
    /// Longest edge, mm.
    pub max_edge: Option<f64>,
    /// Longest size in any direction (the region's extent), mm.
    pub cap: f64,
    /// Largest ratio between the sizes in two directions.
    pub stretch: Option<f64>,
}

impl Sizing {
    /// Sizing for `options`, aiming at `share` of the tolerance, capped at `cap` mm.
    pub fn new(options: &TessellationOptions, share: f64, cap: f64) -> Self {
        Self {
            deviation: options.tolerance * share,
            angle: options.angle_tolerance.map(f64::to_radians),
            max_edge: options.max_edge_length,
            cap,
            stretch: options.max_stretch,
        }
    }

    /// Target edge length, mm, in a direction of normal curvature `kappa` (1/mm).
    pub fn size(&self, kappa: f64) -> f64 {
        let kappa = kappa.abs();
        let delta = self.deviation;
        let mut h = self.cap;
        if kappa * delta > 1e-14 {
            let rho = 1.0 / kappa;
            let circumradius = if delta < rho {
                (delta * (2.0 * rho - delta)).sqrt()
            } else {
                rho
            };
            h = h.min(3f64.sqrt() * circumradius);
            if let Some(angle) = self.angle {
                h = h.min(angle / kappa);
            }
        }
        if let Some(max) = self.max_edge {
            h = h.min(max);
        }
        h
    }

    /// The metric at a regular point with derivatives `d` and unit normal `n`, or
    /// `None` where the first fundamental form is singular (a pole).
    pub fn metric(&self, d: &SurfaceDerivatives, n: DVec3) -> Option<Metric> {
        let (e, f, g) = (d.du.dot(d.du), d.du.dot(d.dv), d.dv.dot(d.dv));
        // Cholesky of the first fundamental form: G = L Lᵀ.
        // A vanishing partial (a pole) leaves the curvature along it undefined.
        if !(e > SINGULAR * g && g > SINGULAR * e) {
            return None;
        }
        let l11 = e.sqrt();
        let l21 = f / l11;
        let l22_sq = g - l21 * l21;
        if l22_sq.is_nan() || l22_sq <= 1e-24 * e.max(g) {
            return None;
        }
        let l22 = l22_sq.sqrt();
        let (b11, b12, b22) = (d.duu.dot(n), d.duv.dot(n), d.dvv.dot(n));
        // C = L⁻¹ B L⁻ᵀ, symmetric; its eigenvalues are the principal curvatures.
        let (i11, i21, i22) = (1.0 / l11, -l21 / (l11 * l22), 1.0 / l22);
        let x11 = i11 * b11;
        let x12 = i11 * b12;
        let x21 = i21 * b11 + i22 * b12;
        let x22 = i21 * b12 + i22 * b22;
        let (p, q, r) = (x11 * i11, x11 * i21 + x12 * i22, x21 * i21 + x22 * i22);
        let mean = 0.5 * (p + r);
        let radius = (0.25 * (p - r) * (p - r) + q * q).sqrt();
        let (k1, k2) = (mean + radius, mean - radius);
        let y1 = if q.abs() > 1e-300 {
            DVec2::new(k1 - r, q).normalize_or(DVec2::X)
        } else if p >= r {
            DVec2::X
        } else {
            DVec2::Y
        };
        let y2 = y1.perp();
        let (h1, h2) = (self.size(k1), self.size(k2));
        let longest = self.stretch.map_or(f64::INFINITY, |r| r * h1.min(h2));
        let (h1, h2) = (h1.min(longest), h2.min(longest));
        let (w1, w2) = (h1.powi(-2), h2.powi(-2));
        // W = Σ wᵢ yᵢ yᵢᵀ, then M = L W Lᵀ.
        let (w11, w12, w22) = (
            w1 * y1.x * y1.x + w2 * y2.x * y2.x,
            w1 * y1.x * y1.y + w2 * y2.x * y2.y,
            w1 * y1.y * y1.y + w2 * y2.y * y2.y,
        );
        let metric = Metric {
            uu: l11 * l11 * w11,
            uv: l11 * (l21 * w11 + l22 * w12),
            vv: l21 * l21 * w11 + 2.0 * l21 * l22 * w12 + l22 * l22 * w22,
        };
        (metric.det() > 0.0 && metric.uu.is_finite() && metric.vv.is_finite()).then_some(metric)
    }

    /// An isotropic metric of the cap size for parameter scales `scale` (mm per unit
    /// u and v): the fallback where no metric can be computed.
    pub fn fallback(&self, scale: DVec2) -> Metric {
        let w = self.cap.powi(-2);
        Metric {
            uu: w * scale.x * scale.x,
            uv: 0.0,
            vv: w * scale.y * scale.y,
        }
    }
}
