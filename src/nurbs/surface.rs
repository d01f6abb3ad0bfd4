//! Rational B-spline (tensor-product) surfaces over homogeneous points.
//!
//! A [`NurbsSurface`] is the unit of geometry every later stage works on: the part
//! builders produce them, the mesher samples them, the exporters write them. Control
//! points are stored row-major, `points[i * v_count + j]`, with `i` along u and `j`
//! along v. The outward normal of every vessel patch is `S_u × S_v`.

use glam::{DVec3, DVec4};

use super::basis::{
    MAX_ORDER, SMALL_ORDER, basis_derivatives_in, basis_functions, basis_functions_in,
};
use super::curve::{check_homogeneous, euclidean};
use super::{KnotVector, NurbsCurve, NurbsError};

/// A rational tensor-product B-spline surface.
#[derive(Clone, Debug, PartialEq)]
pub struct NurbsSurface {
    u_knots: KnotVector,
    v_knots: KnotVector,
    points: Vec<DVec4>,
}

/// Point and first partial derivatives of a surface at one (u, v): what Newton
/// iterations need, at half the cost of [`SurfaceDerivatives`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FirstDerivatives {
    /// S(u, v).
    pub point: DVec3,
    /// ∂S/∂u.
    pub du: DVec3,
    /// ∂S/∂v.
    pub dv: DVec3,
}

/// Point, first and second partial derivatives of a surface at one (u, v).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SurfaceDerivatives {
    /// S(u, v).
    pub point: DVec3,
    /// ∂S/∂u.
    pub du: DVec3,
    /// ∂S/∂v.
    pub dv: DVec3,
    /// ∂²S/∂u².
    pub duu: DVec3,
    /// ∂²S/∂u∂v.
    pub duv: DVec3,
    /// ∂²S/∂v².
    pub dvv: DVec3,
}

impl NurbsSurface {
    /// A surface from two knot vectors and `nu × nv` homogeneous points, row-major
    /// (`points[i * nv + j]`, `i` along u).
    pub fn try_new(
        u_knots: KnotVector,
        v_knots: KnotVector,
        points: Vec<DVec4>,
    ) -> Result<Self, NurbsError> {
        let (nu, nv) = (u_knots.basis_count(), v_knots.basis_count());
        if points.len() != nu * nv {
            return Err(NurbsError::PointCountMismatch {
                direction: "u × v",
                expected: nu * nv,
                got: points.len(),
            });
        }
        for (i, &p) in points.iter().enumerate() {
            check_homogeneous(i, p)?;
        }
        Ok(Self {
            u_knots,
            v_knots,
            points,
        })
    }

    /// Builds without validation, for kernel algorithms that preserve validity.
    pub(crate) fn from_raw(u_knots: KnotVector, v_knots: KnotVector, points: Vec<DVec4>) -> Self {
        debug_assert_eq!(points.len(), u_knots.basis_count() * v_knots.basis_count());
        Self {
            u_knots,
            v_knots,
            points,
        }
    }

    /// Knot vector along u.
    #[inline]
    pub fn u_knots(&self) -> &KnotVector {
        &self.u_knots
    }

    /// Knot vector along v.
    #[inline]
    pub fn v_knots(&self) -> &KnotVector {
        &self.v_knots
    }

    /// Degree along u.
    #[inline]
    pub fn u_degree(&self) -> usize {
        self.u_knots.degree()
    }

    /// Degree along v.
    #[inline]
    pub fn v_degree(&self) -> usize {
        self.v_knots.degree()
    }

    /// Number of control points along u.
    #[inline]
    pub fn u_count(&self) -> usize {
        self.u_knots.basis_count()
    }

    /// Number of control points along v.
    #[inline]
    pub fn v_count(&self) -> usize {
        self.v_knots.basis_count()
    }

    /// Homogeneous control points, row-major.
    #[inline]
    pub fn homogeneous_points(&self) -> &[DVec4] {
        &self.points
    }

    /// Homogeneous control point `(i, j)`.
    #[inline]
    pub fn homogeneous_point_at(&self, i: usize, j: usize) -> DVec4 {
        self.points[i * self.v_count() + j]
    }

    /// Euclidean control points, row-major.
    pub fn control_points(&self) -> Vec<DVec3> {
        self.points.iter().map(|&p| euclidean(p)).collect()
    }

    /// Parameter domain `((u0, u1), (v0, v1))`.
    #[inline]
    pub fn domain(&self) -> ((f64, f64), (f64, f64)) {
        (self.u_knots.domain(), self.v_knots.domain())
    }

    /// Homogeneous point Sʷ(u, v); parameters are clamped to the domain.
    #[inline]
    pub fn homogeneous_point(&self, u: f64, v: f64) -> DVec4 {
        if self.u_degree() < SMALL_ORDER && self.v_degree() < SMALL_ORDER {
            self.homogeneous_point_in::<SMALL_ORDER>(u, v)
        } else {
            self.homogeneous_point_in::<MAX_ORDER>(u, v)
        }
    }

    /// [`homogeneous_point`](Self::homogeneous_point) with basis arrays of `N`
    /// entries (`N` above both degrees).
    #[inline]
    fn homogeneous_point_in<const N: usize>(&self, u: f64, v: f64) -> DVec4 {
        let (p, q) = (self.u_degree(), self.v_degree());
        let u = self.u_knots.clamp(u);
        let v = self.v_knots.clamp(v);
        let su = self.u_knots.find_span(u);
        let sv = self.v_knots.find_span(v);
        let nu = basis_functions_in::<N>(self.u_knots.as_slice(), su, u, p);
        let nv = basis_functions_in::<N>(self.v_knots.as_slice(), sv, v, q);
        let stride = self.v_count();
        let mut s = DVec4::ZERO;
        for (k, &bu) in nu.iter().enumerate().take(p + 1) {
            let row = (su - p + k) * stride + sv - q;
            let mut temp = DVec4::ZERO;
            for (l, &bv) in nv.iter().enumerate().take(q + 1) {
                temp += self.points[row + l] * bv;
            }
            s += temp * bu;
        }
        s
    }

    /// Point S(u, v) (A4.3); parameters are clamped to the domain.
    #[inline]
    pub fn point(&self, u: f64, v: f64) -> DVec3 {
        euclidean(self.homogeneous_point(u, v))
    }

    /// Homogeneous partial derivatives `[A, A_u, A_v, A_uu, A_uv, A_vv]`.
    pub fn homogeneous_derivatives(&self, u: f64, v: f64) -> [DVec4; 6] {
        // The meshing and intersection hot path: vessel surfaces are quadratic
        // (or at most cubic), so their scratch arrays stay small.
        if self.u_degree() < SMALL_ORDER && self.v_degree() < SMALL_ORDER {
            self.homogeneous_derivatives_in::<SMALL_ORDER>(u, v)
        } else {
            self.homogeneous_derivatives_in::<MAX_ORDER>(u, v)
        }
    }

    /// [`homogeneous_derivatives`](Self::homogeneous_derivatives) with scratch
    /// arrays of `N` (more than either degree).
    #[inline]
    fn homogeneous_derivatives_in<const N: usize>(&self, u: f64, v: f64) -> [DVec4; 6] {
        let (p, q) = (self.u_degree(), self.v_degree());
        let u = self.u_knots.clamp(u);
        let v = self.v_knots.clamp(v);
        let su = self.u_knots.find_span(u);
        let sv = self.v_knots.find_span(v);
        let du = basis_derivatives_in::<3, N>(self.u_knots.as_slice(), su, u, p);
        let dv = basis_derivatives_in::<3, N>(self.v_knots.as_slice(), sv, v, q);
        let stride = self.v_count();
        // temp[d][k]: row k contracted with the d-th v-derivative basis.
        let mut temp = [[DVec4::ZERO; N]; 3];
        for (k, row_point) in (0..=p).map(|k| (k, (su - p + k) * stride + sv - q)) {
            let row = &self.points[row_point..=row_point + q];
            for (l, &pt) in row.iter().enumerate() {
                temp[0][k] += pt * dv[0][l];
                temp[1][k] += pt * dv[1][l];
                temp[2][k] += pt * dv[2][l];
            }
        }
        let mut out = [DVec4::ZERO; 6];
        for k in 0..=p {
            out[0] += temp[0][k] * du[0][k];
            out[1] += temp[0][k] * du[1][k];
            out[2] += temp[1][k] * du[0][k];
            out[3] += temp[0][k] * du[2][k];
            out[4] += temp[1][k] * du[1][k];
            out[5] += temp[2][k] * du[0][k];
        }
        out
    }

    /// Point and first partial derivatives of the rational surface (A4.4 to first
    /// order): equal to the first three of [`derivatives`](Self::derivatives).
    pub fn first_derivatives(&self, u: f64, v: f64) -> FirstDerivatives {
        let a = if self.u_degree() < SMALL_ORDER && self.v_degree() < SMALL_ORDER {
            self.homogeneous_first_in::<SMALL_ORDER>(u, v)
        } else {
            self.homogeneous_first_in::<MAX_ORDER>(u, v)
        };
        let inv = 1.0 / a[0].w;
        let point = a[0].truncate() * inv;
        FirstDerivatives {
            point,
            du: (a[1].truncate() - a[1].w * point) * inv,
            dv: (a[2].truncate() - a[2].w * point) * inv,
        }
    }

    /// Homogeneous `[A, A_u, A_v]` with scratch arrays of `N`.
    #[inline]
    fn homogeneous_first_in<const N: usize>(&self, u: f64, v: f64) -> [DVec4; 3] {
        let (p, q) = (self.u_degree(), self.v_degree());
        let u = self.u_knots.clamp(u);
        let v = self.v_knots.clamp(v);
        let su = self.u_knots.find_span(u);
        let sv = self.v_knots.find_span(v);
        let du = basis_derivatives_in::<2, N>(self.u_knots.as_slice(), su, u, p);
        let dv = basis_derivatives_in::<2, N>(self.v_knots.as_slice(), sv, v, q);
        let stride = self.v_count();
        let mut temp = [[DVec4::ZERO; N]; 2];
        for (k, row_point) in (0..=p).map(|k| (k, (su - p + k) * stride + sv - q)) {
            let row = &self.points[row_point..=row_point + q];
            for (l, &pt) in row.iter().enumerate() {
                temp[0][k] += pt * dv[0][l];
                temp[1][k] += pt * dv[1][l];
            }
        }
        let mut out = [DVec4::ZERO; 3];
        for k in 0..=p {
            out[0] += temp[0][k] * du[0][k];
            out[1] += temp[0][k] * du[1][k];
            out[2] += temp[1][k] * du[0][k];
        }
        out
    }

    /// Point and partial derivatives up to second order of the rational surface (A4.4).
    pub fn derivatives(&self, u: f64, v: f64) -> SurfaceDerivatives {
        rational_surface_derivatives(self.homogeneous_derivatives(u, v))
    }

    /// Unit normal `S_u × S_v / |S_u × S_v|` at (u, v).
    ///
    /// At a degenerate edge (a pole of a head, the apex of a cone, where `S_u` or `S_v`
    /// vanishes) the limit of the normal is returned: `S_uv × S_v` (or `S_u × S_uv`),
    /// signed for the side of the domain the edge is on.
    pub fn normal(&self, u: f64, v: f64) -> DVec3 {
        let d = self.derivatives(u, v);
        let ((u0, u1), (v0, v1)) = self.domain();
        let u = self.u_knots.clamp(u);
        let v = self.v_knots.clamp(v);
        normal_from_derivatives(&d, u - u0 < u1 - u, v - v0 < v1 - v)
    }

    /// Isocurve at fixed u (a curve along v).
    pub fn isocurve_u(&self, u: f64) -> NurbsCurve {
        let p = self.u_degree();
        let u = self.u_knots.clamp(u);
        let su = self.u_knots.find_span(u);
        let nu = basis_functions(self.u_knots.as_slice(), su, u, p);
        let stride = self.v_count();
        let points = (0..stride)
            .map(|j| {
                (0..=p)
                    .map(|k| self.points[(su - p + k) * stride + j] * nu[k])
                    .sum()
            })
            .collect();
        NurbsCurve::from_raw(self.v_knots.clone(), points)
    }

    /// Isocurve at fixed v (a curve along u).
    pub fn isocurve_v(&self, v: f64) -> NurbsCurve {
        self.transposed().isocurve_u(v)
    }

    /// The same surface with u and v exchanged (the normal flips).
    pub fn transposed(&self) -> Self {
        let (nu, nv) = (self.u_count(), self.v_count());
        let mut points = Vec::with_capacity(nu * nv);
        for j in 0..nv {
            for i in 0..nu {
                points.push(self.points[i * nv + j]);
            }
        }
        Self::from_raw(self.v_knots.clone(), self.u_knots.clone(), points)
    }

    /// The boundary curve at `u = u0` (`Side::UMin`) and so on.
    pub fn boundary(&self, side: Side) -> NurbsCurve {
        let ((u0, u1), (v0, v1)) = self.domain();
        match side {
            Side::UMin => self.isocurve_u(u0),
            Side::UMax => self.isocurve_u(u1),
            Side::VMin => self.isocurve_v(v0),
            Side::VMax => self.isocurve_v(v1),
        }
    }
}

/// One of the four boundary edges of a surface's parameter rectangle.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Side {
    /// u = u0.
    UMin,
    /// u = u1.
    UMax,
    /// v = v0.
    VMin,
    /// v = v1.
    VMax,
}

/// Rational derivatives from homogeneous ones (A4.4, up to second order).
#[inline]
pub(crate) fn rational_surface_derivatives(a: [DVec4; 6]) -> SurfaceDerivatives {
    let w = a[0].w;
    let inv = 1.0 / w;
    let point = a[0].truncate() * inv;
    let du = (a[1].truncate() - a[1].w * point) * inv;
    let dv = (a[2].truncate() - a[2].w * point) * inv;
    let duu = (a[3].truncate() - 2.0 * a[1].w * du - a[3].w * point) * inv;
    let duv = (a[4].truncate() - a[4].w * point - a[1].w * dv - a[2].w * du) * inv;
    let dvv = (a[5].truncate() - 2.0 * a[2].w * dv - a[5].w * point) * inv;
    SurfaceDerivatives {
        point,
        du,
        dv,
        duu,
        duv,
        dvv,
    }
}

/// Relative size below which a first derivative counts as vanished (a degenerate edge).
const DEGENERATE: f64 = 1e-12;

/// Unit normal from the first derivatives, `None` where they are (nearly)
/// parallel: a degenerate edge, whose normal needs the second derivatives.
#[inline]
pub(crate) fn regular_normal(du: DVec3, dv: DVec3) -> Option<DVec3> {
    let n = du.cross(dv);
    let scale = du.length_squared().max(dv.length_squared());
    (n.length_squared() > DEGENERATE * DEGENERATE * scale * scale).then(|| n.normalize())
}

/// Unit normal from derivatives, with the limit at degenerate edges. `u_low`/`v_low`
/// say whether the parameter is nearer the low end of its domain.
#[inline]
pub(crate) fn normal_from_derivatives(d: &SurfaceDerivatives, u_low: bool, v_low: bool) -> DVec3 {
    if let Some(n) = regular_normal(d.du, d.dv) {
        return n;
    }
    let (lu, lv) = (d.du.length_squared(), d.dv.length_squared());
    // Near the edge S_u ≈ (v − v_e) S_uv: the sign depends on which end v_e is.
    let limit = if lu <= lv {
        let n = d.duv.cross(d.dv);
        if v_low { n } else { -n }
    } else {
        let n = d.du.cross(d.duv);
        if u_low { n } else { -n }
    };
    limit.normalize_or_zero()
}
