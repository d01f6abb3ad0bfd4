//! Rational B-spline curves over homogeneous points.
//!
//! A [`NurbsCurve`] stores its control points as `DVec4(w·x, w·y, w·z, w)`, so that
//! evaluation, knot insertion and splitting are the non-rational algorithms applied
//! once in four dimensions, followed by one projective division. Builders in
//! [`super::builders`] make the exact lines, arcs and conics the parts are made of.

use glam::{DVec3, DVec4};

use super::basis::{basis_derivatives, basis_functions};
use super::{KnotVector, NurbsError};

/// A rational B-spline curve: a clamped knot vector and homogeneous control points.
/// The degree is the knot vector's; the point count is `knots − degree − 1`.
#[derive(Clone, Debug, PartialEq)]
pub struct NurbsCurve {
    knots: KnotVector,
    points: Vec<DVec4>,
}

/// Point and first two derivatives of a curve at one parameter.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CurveDerivatives {
    /// C(u).
    pub point: DVec3,
    /// C′(u).
    pub first: DVec3,
    /// C″(u).
    pub second: DVec3,
}

/// Checks one homogeneous control point: finite coordinates, weight finite and > 0.
pub(crate) fn check_homogeneous(index: usize, p: DVec4) -> Result<(), NurbsError> {
    if !(p.w.is_finite() && p.w > 0.0) {
        return Err(NurbsError::WeightNotPositive { index, weight: p.w });
    }
    if !p.is_finite() {
        return Err(NurbsError::PointNotFinite { index });
    }
    Ok(())
}

/// Homogeneous form `(w·p, w)` of a Euclidean point with a weight.
#[inline]
pub fn homogeneous(p: DVec3, w: f64) -> DVec4 {
    (p * w).extend(w)
}

/// Euclidean point of a homogeneous point.
#[inline]
pub fn euclidean(p: DVec4) -> DVec3 {
    p.truncate() / p.w
}

impl NurbsCurve {
    /// A curve from its knot vector and homogeneous control points `(w·x, w·y, w·z, w)`.
    pub fn try_new(knots: KnotVector, points: Vec<DVec4>) -> Result<Self, NurbsError> {
        if points.len() != knots.basis_count() {
            return Err(NurbsError::PointCountMismatch {
                direction: "curve",
                expected: knots.basis_count(),
                got: points.len(),
            });
        }
        for (i, &p) in points.iter().enumerate() {
            check_homogeneous(i, p)?;
        }
        Ok(Self { knots, points })
    }

    /// A curve from Euclidean control points and their weights.
    pub fn try_from_weighted(
        knots: KnotVector,
        points: &[DVec3],
        weights: &[f64],
    ) -> Result<Self, NurbsError> {
        if weights.len() != points.len() {
            return Err(NurbsError::PointCountMismatch {
                direction: "curve",
                expected: points.len(),
                got: weights.len(),
            });
        }
        let hom = points
            .iter()
            .zip(weights)
            .map(|(&p, &w)| homogeneous(p, w))
            .collect();
        Self::try_new(knots, hom)
    }

    /// A non-rational curve (all weights 1).
    pub fn try_polynomial(knots: KnotVector, points: &[DVec3]) -> Result<Self, NurbsError> {
        let hom = points.iter().map(|&p| p.extend(1.0)).collect();
        Self::try_new(knots, hom)
    }

    /// Builds without validation, for kernel algorithms that preserve validity.
    pub(crate) fn from_raw(knots: KnotVector, points: Vec<DVec4>) -> Self {
        debug_assert_eq!(points.len(), knots.basis_count());
        Self { knots, points }
    }

    /// The degree (from the knot vector).
    #[inline]
    pub fn degree(&self) -> usize {
        self.knots.degree()
    }

    /// The knot vector.
    #[inline]
    pub fn knots(&self) -> &KnotVector {
        &self.knots
    }

    /// Homogeneous control points `(w·x, w·y, w·z, w)`.
    #[inline]
    pub fn homogeneous_points(&self) -> &[DVec4] {
        &self.points
    }

    /// Euclidean control points.
    pub fn control_points(&self) -> Vec<DVec3> {
        self.points.iter().map(|&p| euclidean(p)).collect()
    }

    /// Weights of the control points.
    pub fn weights(&self) -> Vec<f64> {
        self.points.iter().map(|p| p.w).collect()
    }

    /// True when every weight is 1 (a polynomial B-spline).
    pub fn is_polynomial(&self) -> bool {
        self.points.iter().all(|p| p.w == 1.0)
    }

    /// Parameter domain.
    #[inline]
    pub fn domain(&self) -> (f64, f64) {
        self.knots.domain()
    }

    /// Homogeneous point Cʷ(u); `u` is clamped to the domain.
    #[inline]
    pub fn homogeneous_point(&self, u: f64) -> DVec4 {
        let p = self.degree();
        let u = self.knots.clamp(u);
        let span = self.knots.find_span(u);
        let n = basis_functions(self.knots.as_slice(), span, u, p);
        let mut c = DVec4::ZERO;
        for (j, &nj) in n.iter().enumerate().take(p + 1) {
            c += self.points[span - p + j] * nj;
        }
        c
    }

    /// Point C(u) (A4.1); `u` is clamped to the domain.
    #[inline]
    pub fn point(&self, u: f64) -> DVec3 {
        euclidean(self.homogeneous_point(u))
    }

    /// Homogeneous derivatives Aʷ⁽ᵏ⁾(u), k = 0..D (A3.2 in four dimensions).
    pub fn homogeneous_derivatives<const D: usize>(&self, u: f64) -> [DVec4; D] {
        let p = self.degree();
        let u = self.knots.clamp(u);
        let span = self.knots.find_span(u);
        let ders = basis_derivatives::<D>(self.knots.as_slice(), span, u, p);
        let mut out = [DVec4::ZERO; D];
        for (k, row) in ders.iter().enumerate() {
            for (j, &n) in row.iter().enumerate().take(p + 1) {
                out[k] += self.points[span - p + j] * n;
            }
        }
        out
    }

    /// Point and first and second derivatives of the rational curve (A4.2).
    pub fn derivatives(&self, u: f64) -> CurveDerivatives {
        let [a0, a1, a2] = self.homogeneous_derivatives::<3>(u);
        let [point, first, second] = rational_derivatives([a0, a1, a2]);
        CurveDerivatives {
            point,
            first,
            second,
        }
    }

    /// Unit tangent at `u`; zero where the derivative vanishes.
    pub fn tangent(&self, u: f64) -> DVec3 {
        self.derivatives(u).first.normalize_or_zero()
    }

    /// The first control point (= the start point of a clamped curve).
    pub fn start(&self) -> DVec3 {
        euclidean(self.points[0])
    }

    /// The last control point (= the end point of a clamped curve).
    pub fn end(&self) -> DVec3 {
        euclidean(self.points[self.points.len() - 1])
    }

    /// The same point set traversed backwards, over the same domain.
    pub fn reversed(&self) -> Self {
        let mut points = self.points.clone();
        points.reverse();
        Self::from_raw(self.knots.reversed(), points)
    }

    /// The curve with knots mapped affinely onto `[start, end]`.
    pub fn reparametrized(&self, start: f64, end: f64) -> Result<Self, NurbsError> {
        Ok(Self::from_raw(
            self.knots.reparametrized(start, end)?,
            self.points.clone(),
        ))
    }

    /// The curve with its control points replaced (same knots, same count), for
    /// transforms that map homogeneous points.
    pub(crate) fn map_points(&self, f: impl Fn(DVec4) -> DVec4) -> Self {
        Self::from_raw(
            self.knots.clone(),
            self.points.iter().map(|&p| f(p)).collect(),
        )
    }
}

/// Derivatives of the projected curve from homogeneous derivatives (A4.2, up to 2):
/// `C⁽ᵏ⁾ = (A⁽ᵏ⁾ − Σ_{i=1..k} C(k,i) w⁽ⁱ⁾ C⁽ᵏ⁻ⁱ⁾) / w`.
#[inline]
pub(crate) fn rational_derivatives(a: [DVec4; 3]) -> [DVec3; 3] {
    let w = a[0].w;
    let c0 = a[0].truncate() / w;
    let c1 = (a[1].truncate() - a[1].w * c0) / w;
    let c2 = (a[2].truncate() - 2.0 * a[1].w * c1 - a[2].w * c0) / w;
    [c0, c1, c2]
}
