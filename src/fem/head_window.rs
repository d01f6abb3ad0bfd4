//! The chart a window takes on a head, for a nozzle off the head's centre
//! ([`super::window`] plans it, [`super::nozzle`] meshes it): a head is a
//! surface of revolution, so the point at meridian arc length σ (along the
//! envelope's chain, through the head's knuckle and crown alike) and angle θ
//! is an exact point of its mid-surface, and `(u, v) = (ρ·Δθ, Δσ)` about the
//! point where the nozzle axis meets the head (ρ its radius there) charts the
//! head round the opening as the unrolled `(R·Δθ, Δz)` charts a course. The
//! envelope's stations and divisions are lines of constant σ and θ, so the
//! window is a block of whole cells as on a course. A head nozzle is parallel
//! to the vessel axis, so each generator of its neck meets the head's
//! mid-surface at the one point of the head's meridian at the generator's
//! distance from the axis: the intersection is in closed form (the piece's
//! parameter at that radius). The pole cap ([`super::cap`]) has no rows of
//! constant σ: where an opening's window would reach it,
//! [`super::envelope`] shrinks the cap so the window lies on the rows around it
//! ([`cap_limit`]).

use glam::{DVec2, DVec3};

use super::meridian::{Meridian, Segment, arc_table};
use crate::operating::profile::Piece;

/// A head's mid-surface charted by meridian arc length and angle.
#[derive(Clone, Debug, PartialEq)]
pub struct HeadChart {
    /// The chain's segments (the meridian's).
    segments: Vec<Segment>,
    /// The head's FE part index.
    part: usize,
    /// σ at each segment's start, mm from the chain's start.
    starts: Vec<f64>,
    /// Each segment's (parameter, arc length from its start) table.
    tables: Vec<Vec<(f64, f64)>>,
}

/// Where a neck's generator meets the head: the distance along the nozzle
/// axis, the segment and its parameter.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Meet {
    /// Distance along the nozzle axis from the generator's origin, mm.
    pub t: f64,
    /// Segment index.
    pub seg: usize,
    /// Parameter on the segment's piece.
    pub s: f64,
}

impl HeadChart {
    /// The chart of part `part` (a head) of the meridian `mer`.
    pub fn new(mer: &Meridian, part: usize) -> HeadChart {
        let tables: Vec<Vec<(f64, f64)>> = mer
            .segments
            .iter()
            .map(|s| arc_table(s, s.s0, s.s1))
            .collect();
        let mut starts = Vec::with_capacity(tables.len());
        let mut acc = 0.0;
        for t in &tables {
            starts.push(acc);
            acc += t.last().map_or(0.0, |x| x.1);
        }
        HeadChart {
            segments: mer.segments.clone(),
            part,
            starts,
            tables,
        }
    }

    /// The chain's segments on the head, in chain order.
    pub fn segments(&self) -> Vec<usize> {
        (0..self.segments.len())
            .filter(|&k| self.segments[k].part == self.part)
            .collect()
    }

    /// The segment `k`.
    pub fn segment(&self, k: usize) -> Segment {
        self.segments[k]
    }

    /// Arc length σ of parameter `s` on segment `seg` (within its stations'
    /// range), interpolated in the segment's table as [`HeadChart::at_sigma`]
    /// inverts it.
    pub fn sigma(&self, seg: usize, s: f64) -> f64 {
        let sg = &self.segments[seg];
        let table = &self.tables[seg];
        let n = table.len() - 1;
        let span = sg.s1 - sg.s0;
        if span == 0.0 {
            return self.starts[seg];
        }
        let x = ((s - sg.s0) / span * n as f64).clamp(0.0, n as f64);
        let j = (x.floor() as usize).min(n - 1);
        let f = x - j as f64;
        self.starts[seg] + table[j].1 + f * (table[j + 1].1 - table[j].1)
    }

    /// Segment and parameter at arc length `sigma` (clamped to the chain).
    pub fn at_sigma(&self, sigma: f64) -> (usize, f64) {
        let k = self
            .starts
            .partition_point(|&s| s <= sigma)
            .saturating_sub(1)
            .min(self.segments.len() - 1);
        let table = &self.tables[k];
        let local = sigma - self.starts[k];
        let j = table
            .partition_point(|&(_, a)| a < local)
            .clamp(1, table.len() - 1);
        let (a, b) = (table[j - 1], table[j]);
        let f = ((local - a.1) / (b.1 - a.1).max(f64::MIN_POSITIVE)).clamp(0.0, 1.0);
        (k, a.0 + f * (b.0 - a.0))
    }

    /// The exact point of the mid-surface at arc length `sigma`, angle `theta`.
    pub fn point(&self, sigma: f64, theta: f64) -> DVec3 {
        let (k, s) = self.at_sigma(sigma);
        self.segments[k].point(s, theta)
    }

    /// Where the line through `q` along `d` (parallel to the vessel axis)
    /// meets the head's mid-surface within its meshed rows: the head's point at
    /// the line's distance from the axis. `None` when the line is not parallel
    /// to the axis or meets the head nowhere on its rows (past its rim, or in
    /// its pole cap).
    pub fn meet(&self, q: DVec3, d: DVec3) -> Option<Meet> {
        if d.z.abs() < 1.0 - 1e-9 {
            return None;
        }
        for k in self.segments() {
            let sg = self.segments[k];
            if let Piece::Line { r0, r1, .. } = sg.piece
                && (r0 - r1).abs() <= 1e-9 * r0.abs().max(1.0)
            {
                continue;
            }
            let rho = (q.truncate() - sg.centre.at(q.z)).length();
            let (ra, rb) = (sg.rz(sg.s0).x, sg.rz(sg.s1).x);
            let tol = 1e-9 * ra.max(rb).max(1.0);
            if rho < ra.min(rb) - tol || rho > ra.max(rb) + tol {
                continue;
            }
            let s = sg.piece.at_r(rho);
            let z = sg.rz(s).y;
            return Some(Meet {
                t: (z - q.z) / d.z,
                seg: k,
                s,
            });
        }
        None
    }

    /// The unit tangent of the meridian, in the chain's direction, at
    /// parameter `s` of segment `seg` and angle `theta`.
    pub fn tangent(&self, seg: usize, s: f64, theta: f64) -> DVec3 {
        let sg = self.segments[seg];
        let (dr, dz) = sg.piece.derivative(s);
        let sign = if sg.s1 >= sg.s0 { 1.0 } else { -1.0 };
        let (sin, cos) = theta.sin_cos();
        (DVec3::new(dr * cos, dr * sin, dz) * sign).normalize()
    }
}

/// The largest rim radius of a pole cap that leaves a window round an
/// opening whose nearest point to the axis is `rho_min` from it, centred at
/// `rho_c`, with `room` mm of window (in arc length) needed beyond the opening
/// on the pole's side and cells `cell` mm wide there: the arc length between
/// two radii is at least their difference, so a rim at `rho_min − room − cell`
/// leaves the room and a row. `None` when that is under a fifth of `rho_c`
/// (an opening that near the centre is left out).
pub fn cap_limit(rho_c: f64, rho_min: f64, room: f64, cell: f64) -> Option<f64> {
    let limit = rho_min - room - cell;
    (limit >= 0.2 * rho_c).then_some(limit)
}

/// The opening's centre on the head in the chart: (θ, σ, ρ) where the
/// nozzle axis through `o` meets it.
pub fn centre(chart: &HeadChart, o: DVec3, d: DVec3) -> Option<(f64, f64, f64, Meet)> {
    let m = chart.meet(o, d)?;
    let p = o + d * m.t;
    let sg = chart.segment(m.seg);
    let rel = p.truncate() - sg.centre.at(p.z);
    let theta = rel.y.atan2(rel.x).rem_euclid(std::f64::consts::TAU);
    Some((theta, chart.sigma(m.seg, m.s), rel.length(), m))
}

/// Chart coordinates `(ρ_c·Δθ, Δσ)` of the point of segment `seg`,
/// parameter `s`, at plane position `p`, about the centre `(theta, sigma)`.
pub fn uv(chart: &HeadChart, seg: usize, s: f64, p: DVec3, centre: (f64, f64, f64)) -> DVec2 {
    let (theta, sigma, rho) = centre;
    let sg = chart.segment(seg);
    let rel = p.truncate() - sg.centre.at(p.z);
    let pi = std::f64::consts::PI;
    let dth = (rel.y.atan2(rel.x) - theta + pi).rem_euclid(std::f64::consts::TAU) - pi;
    DVec2::new(rho * dth, chart.sigma(seg, s) - sigma)
}
