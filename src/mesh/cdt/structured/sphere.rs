//! The rows of a whole sphere patch without openings (a hemispherical head's
//! crown, a torispherical or F&D crown: one ring and a pole), sized by the
//! chordal bound of the whole triangle rather than by a metric at its vertices.
//!
//! Every vertex lies on the sphere, so a flat triangle's largest distance to it
//! is R − |q|, q the triangle's point nearest the centre: R − √(R² − ρ²) with ρ
//! its circumradius when the centre's projection falls inside it, the bound of
//! its longest edge otherwise. From the given ring towards the pole, each next
//! row is chosen greedily among the same count shifted by half a step (a strip
//! of near-isosceles triangles) and a few smaller counts, each raised as far
//! towards the pole as the zip of the two rows (by the shorter diagonal, as
//! `structured::zip` takes it) keeps every triangle within the tolerance; the
//! candidate covering the most area per triangle is kept, and the pole's fan
//! ends the rows once it fits and covers more. Counts are not rounded (to
//! quarter turns or a slack): the patch is meshed as a whole turn, not as a
//! `sector`. Triangle counts come out 1.10–1.16× an ideal mesh of equilateral
//! triangles that just meet the tolerance (`tests/mesh_chordal.rs`), against
//! 1.22–1.43× for the metric-sized lattice.

use std::f64::consts::{FRAC_1_SQRT_2, FRAC_PI_2, TAU};

use glam::DVec3;

use super::Side;
use crate::mesh::TessellationOptions;
use crate::mesh::cdt::CdtError;
use crate::mesh::cdt::patch::PatchInfo;
use crate::mesh::cdt::region::Region;
use crate::nurbs::builders::FULL_TURN_KNOTS;
use crate::parts::Analytic;

/// Share of the tolerance the rows aim at: room for the evaluated vertices'
/// rounding against the ideal points the rows are chosen on.
const SHARE: f64 = 0.9999;

/// Bisection steps of a row's height (the height to about 1e-7 of the
/// remaining colatitude).
const BISECTIONS: usize = 24;

/// Smaller counts tried for the next row: `n·(1 − k/16)` for k = 1..=SMALLER.
const SMALLER: usize = 8;

/// A staggered row covering at least this share of an ideal triangle's area
/// per triangle is taken without trying smaller counts (they win only where
/// the shrinking parallels have squeezed the staggered strips).
const GOOD_ENOUGH: f64 = 0.9;

/// Largest distance of a vertex evaluated from the surface to the row's ideal
/// point, relative to the radius, for the surface's parametrization to be the
/// full turn of quarter arcs the rows are converted with.
const SAME_POINT: f64 = 1e-9;

/// Whether [`rows`] may lay out `region` (the sector path is then skipped): a
/// sphere patch closed in u by a full turn of quarter arcs, without holes,
/// with one pole, without a stretch limit.
pub(super) fn applies(info: &PatchInfo, region: &Region, options: &TessellationOptions) -> bool {
    let knots = info.surface.u_knots();
    matches!(info.analytic, Some(Analytic::Sphere { .. }))
        && region.holes.is_empty()
        && info.closed_u
        && knots.degree() == 2
        && knots.as_slice() == FULL_TURN_KNOTS
        && info.collapsed[2] != info.collapsed[3]
        && options.max_stretch.is_none()
        && options.tolerance > 0.0
}

/// A row of the lattice: its v and its u values, seam to seam.
type Parallel = (f64, Vec<f64>);

/// The rows strictly between the ring and the pole as `(v, u values)`, v
/// increasing, each running from `lo.x` to `hi.x`; `None` when the patch is not
/// one [`applies`] takes, its sides are not a ring and a pole, or no row fits.
pub(super) fn rows(
    info: &PatchInfo,
    region: &Region,
    options: &TessellationOptions,
    bottom: &Side,
    top: &Side,
    budget: usize,
) -> Result<Option<Vec<Parallel>>, CdtError> {
    let Some(Analytic::Sphere { center, radius }) = info.analytic else {
        return Ok(None);
    };
    if !applies(info, region, options) {
        return Ok(None);
    }
    let (lo, hi) = region.bounds();
    let (ring, ring_v, pole_v) = match (bottom, top) {
        (Side::Ring(u), Side::Pole) => (u, lo.y, hi.y),
        (Side::Pole, Side::Ring(u)) => (u, hi.y, lo.y),
        _ => return Ok(None),
    };
    let Some(frame) = Frame::new(info, center, radius, lo.x, ring_v, pole_v) else {
        return Ok(None);
    };
    let Some(first) = frame.ring(info, ring, ring_v) else {
        return Ok(None);
    };
    let bound = Bound::new(radius, options);
    let Some(chosen) = lay_out(&bound, first, budget)? else {
        return Ok(None);
    };
    let mut out = Vec::with_capacity(chosen.len());
    for row in &chosen {
        let v = frame.v_of(info, row.phi, ring_v, pole_v);
        let Some(us) = frame.us_of(info, &row.lams, v, (lo.x, hi.x)) else {
            return Ok(None);
        };
        out.push((v, us));
    }
    if pole_v < ring_v {
        out.reverse();
    }
    Ok(Some(out))
}

/// A parallel of the sphere: its colatitude from the pole and its vertices'
/// longitudes from the seam, 0 and 2π included.
#[derive(Clone, Debug)]
struct Row {
    phi: f64,
    lams: Vec<f64>,
    /// Vertices of the uniform spacing the row was made with (the seam's extra
    /// vertex of a shifted row not counted).
    count: usize,
    /// Whether the uniform spacing is shifted by half a step from the seam.
    shifted: bool,
}

impl Row {
    fn uniform(phi: f64, count: usize, shifted: bool) -> Self {
        let step = TAU / count as f64;
        let shift = if shifted { 0.5 } else { 0.0 };
        let mut lams = Vec::with_capacity(count + 2);
        if shifted {
            lams.push(0.0);
        }
        lams.extend((0..count).map(|k| (k as f64 + shift) * step));
        lams.push(TAU);
        Self {
            phi,
            lams,
            count,
            shifted,
        }
    }

    /// The row's vertices on the sphere of radius `r` about the origin, the
    /// pole on +Z.
    fn points(&self, r: f64) -> Vec<DVec3> {
        let (s, c) = self.phi.sin_cos();
        self.lams
            .iter()
            .map(|l| {
                let (sl, cl) = l.sin_cos();
                DVec3::new(r * s * cl, r * s * sl, r * c)
            })
            .collect()
    }
}

/// What every triangle of the rows must hold on the sphere of radius `r`
/// about the origin: the chordal tolerance (its [`SHARE`]) and, as an edge
/// length, the angle limit (the normals at an edge's ends, exact on a sphere,
/// turn by the edge's central angle 2·asin(c / 2r)) and the edge length limit.
struct Bound {
    r: f64,
    tolerance: f64,
    max_chord: f64,
}

impl Bound {
    fn new(r: f64, options: &TessellationOptions) -> Self {
        let by_angle = options
            .angle_tolerance
            .map(f64::to_radians)
            .filter(|a| *a < std::f64::consts::PI)
            .map_or(f64::INFINITY, |a| 2.0 * r * (0.5 * a).sin());
        let max_chord = by_angle.min(options.max_edge_length.unwrap_or(f64::INFINITY));
        Self {
            r,
            tolerance: SHARE * options.tolerance.min(r),
            max_chord: max_chord * SHARE,
        }
    }

    /// Whether triangle `p` holds the limits.
    fn holds(&self, p: [DVec3; 3]) -> bool {
        deviation(self.r, p) <= self.tolerance
            && (0..3).all(|i| p[i].distance(p[(i + 1) % 3]) <= self.max_chord)
    }
}

/// A candidate row: the area it covers per triangle, the row and its vertices.
type Candidate = Option<(f64, Row, Vec<DVec3>)>;

/// The greedy rows from the ring `first` to the pole (the ring and the pole
/// excluded), on a sphere of radius `r` to `tolerance`; `None` when no row fits
/// and the pole's fan does not either.
fn lay_out(bound: &Bound, first: Row, budget: usize) -> Result<Option<Vec<Row>>, CdtError> {
    let (r, tolerance) = (bound.r, bound.tolerance);
    // Area per triangle of the ideal mesh: equilateral, circumradius at the bound.
    let ideal = 0.75 * 3f64.sqrt() * (2.0 * r * tolerance - tolerance * tolerance);
    // The area between colatitudes a < b.
    let band = |a: f64, b: f64| TAU * r * r * (a.cos() - b.cos());
    let pole = DVec3::new(0.0, 0.0, r);
    let mut rows: Vec<Row> = Vec::new();
    let mut current = first;
    let mut lower = current.points(r);
    let mut placed = 0usize;
    loop {
        let fan_ok = (0..lower.len() - 1).all(|k| bound.holds([lower[k], lower[k + 1], pole]));
        let fan = fan_ok.then(|| band(0.0, current.phi) / (lower.len() - 1) as f64);
        let mut best: Candidate = None;
        let consider = |count: usize, shifted: bool, best: &mut Candidate| {
            let Some((row, upper)) = raise(bound, &current, &lower, count, shifted) else {
                return;
            };
            let triangles = (lower.len() - 1) + (upper.len() - 1);
            let area = band(row.phi, current.phi) / triangles as f64;
            if best.as_ref().is_none_or(|b| area > b.0) {
                *best = Some((area, row, upper));
            }
        };
        let n = current.count;
        consider(n, !current.shifted, &mut best);
        if best.as_ref().is_none_or(|b| b.0 < GOOD_ENOUGH * ideal) {
            let mut counts: Vec<usize> = (1..=SMALLER)
                .map(|k| ((n * (16 - k)).div_ceil(16)).max(3))
                .filter(|&m| m < n)
                .collect();
            counts.dedup();
            for m in counts {
                consider(m, false, &mut best);
                consider(m, true, &mut best);
            }
        }
        match (fan, best) {
            (Some(f), Some((area, _, _))) if f >= area => break,
            (Some(_), None) => break,
            (_, Some((_, row, upper))) => {
                placed += upper.len();
                if placed > budget {
                    return Err(CdtError::BudgetExceeded {
                        max_vertices: budget,
                        needed: placed,
                    });
                }
                rows.push(row.clone());
                current = row;
                lower = upper;
            }
            (None, None) => return Ok(None),
        }
    }
    Ok(Some(rows))
}

/// The next row of `count` vertices (shifted by half a step or not) above
/// `current` (vertices `lower`), raised as far towards the pole as the zip of
/// the two keeps within `tolerance`; `None` when not even a sliver of a strip
/// does, or the row would reach the pole.
fn raise(
    bound: &Bound,
    current: &Row,
    lower: &[DVec3],
    count: usize,
    shifted: bool,
) -> Option<(Row, Vec<DVec3>)> {
    let within = |phi: f64| {
        let row = Row::uniform(phi, count, shifted);
        let upper = row.points(bound.r);
        zip_within(bound, (current, lower), (&row, &upper)).then_some((row, upper))
    };
    let (mut ok, mut bad) = (0.0f64, current.phi);
    let mut found = within(current.phi * (1.0 - 1e-6))?;
    for _ in 0..BISECTIONS {
        // Heights: the row's colatitude is `current.phi - height`.
        let mid = 0.5 * (ok + bad);
        match within(current.phi - mid) {
            Some(f) => {
                ok = mid;
                found = f;
            }
            None => bad = mid,
        }
    }
    (ok > 0.0 && ok < current.phi * (1.0 - 1e-3)).then_some(found)
}

/// Whether every triangle of the zip of `a` and `b` (each seam to seam, by the
/// shorter diagonal as `structured::zip` takes it) holds `bound`.
///
/// Both rows are uniform, so a turn by 2π/g (g the greatest common divisor of
/// their counts) maps the pair onto itself away from the seam's extra
/// vertices, and the zip's triangles (chosen by lengths alone) with it: only
/// the triangles of the first such period and those near the seam are
/// measured.
fn zip_within(bound: &Bound, (ra, a): (&Row, &[DVec3]), (rb, b): (&Row, &[DVec3])) -> bool {
    let (na, nb) = (a.len() - 1, b.len() - 1);
    let step = TAU / ra.count.min(rb.count) as f64;
    let period = TAU / gcd(ra.count, rb.count) as f64;
    // Triangles wholly inside (from, to) repeat one of the first period's.
    let (from, to) = (period + 2.0 * step, TAU - 2.0 * step);
    let repeats = |l: [f64; 3]| l.iter().all(|&x| x > from && x < to);
    let (mut i, mut j) = (0usize, 0usize);
    while i < na || j < nb {
        let advance_a = if i == na {
            false
        } else if j == nb {
            true
        } else {
            a[i + 1].distance_squared(b[j]) <= a[i].distance_squared(b[j + 1])
        };
        let (tri, l) = if advance_a {
            i += 1;
            (
                [a[i - 1], a[i], b[j]],
                [ra.lams[i - 1], ra.lams[i], rb.lams[j]],
            )
        } else {
            j += 1;
            (
                [a[i], b[j], b[j - 1]],
                [ra.lams[i], rb.lams[j], rb.lams[j - 1]],
            )
        };
        if !repeats(l) && !bound.holds(tri) {
            return false;
        }
    }
    true
}

/// The greatest common divisor of `a` and `b`.
fn gcd(mut a: usize, mut b: usize) -> usize {
    while b != 0 {
        (a, b) = (b, a % b);
    }
    a.max(1)
}

/// The largest distance from the flat triangle `p` (vertices on the sphere of
/// radius `r` about the origin) to the sphere: `r` less the distance from the
/// origin to the triangle's nearest point.
fn deviation(r: f64, p: [DVec3; 3]) -> f64 {
    r - nearest_to_origin(p).length()
}

/// The point of triangle `p` nearest the origin (Ericson, *Real-Time
/// Collision Detection*, 5.1.5).
fn nearest_to_origin([a, b, c]: [DVec3; 3]) -> DVec3 {
    let (ab, ac, ap) = (b - a, c - a, -a);
    let (d1, d2) = (ab.dot(ap), ac.dot(ap));
    if d1 <= 0.0 && d2 <= 0.0 {
        return a;
    }
    let bp = -b;
    let (d3, d4) = (ab.dot(bp), ac.dot(bp));
    if d3 >= 0.0 && d4 <= d3 {
        return b;
    }
    let vc = d1 * d4 - d3 * d2;
    if vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0 {
        return a + ab * (d1 / (d1 - d3));
    }
    let cp = -c;
    let (d5, d6) = (ab.dot(cp), ac.dot(cp));
    if d6 >= 0.0 && d5 <= d6 {
        return c;
    }
    let vb = d5 * d2 - d1 * d6;
    if vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0 {
        return a + ac * (d2 / (d2 - d6));
    }
    let va = d3 * d6 - d5 * d4;
    if va <= 0.0 && d4 - d3 >= 0.0 && d5 - d6 >= 0.0 {
        return b + (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6)));
    }
    let denom = 1.0 / (va + vb + vc);
    a + ab * (vb * denom) + ac * (vc * denom)
}

/// The sphere's frame as the surface lays it: centre, radius, the axis towards
/// the pole, the seam's direction and the direction of increasing u.
struct Frame {
    center: DVec3,
    radius: f64,
    axis: DVec3,
    e1: DVec3,
    e2: DVec3,
    /// The seam's angle in the surface's own turn (its angle at u = u0 is 0).
    seam: f64,
}

impl Frame {
    fn new(
        info: &PatchInfo,
        center: DVec3,
        radius: f64,
        seam_u: f64,
        ring_v: f64,
        pole_v: f64,
    ) -> Option<Self> {
        let s = info.surface;
        let u = info.wrap_u(seam_u);
        let axis = (s.point(u, pole_v) - center).normalize_or_zero();
        let d = s.point(u, ring_v) - center;
        let e1 = (d - axis * d.dot(axis)).normalize_or_zero();
        if axis == DVec3::ZERO || e1 == DVec3::ZERO || radius.is_nan() || radius <= 0.0 {
            return None;
        }
        let ((u0, u1), _) = s.domain();
        let seam = angle_of((u - u0) / (u1 - u0));
        let mut frame = Self {
            center,
            radius,
            axis,
            e1,
            e2: axis.cross(e1),
            seam,
        };
        // u turns the right way about the axis: a quarter turn on is +e2.
        let q = s.point(info.wrap_u(seam_u + 0.25 * (u1 - u0)), ring_v) - center;
        if q.dot(frame.e2) < 0.0 {
            frame.e2 = -frame.e2;
        }
        Some(frame)
    }

    /// The ring's row: its colatitude and longitudes, `None` unless its
    /// vertices are uniform in angle from the seam (as `edge_parameters` puts
    /// them on a circle).
    fn ring(&self, info: &PatchInfo, us: &[f64], v: f64) -> Option<Row> {
        let n = us.len().checked_sub(1).filter(|&n| n >= 3)?;
        let p = info.surface.point(info.wrap_u(us[0]), v) - self.center;
        let phi = p.normalize().dot(self.axis).clamp(-1.0, 1.0).acos();
        if phi.is_nan() || phi <= 0.0 || phi >= std::f64::consts::PI {
            return None;
        }
        let row = Row::uniform(phi, n, false);
        let ideal = row.points(self.radius);
        for (k, &u) in us.iter().enumerate() {
            let q = info.surface.point(info.wrap_u(u), v) - self.center;
            let local = DVec3::new(q.dot(self.e1), q.dot(self.e2), q.dot(self.axis));
            if local.distance(ideal[k]) > 1e-7 * self.radius {
                return None;
            }
        }
        Some(row)
    }

    /// The v of colatitude `phi`, by bisection along the meridian.
    fn v_of(&self, info: &PatchInfo, phi: f64, ring_v: f64, pole_v: f64) -> f64 {
        let u = info.wrap_u(0.0);
        let colatitude = |v: f64| {
            let d = (info.surface.point(u, v) - self.center).normalize_or_zero();
            d.dot(self.axis).clamp(-1.0, 1.0).acos()
        };
        // Colatitude falls from the ring's to 0 going from `ring_v` to `pole_v`.
        let (mut a, mut b) = (ring_v, pole_v);
        for _ in 0..64 {
            let m = 0.5 * (a + b);
            if colatitude(m) > phi { a = m } else { b = m }
        }
        0.5 * (a + b)
    }

    /// The u values of longitudes `lams` from the seam on the row at `v`,
    /// increasing from `span.0` to `span.1`; `None` unless the surface puts
    /// each at its point.
    fn us_of(&self, info: &PatchInfo, lams: &[f64], v: f64, span: (f64, f64)) -> Option<Vec<f64>> {
        let ((u0, u1), _) = info.surface.domain();
        let period = u1 - u0;
        let last = lams.len() - 1;
        let mut us = Vec::with_capacity(lams.len());
        for (k, &lam) in lams.iter().enumerate() {
            let u = match k {
                0 => span.0,
                _ if k == last => span.1,
                _ => {
                    let own = u0 + period * parameter_of((self.seam + lam).rem_euclid(TAU));
                    span.0 + (own - span.0).rem_euclid(period)
                }
            };
            if us.last().is_some_and(|&p: &f64| u <= p) {
                return None;
            }
            us.push(u);
        }
        // Spot checks of the conversion: the first steps and the middle.
        let phi_point = |lam: f64| {
            let d = (info.surface.point(info.wrap_u(us[0]), v) - self.center).normalize_or_zero();
            let phi = d.dot(self.axis).clamp(-1.0, 1.0).acos();
            let (s, c) = phi.sin_cos();
            let (sl, cl) = lam.sin_cos();
            self.center + self.radius * (self.e1 * s * cl + self.e2 * s * sl + self.axis * c)
        };
        for k in [1, 2, last / 2].into_iter().filter(|&k| k < last) {
            let p = info.surface.point(info.wrap_u(us[k]), v);
            if p.distance(phi_point(lams[k])) > SAME_POINT * self.radius {
                return None;
            }
        }
        Some(us)
    }
}

/// The angle of parameter `t` ∈ [0, 1) of a full turn of four symmetric
/// rational quarter arcs (middle weight cos 45°), from its start.
fn angle_of(t: f64) -> f64 {
    let x = 4.0 * t.rem_euclid(1.0);
    let q = x.floor().min(3.0);
    let s = x - q;
    let w = FRAC_1_SQRT_2;
    q * FRAC_PI_2 + 2.0 * (w * s).atan2(1.0 - s + w * s)
}

/// The parameter in [0, 1) of angle `a` ∈ [0, 2π) on such a turn (the
/// inverse of [`angle_of`], as `layout::circles` places a circle's vertices).
fn parameter_of(a: f64) -> f64 {
    let x = a / FRAC_PI_2;
    let q = x.floor().clamp(0.0, 3.0);
    let phi = a - q * FRAC_PI_2;
    let s = (0.5 * phi).tan();
    let w = FRAC_1_SQRT_2;
    (q + s / (w + s * (1.0 - w))) / 4.0
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn parameters_and_angles_invert() {
        for k in 0..64 {
            let a = TAU * k as f64 / 64.0 + 0.01;
            assert!((angle_of(parameter_of(a)) - a).abs() < 1e-12, "{a}");
        }
    }

    /// The deviation is the closed form R − √(R² − ρ²) for an acute triangle
    /// (ρ its circumradius) and the longest edge's for an obtuse one.
    #[test]
    fn deviation_is_the_whole_triangle_bound() {
        let r = 1000.0;
        let at = |phi: f64, lam: f64| {
            DVec3::new(
                r * phi.sin() * lam.cos(),
                r * phi.sin() * lam.sin(),
                r * phi.cos(),
            )
        };
        // Equilateral about the pole: circumradius r·sin φ.
        let phi = 0.1;
        let tri = [0.0, TAU / 3.0, 2.0 * TAU / 3.0].map(|l| at(phi, l));
        let rho = r * phi.sin();
        let expected = r - (r * r - rho * rho).sqrt();
        assert!((deviation(r, tri) - expected).abs() < 1e-9);
        // Obtuse: two close points and one far round the parallel; the
        // longest edge's half-length decides.
        let tri = [at(phi, 0.0), at(phi, 0.01), at(phi, 2.0)];
        let half = 0.5 * tri[0].distance(tri[2]);
        let expected = r - (r * r - half * half).sqrt();
        assert!((deviation(r, tri) - expected).abs() < 1e-9);
    }
}
