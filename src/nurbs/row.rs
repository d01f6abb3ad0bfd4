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

use super::basis::{
    MAX_ORDER, SMALL_ORDER, basis_derivatives, basis_derivatives_in, basis_functions_in,
};
use super::curve::euclidean;
use super::surface::{
    NurbsSurface, SurfaceDerivatives, normal_from_derivatives, rational_surface_derivatives,
    regular_normal,
};

/// One row of constant v of a surface; see the module documentation.
#[derive(Clone, Debug)]
pub struct SurfaceRow<'a> {
    surface: &'a NurbsSurface,
    /// The row's v (clamped to the domain).
    v: f64,
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
            v,
            rows,
            hint: Cell::new(self.u_degree()),
        }
    }
}

impl SurfaceRow<'_> {
    /// S(u, v) on this row (u clamped to the domain).
    pub fn point(&self, u: f64) -> DVec3 {
        if self.surface.u_degree() < SMALL_ORDER {
            self.point_in::<SMALL_ORDER>(u)
        } else {
            self.point_in::<MAX_ORDER>(u)
        }
    }

    /// The point and first derivatives `(S, S_u, S_v)` at (u, v) on this row (u
    /// clamped): what a mesh vertex needs, at about half the cost of
    /// [`derivatives`](Self::derivatives).
    pub fn first_derivatives(&self, u: f64) -> (DVec3, DVec3, DVec3) {
        if self.surface.u_degree() < SMALL_ORDER {
            self.first_derivatives_in::<SMALL_ORDER>(u)
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
        let span = su - p..=su;
        let terms = self.rows[0][span.clone()].iter().zip(&self.rows[1][span]);
        for (k, (&x, &xv)) in terms.enumerate() {
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

    /// The unit normal at (u, v) on this row (u clamped), equal to
    /// [`NurbsSurface::normal`] bit for bit, poles included.
    pub fn normal(&self, u: f64) -> DVec3 {
        // First derivatives suffice but where they are parallel (a pole).
        let (_, du, dv) = self.first_derivatives(u);
        if let Some(n) = regular_normal(du, dv) {
            return n;
        }
        let d = self.derivatives(u);
        let ((u0, u1), (v0, v1)) = self.surface.domain();
        let u = self.surface.u_knots().clamp(u);
        normal_from_derivatives(&d, u - u0 < u1 - u, self.v - v0 < v1 - self.v)
    }

    /// The derivatives up to second order at (u, v) on this row (u clamped).
    pub fn derivatives(&self, u: f64) -> SurfaceDerivatives {
        if self.surface.u_degree() < SMALL_ORDER {
            self.derivatives_in::<SMALL_ORDER>(u)
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
            let [a, av, avv] = self.rows.each_ref().map(|row| row[su - p + k]);
            let [n, nu, nuu] = du.map(|d| d[k]);
            out[0] += a * n;
            out[1] += a * nu;
            out[2] += av * n;
            out[3] += a * nuu;
            out[4] += av * nu;
            out[5] += avv * n;
        }
        rational_surface_derivatives(out)
    }
}

#[cfg(test)]
mod tests {
    use crate::parts::heads::{Head, HeadKind};

    #[test]
    fn a_row_evaluates_as_the_surface_does() {
        let od = 2400.0;
        let patches = Head::new(od, HeadKind::asme_fd(od))
            .patches()
            .expect("the head is valid");
        for patch in &patches {
            let surface = &patch.surface;
            let ((u0, u1), (v0, v1)) = surface.domain();
            for j in 0..=7 {
                let v = v0 + (v1 - v0) * j as f64 / 7.0;
                let row = surface.row(v);
                // Increasing u, then back to the start: the span hint must not stick.
                for i in (0..=40).chain([3, 0, 40, 17]) {
                    let u = u0 + (u1 - u0) * i as f64 / 40.0;
                    let d = surface.derivatives(u, v);
                    assert_eq!(row.derivatives(u), d, "{} at ({u}, {v})", patch.name);
                    assert_eq!(row.first_derivatives(u), (d.point, d.du, d.dv));
                    assert_eq!(row.normal(u), surface.normal(u, v));
                    let p = row.point(u);
                    assert!((p - surface.point(u, v)).length() <= 1e-9 * od);
                }
            }
        }
    }
}
