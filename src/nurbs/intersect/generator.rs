//! One straight generator of a neck-like surface against the host: where the line
//! N(u, ·) meets H(a, b).
//!
//! For a fixed neck angle u the unknowns are the neck parameter s along the
//! generator and the host parameters (a, b); the equation N(u, s) = H(a, b) is a
//! square 3×3 system solved by Newton's method with the Jacobian
//! `[N_s, −H_a, −H_b]`, damped by halving the step until the residual falls. Where
//! the Jacobian is singular (an iterate on the pole of a head, where H_a = 0) a
//! Levenberg–Marquardt step is taken instead. Without a nearby solution to start
//! from, a coarse search seeds Newton: from points spread along the generator,
//! alternate closest-point projections onto the host and back onto the generator
//! line; their fixed points are where the line meets the host, or its closest
//! approach when it misses.

use glam::{DMat3, DVec2, DVec3};

use super::pair::{NeckPoint, Pair};
use crate::nurbs::{FirstDerivatives, NurbsError, NurbsSurface};

/// Newton iterations per solve.
const MAX_ITERATIONS: usize = 50;

/// Step halvings tried before a Newton step counts as not reducing the residual.
const MAX_HALVINGS: usize = 30;

/// A converged residual below this fraction of the tolerance (1e-14 of the size of
/// the surfaces, some tens of units in the last place of their coordinates) is at
/// the level of rounding: the extra polishing step is skipped.
const ROUNDING: f64 = 1e-2;

/// |det J| below this fraction of the product of its column lengths counts as
/// singular: the generator is (nearly) tangent to the host or H_a or H_b vanishes.
const SINGULAR: f64 = 1e-12;

/// Levenberg–Marquardt damping, relative to the largest diagonal entry of JᵀJ.
const DAMPING: f64 = 1e-6;

/// Starting points of the coarse search, spread evenly along the generator.
const SEARCH_STARTS: usize = 5;

/// Alternating projections per starting point of the coarse search.
const ALTERNATIONS: usize = 24;

/// Newton iterations tried straight from a first projection of the coarse search
/// (the damped iteration converges in a handful from a seed near the curve).
const QUICK_ITERATIONS: usize = 12;

/// How far the coarse search may follow the generator line beyond the neck's ends,
/// in multiples of the neck's length.
const SEARCH_REACH: f64 = 1.0;

/// A solution this far outside the neck's v-domain, relative to its width, still
/// counts as on the neck (and is clamped onto it).
const NECK_SLACK: f64 = 1e-10;

/// A generator whose closest approach to the host exceeds this fraction of the size
/// of the two surfaces misses the host.
const MISS: f64 = 1e-6;

/// Where one generator of a neck-like surface meets the host.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct GeneratorHit {
    /// Neck parameter v of the meeting point (along the generator).
    pub neck_v: f64,
    /// Host parameters (u, v) of the meeting point, within the host's domain.
    pub host_uv: DVec2,
    /// The meeting point.
    pub point: DVec3,
}

/// Where the straight generator at neck parameter `u` of `neck` meets `host`, both
/// surfaces in one frame, found by a coarse search and Newton's method.
///
/// Works for any surface whose v-isolines are straight lines: a nozzle neck, or the
/// coaxial cylinder of a reinforcing pad's outside diameter.
///
/// # Errors
///
/// [`NurbsError::InvalidGeometry`] for a non-finite `u` or a generator of zero
/// length; [`NurbsError::GeneratorMissesHost`] where the generator passes beside
/// the host patch; [`NurbsError::IntersectionOutsideNeck`] where it meets the host
/// only beyond the neck's ends; [`NurbsError::IntersectionNotConverged`] where
/// Newton's method fails.
pub fn intersect_generator(
    neck: &NurbsSurface,
    host: &NurbsSurface,
    u: f64,
) -> Result<GeneratorHit, NurbsError> {
    if !u.is_finite() {
        return Err(NurbsError::InvalidGeometry {
            what: "neck parameter u",
            value: u,
            rule: "must be finite",
        });
    }
    let pair = Pair::new(neck, host);
    let found = pair.search(pair.neck_u.wrap(u))?;
    let [a, b] = pair.host_axes;
    Ok(GeneratorHit {
        neck_v: found.s,
        host_uv: DVec2::new(a.wrap(found.host.x), b.wrap(found.host.y)),
        point: found.point,
    })
}

/// A point of the intersection curve at neck angle `u`, with the curve's tangent.
#[derive(Clone, Copy, Debug)]
pub(super) struct Solution {
    /// Neck parameter u.
    pub u: f64,
    /// Neck parameter v (along the generator).
    pub s: f64,
    /// Host parameters, unwrapped across closed directions.
    pub host: DVec2,
    /// The point.
    pub point: DVec3,
    /// dC/du, the curve's derivative with respect to the neck angle.
    pub tangent: DVec3,
    /// (ds/du, da/du, db/du).
    pub rates: DVec3,
}

/// A Newton iterate: unknowns (s, a, b), the two surfaces there and the residual.
struct Iterate {
    x: DVec3,
    neck: NeckPoint,
    host: FirstDerivatives,
    residual: DVec3,
}

/// The Jacobian `[N_s, −H_a, −H_b]` of N(u, s) − H(a, b) with respect to (s, a, b).
fn jacobian(neck: &NeckPoint, host: &FirstDerivatives) -> DMat3 {
    DMat3::from_cols(neck.dv, -host.du, -host.dv)
}

/// `J⁻¹ rhs`, or `None` where J is singular.
fn solve(j: DMat3, rhs: DVec3) -> Option<DVec3> {
    let det = j.determinant();
    let scale = j.x_axis.length() * j.y_axis.length() * j.z_axis.length();
    (det.abs() > SINGULAR * scale && det.is_finite()).then(|| j.inverse() * rhs)
}

/// The Newton step for residual `f`, or the Levenberg–Marquardt step where J is
/// singular.
pub(super) fn newton_step(j: DMat3, f: DVec3) -> DVec3 {
    solve(j, -f).unwrap_or_else(|| {
        let jt = j.transpose();
        let normal = jt * j;
        let largest = normal.x_axis.x.max(normal.y_axis.y).max(normal.z_axis.z);
        let damped = normal + DMat3::from_diagonal(DVec3::splat(DAMPING * largest));
        let det = damped.determinant();
        if det.is_finite() && det > 0.0 {
            damped.inverse() * (jt * -f)
        } else {
            DVec3::ZERO
        }
    })
}

impl Pair<'_> {
    /// The iterate at unknowns `x`, open host directions clamped.
    fn iterate(&self, u: f64, x: DVec3) -> Iterate {
        let host_x = self.hold_host(DVec2::new(x.y, x.z));
        let x = DVec3::new(x.x, host_x.x, host_x.y);
        let neck = self.neck_at(u, x.x);
        let host = self.host_at(host_x);
        Iterate {
            x,
            neck,
            host,
            residual: neck.point - host.point,
        }
    }

    /// Newton's method from `seed` = (s, a, b); the residual where it stalls.
    pub(super) fn newton(&self, u: f64, seed: DVec3) -> Result<Solution, f64> {
        self.newton_within(u, seed, MAX_ITERATIONS)
    }

    /// [`Pair::newton`] giving up after `iterations` steps.
    fn newton_within(&self, u: f64, seed: DVec3, iterations: usize) -> Result<Solution, f64> {
        let mut here = self.iterate(u, seed);
        let mut polished = false;
        for _ in 0..iterations {
            let r = here.residual.length();
            if r <= self.eps {
                // Polished, or already down to rounding: nothing left to gain.
                if polished || r <= ROUNDING * self.eps {
                    break;
                }
                polished = true;
            }
            let step = newton_step(jacobian(&here.neck, &here.host), here.residual);
            let mut t = 1.0;
            let mut next = None;
            // Once converged, one full step polishes the last digits; where rounding
            // keeps it from lowering the residual there is nothing left to gain, so
            // shorter steps are not tried.
            let halvings = if polished { 1 } else { MAX_HALVINGS };
            for _ in 0..halvings {
                let trial = self.iterate(u, here.x + step * t);
                if trial.residual.length() < r {
                    next = Some(trial);
                    break;
                }
                t *= 0.5;
            }
            match next {
                Some(next) => here = next,
                None => break,
            }
        }
        let r = here.residual.length();
        if r <= self.eps {
            Ok(self.solution(u, &here))
        } else {
            Err(r)
        }
    }

    /// The solution at a converged iterate, with the curve's tangent.
    fn solution(&self, u: f64, at: &Iterate) -> Solution {
        // N_s s' − H_a a' − H_b b' = −N_u along the curve.
        let rates = solve(jacobian(&at.neck, &at.host), -at.neck.du).unwrap_or(DVec3::ZERO);
        Solution {
            u,
            s: at.x.x,
            host: DVec2::new(at.x.y, at.x.z),
            point: 0.5 * (at.neck.point + at.host.point),
            tangent: at.neck.du + at.neck.dv * rates.x,
            rates,
        }
    }

    /// `found` with s clamped onto the neck, or the error where it lies beyond it.
    pub(super) fn within_neck(&self, found: Solution) -> Result<Solution, NurbsError> {
        let v = self.neck_v;
        let slack = NECK_SLACK * v.width();
        if found.s < v.start - slack || found.s > v.end + slack || !found.s.is_finite() {
            return Err(NurbsError::IntersectionOutsideNeck {
                u: found.u,
                v: found.s,
                start: v.start,
                end: v.end,
            });
        }
        Ok(Solution {
            s: found.s.clamp(v.start, v.end),
            ..found
        })
    }

    /// The solution at `u` continued from the nearby solution `from`: Newton from the
    /// tangent predictor. `None` where it fails or leaves the neck.
    pub(super) fn continue_from(&self, from: &Solution, u: f64) -> Option<Solution> {
        let seed = DVec3::new(from.s, from.host.x, from.host.y) + from.rates * (u - from.u);
        self.converge_near(from, u, seed)
    }

    /// The solution at `u` by Newton from `seed` = (s, a, b), kept in the host
    /// period nearest the nearby solution `from`. `None` where it fails or leaves
    /// the neck.
    pub(super) fn converge_near(&self, from: &Solution, u: f64, seed: DVec3) -> Option<Solution> {
        let found = self.newton(u, seed).ok()?;
        // Near a pole the host's u may turn fast: keep the nearest period, so that a
        // step never wraps around.
        let host = self.unwrap_host_near(found.host, from.host);
        self.within_neck(Solution { host, ..found }).ok()
    }

    /// The solution at `u` from a coarse search (see the module documentation).
    pub(super) fn search(&self, u: f64) -> Result<Solution, NurbsError> {
        let (v0, v1) = (self.neck_v.start, self.neck_v.end);
        let p0 = self.neck_at(u, v0).point;
        let d = self.neck_at(u, v1).point - p0;
        let length2 = d.length_squared();
        if !(length2 > 0.0 && length2.is_finite()) {
            return Err(NurbsError::InvalidGeometry {
                what: "neck generator length",
                value: length2.sqrt(),
                rule: "must be finite and > 0",
            });
        }
        let mut seeds: Vec<(f64, DVec3)> = Vec::with_capacity(SEARCH_STARTS);
        for k in 0..SEARCH_STARTS {
            let mut t = k as f64 / (SEARCH_STARTS - 1) as f64;
            let mut best = None;
            for alternation in 0..ALTERNATIONS {
                let projection = self.host.closest_point(p0 + d * t)?;
                let next = ((projection.point - p0).dot(d) / length2)
                    .clamp(-SEARCH_REACH, 1.0 + SEARCH_REACH);
                let distance = (p0 + d * next - projection.point).length();
                best = Some((
                    distance,
                    DVec3::new(v0 + next * (v1 - v0), projection.u, projection.v),
                ));
                // Fast path: Newton straight from the first projection usually
                // converges; the alternations below are for where it does not.
                if alternation == 0
                    && let Some(&(_, seed)) = best.as_ref()
                    && let Ok(found) = self.newton_within(u, seed, QUICK_ITERATIONS)
                    && let Ok(found) = self.within_neck(found)
                {
                    return Ok(found);
                }
                let moved = (next - t).abs() * length2.sqrt();
                t = next;
                if distance <= self.eps || moved <= self.eps {
                    break;
                }
            }
            seeds.extend(best);
        }
        seeds.sort_by(|a, b| a.0.total_cmp(&b.0));
        let closest = seeds.first().map_or(f64::INFINITY, |s| s.0);
        let mut outside = None;
        let mut residual = f64::INFINITY;
        for &(_, seed) in &seeds {
            match self.newton(u, seed) {
                Ok(found) => match self.within_neck(found) {
                    Ok(found) => return Ok(found),
                    Err(e) => outside = outside.or(Some(e)),
                },
                Err(r) => residual = residual.min(r),
            }
        }
        if let Some(e) = outside {
            Err(e)
        } else if closest > MISS * self.size {
            Err(NurbsError::GeneratorMissesHost {
                u,
                distance: closest,
            })
        } else {
            Err(NurbsError::IntersectionNotConverged { u, residual })
        }
    }
}
