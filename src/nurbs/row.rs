//! A surface restricted to one row of constant v, for evaluating many points
//! along it.
//!
//! Point-by-point evaluation contracts `(p + 1)(q + 1)` control points and
//! computes both directions' basis functions for every point. Along a row the v
//! half of that work is the same for every point, so [`SurfaceRow`] does it once:
//! the net is contracted with the v basis and its first two derivatives into three
//! rows of homogeneous points (those of the isocurve `S(·, v)` and of its v
//! derivatives); a point then costs a `(p + 1)`-term contraction per quantity. The
//! mesher's structured path evaluates its rows of vertices and its screen's probes
//! this way. Derivatives equal [`NurbsSurface::derivatives`] bit for bit (the sums
//! run in the same order); points equal [`NurbsSurface::point`] to rounding.

use std::cell::Cell;

use glam::{DVec3, DVec4};

use super::basis::{MAX_ORDER, basis_derivatives, basis_derivatives_in, basis_functions_in};
use super::curve::euclidean;
use super::surface::{LOW_ORDER, NurbsSurface, SurfaceDerivatives, rational_surface_derivatives};

/// One row of constant v of a surface; see the module documentation.
#[derive(Clone, Debug)]
pub struct SurfaceRow<'a> {
    surface: &'a NurbsSurface,
    /// Homogeneous points of `Aʷ(·, v)`, `Aʷ_v` and `Aʷ_vv`, one per u control
    /// index.
    rows: [Vec<DVec4>; 3],
    /// The knot span of the last point evaluated.
    hint: Cell<usize>,
}

impl NurbsSurface {
    /// The row of constant `v` (clamped to the domain).
    pub fn row(&self, v: f64) -> SurfaceRow<'_> {
        let q = self.v_degree();
        let v = self.v_knots().clamp(v);
        let sv = self.v_knots().find_span(v);
        let dv = basis_derivatives::<3>(self.v_knots().as_slice(), sv, v, q);
        let (nu, stride) = (self.u_count(), self.v_count());
        let points = self.homogeneous_points();
        let mut rows = [
            Vec::with_capacity(nu),
            Vec::with_capacity(nu),
            Vec::with_capacity(nu),
        ];
        for i in 0..nu {
            let row = &points[i * stride + sv - q..=i * stride + sv];
            let mut sums = [DVec4::ZERO; 3];
            for (l, &pt) in row.iter().enumerate() {
                sums[0] += pt * dv[0][l];
                sums[1] += pt * dv[1][l];
                sums[2] += pt * dv[2][l];
            }
            for (d, sum) in sums.into_iter().enumerate() {
                rows[d].push(sum);
            }
        }
        SurfaceRow {
            surface: self,
            rows,
            hint: Cell::new(self.u_degree()),
        }
    }
}

impl SurfaceRow<'_> {
    /// S(u, v) on this row (u clamped to the domain).
    pub fn point(&self, u: f64) -> DVec3 {
        if self.surface.u_degree() < LOW_ORDER {
            self.point_in::<LOW_ORDER>(u)
        } else {
            self.point_in::<MAX_ORDER>(u)
        }
    }

    /// The point and first derivatives `(S, S_u, S_v)` at (u, v) on this row (u
    /// clamped): what a mesh vertex needs, at about half the cost of
    /// [`derivatives`](Self::derivatives).
    pub fn first_derivatives(&self, u: f64) -> (DVec3, DVec3, DVec3) {
        if self.surface.u_degree() < LOW_ORDER {
            self.first_derivatives_in::<LOW_ORDER>(u)
        } else {
            self.first_derivatives_in::<MAX_ORDER>(u)
        }
    }

    fn first_derivatives_in<const N: usize>(&self, u: f64) -> (DVec3, DVec3, DVec3) {
        let p = self.surface.u_degree();
        let knots = self.surface.u_knots();
        let u = knots.clamp(u);
        let su = self.span(u);
        let du = basis_derivatives_in::<2, N>(knots.as_slice(), su, u, p);
        let (mut a, mut au, mut av) = (DVec4::ZERO, DVec4::ZERO, DVec4::ZERO);
        for k in 0..=p {
            let (x, xv) = (self.rows[0][su - p + k], self.rows[1][su - p + k]);
            a += x * du[0][k];
            au += x * du[1][k];
            av += xv * du[0][k];
        }
        let inv = 1.0 / a.w;
        let point = a.truncate() * inv;
        (
            point,
            (au.truncate() - au.w * point) * inv,
            (av.truncate() - av.w * point) * inv,
        )
    }

    /// The knot span of `u` (clamped), trying the last one found first: the points
    /// of a row come in increasing u.
    fn span(&self, u: f64) -> usize {
        let k = self.surface.u_knots().as_slice();
        let hint = self.hint.get();
        if hint + 1 < k.len() && k[hint] <= u && u < k[hint + 1] {
            return hint;
        }
        let span = self.surface.u_knots().find_span(u);
        self.hint.set(span);
        span
    }

    /// The derivatives up to second order at (u, v) on this row (u clamped).
    pub fn derivatives(&self, u: f64) -> SurfaceDerivatives {
        if self.surface.u_degree() < LOW_ORDER {
            self.derivatives_in::<LOW_ORDER>(u)
        } else {
            self.derivatives_in::<MAX_ORDER>(u)
        }
    }

    fn point_in<const N: usize>(&self, u: f64) -> DVec3 {
        let p = self.surface.u_degree();
        let knots = self.surface.u_knots();
        let u = knots.clamp(u);
        let su = self.span(u);
        let nu = basis_functions_in::<N>(knots.as_slice(), su, u, p);
        let mut s = DVec4::ZERO;
        for (k, &b) in nu.iter().enumerate().take(p + 1) {
            s += self.rows[0][su - p + k] * b;
        }
        euclidean(s)
    }

    fn derivatives_in<const N: usize>(&self, u: f64) -> SurfaceDerivatives {
        let p = self.surface.u_degree();
        let knots = self.surface.u_knots();
        let u = knots.clamp(u);
        let su = self.span(u);
        let du = basis_derivatives_in::<3, N>(knots.as_slice(), su, u, p);
        let mut out = [DVec4::ZERO; 6];
        for k in 0..=p {
            let [a, av, avv] = [0, 1, 2].map(|d| self.rows[d][su - p + k]);
            out[0] += a * du[0][k];
            out[1] += a * du[1][k];
            out[2] += av * du[0][k];
            out[3] += a * du[2][k];
            out[4] += av * du[1][k];
            out[5] += avv * du[0][k];
        }
        rational_surface_derivatives(out)
    }
}
