//! Closest point of a curve: 1-D bounded Newton from the sampled local minima.

use glam::DVec3;

use super::search::{
    Axis, COINCIDENT_CONTROL_POINTS, MAX_ITERATIONS, MAX_SEEDS, POINT_COINCIDENCE, Trial,
    ZERO_COSINE, backtrack, check_query, net_size, sample_parameters,
};
use crate::nurbs::{NurbsCurve, NurbsError};

/// The closest point of a curve to a query point.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CurveProjection {
    /// Parameter of the closest point.
    pub u: f64,
    /// The closest point C(u).
    pub point: DVec3,
    /// Its distance from the query point.
    pub distance: f64,
}

impl NurbsCurve {
    /// The point of the curve closest to `p`, with its parameter.
    ///
    /// Errors only for a non-finite `p`. Where several points are equally close (the
    /// centre of a circle) one of them is returned.
    pub fn closest_point(&self, p: DVec3) -> Result<CurveProjection, NurbsError> {
        let p = check_query(p)?;
        let size = net_size(&self.control_points());
        let eps = POINT_COINCIDENCE * size;
        let closed = (self.start() - self.end()).length() <= COINCIDENT_CONTROL_POINTS * size;
        let axis = Axis::new(self.knots(), closed);
        let us = sample_parameters(self.knots());
        let dist: Vec<f64> = us.iter().map(|&u| (self.point(u) - p).length()).collect();
        let mut minima: Vec<usize> = (0..us.len())
            .filter(|&i| {
                (i == 0 || dist[i] <= dist[i - 1]) && (i + 1 == us.len() || dist[i] <= dist[i + 1])
            })
            .collect();
        minima.sort_by(|&a, &b| dist[a].total_cmp(&dist[b]));
        let first = minima.first().copied().unwrap_or(0);
        let mut best = CurveProjection {
            u: us[first],
            point: self.point(us[first]),
            distance: dist[first],
        };
        if best.distance <= eps {
            return Ok(best);
        }
        for &i in minima.iter().take(MAX_SEEDS) {
            let found = self.descend(p, us[i], axis, eps);
            if found.distance < best.distance {
                best = found;
            }
        }
        Ok(best)
    }

    /// Damped, bounded Newton iteration from `u`.
    fn descend(&self, p: DVec3, u: f64, axis: Axis, eps: f64) -> CurveProjection {
        let evaluate = |u: f64| {
            let d = self.derivatives(u);
            let r = d.point - p;
            let (g, speed) = (r.dot(d.first), d.first.length());
            let free = axis.is_free(u, g) && speed > 0.0;
            let residual = if free { g.abs() / speed } else { 0.0 };
            Trial {
                value: r.length_squared(),
                residual,
                state: (u, d),
            }
        };
        let mut here = evaluate(u);
        for _ in 0..MAX_ITERATIONS {
            let (u, d) = here.state;
            let r = d.point - p;
            let dist = here.value.sqrt();
            if dist <= eps || here.residual <= ZERO_COSINE * dist {
                break;
            }
            let g = r.dot(d.first);
            let speed2 = d.first.length_squared();
            let h = speed2 + r.dot(d.second);
            let step = axis.limit(if h > 0.0 { -g / h } else { -g / speed2 });
            let Some((next, full)) = backtrack(here.value, here.residual, |t| {
                evaluate(axis.place(u + t * step))
            }) else {
                break;
            };
            let moved = (next.state.1.point - d.point).length();
            here = next;
            if full && moved <= eps {
                break;
            }
        }
        let (u, d) = here.state;
        CurveProjection {
            u,
            point: d.point,
            distance: here.value.sqrt(),
        }
    }
}
