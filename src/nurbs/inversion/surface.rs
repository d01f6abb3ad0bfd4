//! Closest point of a surface: 2-D bounded Newton from the sampled local minima,
//! with seeds moved off degenerate edges and closed directions wrapped.

use glam::{DVec2, DVec3};

use super::search::{
    Axis, COINCIDENT_CONTROL_POINTS, MAX_ITERATIONS, MAX_SEEDS, POINT_COINCIDENCE, Trial,
    ZERO_COSINE, all_coincide, backtrack, check_query, net_size, sample_parameters,
};
use crate::nurbs::{NurbsError, NurbsSurface, SurfaceDerivatives};

/// The closest point of a surface to a query point.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SurfaceProjection {
    /// u parameter of the closest point.
    pub u: f64,
    /// v parameter of the closest point.
    pub v: f64,
    /// The closest point S(u, v).
    pub point: DVec3,
    /// Its distance from the query point.
    pub distance: f64,
}

/// A 2×2 matrix [[a, b], [b, c]] counts as positive definite when a, c > 0 and its
/// determinant exceeds this fraction of a·c (|cos| of the angle between S_u and S_v
/// below 1 − 10⁻¹² for the Gauss–Newton matrix).
const POSITIVE_DEFINITE_MARGIN: f64 = 1e-12;

/// The Newton step for the free variables (P&T eq. 6.6), falling back to the
/// Gauss–Newton matrix JᵀJ and then to its diagonal where the Hessian is not positive
/// definite. Held variables get a zero step.
fn surface_step(d: &SurfaceDerivatives, r: DVec3, g: DVec2, free: [bool; 2]) -> DVec2 {
    let gauss = [d.du.length_squared(), d.du.dot(d.dv), d.dv.length_squared()];
    let hessian = [
        gauss[0] + r.dot(d.duu),
        gauss[1] + r.dot(d.duv),
        gauss[2] + r.dot(d.dvv),
    ];
    let one = |i: usize, gi: f64| {
        let (h, j) = (hessian[2 * i], gauss[2 * i]);
        if h > 0.0 {
            -gi / h
        } else if j > 0.0 {
            -gi / j
        } else {
            0.0
        }
    };
    match free {
        [true, true] => {
            for [a, b, c] in [hessian, gauss] {
                let det = a * c - b * b;
                if a > 0.0 && c > 0.0 && det > POSITIVE_DEFINITE_MARGIN * a * c {
                    return DVec2::new(c * g.x - b * g.y, a * g.y - b * g.x) / -det;
                }
            }
            let diag = |gi: f64, j: f64| if j > 0.0 { -gi / j } else { 0.0 };
            DVec2::new(diag(g.x, gauss[0]), diag(g.y, gauss[2]))
        }
        [true, false] => DVec2::new(one(0, g.x), 0.0),
        [false, true] => DVec2::new(0.0, one(1, g.y)),
        [false, false] => DVec2::ZERO,
    }
}

impl NurbsSurface {
    /// The point of the surface closest to `p`, with its parameters.
    ///
    /// Errors only for a non-finite `p`. Where the parameters of a point are not
    /// unique (a pole, a seam) any of them may be returned; where several points are
    /// equally close (the centre of a sphere) one of them is.
    pub fn closest_point(&self, p: DVec3) -> Result<SurfaceProjection, NurbsError> {
        let p = check_query(p)?;
        let points = self.control_points();
        let size = net_size(&points);
        let eps = POINT_COINCIDENCE * size;
        let tol = COINCIDENT_CONTROL_POINTS * size;
        let (nu, nv) = (self.u_count(), self.v_count());
        let at = |i: usize, j: usize| points[i * nv + j];
        let weight = |i: usize, j: usize| self.homogeneous_point_at(i, j).w;
        let same = |a: (usize, usize), b: (usize, usize)| {
            (at(a.0, a.1) - at(b.0, b.1)).length() <= tol
                && (weight(a.0, a.1) - weight(b.0, b.1)).abs()
                    <= COINCIDENT_CONTROL_POINTS * weight(a.0, a.1)
        };
        let u_closed = (0..nv).all(|j| same((0, j), (nu - 1, j)));
        let v_closed = (0..nu).all(|i| same((i, 0), (i, nv - 1)));
        let axes = [
            Axis::new(self.u_knots(), u_closed),
            Axis::new(self.v_knots(), v_closed),
        ];
        // Degenerate edges: u = u0, u = u1, v = v0, v = v1.
        let degenerate = [
            all_coincide((0..nv).map(|j| at(0, j)), tol),
            all_coincide((0..nv).map(|j| at(nu - 1, j)), tol),
            all_coincide((0..nu).map(|i| at(i, 0)), tol),
            all_coincide((0..nu).map(|i| at(i, nv - 1)), tol),
        ];

        let (us, vs) = (
            sample_parameters(self.u_knots()),
            sample_parameters(self.v_knots()),
        );
        let (m, n) = (us.len(), vs.len());
        let dist: Vec<f64> = us
            .iter()
            .flat_map(|&u| vs.iter().map(move |&v| (u, v)))
            .map(|(u, v)| (self.point(u, v) - p).length())
            .collect();
        let distance = |i: usize, j: usize| dist[i * n + j];
        let mut minima: Vec<(usize, usize)> = (0..m)
            .flat_map(|i| (0..n).map(move |j| (i, j)))
            .filter(|&(i, j)| {
                let x = distance(i, j);
                (i == 0 || x <= distance(i - 1, j))
                    && (i + 1 == m || x <= distance(i + 1, j))
                    && (j == 0 || x <= distance(i, j - 1))
                    && (j + 1 == n || x <= distance(i, j + 1))
            })
            .collect();
        minima.sort_by(|a, b| distance(a.0, a.1).total_cmp(&distance(b.0, b.1)));
        let (i0, j0) = minima.first().copied().unwrap_or((0, 0));
        let mut best = SurfaceProjection {
            u: us[i0],
            v: vs[j0],
            point: self.point(us[i0], vs[j0]),
            distance: distance(i0, j0),
        };
        if best.distance <= eps {
            return Ok(best);
        }
        let best_in_row =
            |j: usize| (0..m).min_by(|&a, &b| distance(a, j).total_cmp(&distance(b, j)));
        let best_in_column =
            |i: usize| (0..n).min_by(|&a, &b| distance(i, a).total_cmp(&distance(i, b)));
        let mut seeds: Vec<(usize, usize)> = Vec::new();
        for &(i, j) in &minima {
            if seeds.len() == MAX_SEEDS {
                break;
            }
            // Off a degenerate edge: the best sample of the next ring inwards.
            let (mut i, mut j) = (i, j);
            if m > 1 && ((i == 0 && degenerate[0]) || (i == m - 1 && degenerate[1])) {
                i = if i == 0 { 1 } else { m - 2 };
                j = best_in_column(i).unwrap_or(j);
            }
            if n > 1 && ((j == 0 && degenerate[2]) || (j == n - 1 && degenerate[3])) {
                j = if j == 0 { 1 } else { n - 2 };
                i = best_in_row(j).unwrap_or(i);
            }
            if seeds
                .iter()
                .all(|s| s.0.abs_diff(i) > 1 || s.1.abs_diff(j) > 1)
            {
                seeds.push((i, j));
            }
        }
        for (i, j) in seeds {
            let found = self.descend(p, DVec2::new(us[i], vs[j]), axes, eps);
            if found.distance < best.distance {
                best = found;
            }
        }
        Ok(best)
    }

    /// Damped, bounded Newton iteration from `x = (u, v)`.
    fn descend(&self, p: DVec3, x: DVec2, axes: [Axis; 2], eps: f64) -> SurfaceProjection {
        let evaluate = |x: DVec2| {
            let d = self.derivatives(x.x, x.y);
            let r = d.point - p;
            let g = DVec2::new(r.dot(d.du), r.dot(d.dv));
            let free = [axes[0].is_free(x.x, g.x), axes[1].is_free(x.y, g.y)];
            let residual = [(g.x, d.du, free[0]), (g.y, d.dv, free[1])]
                .into_iter()
                .filter(|&(_, tangent, free)| free && tangent != DVec3::ZERO)
                .map(|(gk, tangent, _)| gk.abs() / tangent.length())
                .fold(0.0, f64::max);
            Trial {
                value: r.length_squared(),
                residual,
                state: (x, d, g, free),
            }
        };
        let mut here = evaluate(x);
        for _ in 0..MAX_ITERATIONS {
            let (x, d, g, free) = here.state;
            let dist = here.value.sqrt();
            if dist <= eps || here.residual <= ZERO_COSINE * dist {
                break;
            }
            let step = surface_step(&d, d.point - p, g, free);
            let step = DVec2::new(axes[0].limit(step.x), axes[1].limit(step.y));
            if step == DVec2::ZERO {
                break;
            }
            let Some((next, full)) = backtrack(here.value, here.residual, |t| {
                evaluate(DVec2::new(
                    axes[0].place(x.x + t * step.x),
                    axes[1].place(x.y + t * step.y),
                ))
            }) else {
                break;
            };
            let moved = (next.state.1.point - d.point).length();
            here = next;
            if full && moved <= eps {
                break;
            }
        }
        let (x, d, _, _) = here.state;
        SurfaceProjection {
            u: x.x,
            v: x.y,
            point: d.point,
            distance: here.value.sqrt(),
        }
    }
}
