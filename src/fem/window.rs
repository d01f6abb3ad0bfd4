//! Where a nozzle opens into the structured mesh of rows and divisions: each
//! nozzle on a cylindrical course (radial, hillside, tangential or inclined)
//! or off the centre of a head takes a window of whole cells (station
//! intervals × circumferential divisions) around its opening, which [`super::nozzle`] re-meshes as a ring of quadrilaterals from
//! the window's edges to the exact intersection curve, and then the neck. The
//! window reaches at least [`MARGIN`] times the opening's extent on each side of
//! the point where the nozzle axis meets the course (and past the pad), and
//! far enough past it for the ring to grade from the opening's node spacing to
//! the cells' width at [`super::grading::RING_GROWTH`] (at
//! [`super::grading::GROWTH`] where the course's end cuts that room short), holds at
//! least [`MIN_LOOP`] cell edges round its boundary (so the opening gets as many
//! nodes), and stays on its course (or head). The intersection of the neck's and the
//! course's mid-surfaces is solved in closed form along each generator of the
//! neck (a quadratic; on a head [`super::head_window`] charts the head by
//! meridian arc length and angle and solves it there), so its nodes are exact
//! points of both. Nozzles the mesh cannot take (a window that would overlap
//! another, an opening too near its head's centre) are left out with a note
//! saying so; centre head nozzles are meshed by [`super::head_nozzle`].

use std::f64::consts::{PI, TAU};

use glam::{DVec2, DVec3};

use super::FePart;
use super::head_window::{self, HeadChart};
use super::meridian::Meridian;
use crate::constraints::ResolvedVessel;
use crate::operating::profile::Piece;
use crate::parts::PartGeometry;
use crate::parts::tables::pipe;

/// Window extent over the opening's extent, at least.
pub const MARGIN: f64 = 1.6;
/// Cell edges round a window (the opening's node count), at least.
pub const MIN_LOOP: usize = 16;
/// Generators sampled to find the opening's extent and its polar angles.
const SAMPLES: usize = 720;

/// A nozzle on a cylindrical course and the window it re-meshes, in the vessel
/// frame.
#[derive(Clone, Debug, PartialEq)]
pub struct Hole {
    /// Nozzle mark.
    pub mark: String,
    /// FE part index of the host course.
    pub part: usize,
    /// Meridian segment of the host course.
    pub seg: usize,
    /// Lower and upper station of the window (cells are intervals `i0..i1`).
    pub i0: usize,
    /// Upper station.
    pub i1: usize,
    /// First circumferential division (unwrapped; node `k.rem_euclid(n)`).
    pub k0: i64,
    /// Divisions across the window.
    pub a: usize,
    /// Angle about the vessel axis (radians from +x) of the point where the
    /// nozzle axis meets the course's mid-surface: the window's centre.
    pub theta: f64,
    /// Axial position of that point, mm.
    pub z: f64,
    /// Centre of the course's cross-section (vessel frame x, y).
    pub centre: DVec2,
    /// Course mid-surface radius, mm.
    pub big_r: f64,
    /// Neck mid-surface radius, mm.
    pub r: f64,
    /// Neck wall, mm.
    pub wall: f64,
    /// Origin of the nozzle frame (where its projection is measured from).
    pub origin: DVec3,
    /// Unit nozzle axis, outwards.
    pub axis: DVec3,
    /// Unit neck direction at neck angle φ = 0 (across the axis, along the
    /// course's circumference at a radial nozzle).
    pub e1: DVec3,
    /// Unit neck direction at φ = 90° (the vessel axis made normal to the nozzle's).
    pub e2: DVec3,
    /// Distance of the neck's end (the flange's back) from `origin`, mm.
    pub end: f64,
    /// Pad (outside diameter, thickness), mm.
    pub pad: Option<(f64, f64)>,
    /// Growth of the ring's size field ([`super::grading::layers_at`]).
    pub growth: f64,
    /// On a head, its chart ([`super::head_window`]): then `theta`, `big_r`
    /// are the angle and radius of the window's centre and `z` its meridian
    /// arc length σ, and the window is charted `(ρ·Δθ, Δσ)`; `None` on a
    /// course, unrolled `(R·Δθ, Δz)`.
    pub chart: Option<HeadChart>,
}

impl Hole {
    /// Whether cell (interval `i`, division `k` in 0..n) lies in the window.
    pub fn covers(&self, i: usize, k: usize, n: usize) -> bool {
        let dk = (k as i64 - self.k0).rem_euclid(n as i64) as usize;
        (self.i0..self.i1).contains(&i) && dk < self.a
    }

    /// The point of the neck's mid-surface at neck angle `phi`, `t` mm along
    /// the axis from the origin.
    pub fn on_neck(&self, phi: f64, t: f64) -> DVec3 {
        self.origin + self.axis * t + (self.e1 * phi.cos() + self.e2 * phi.sin()) * self.r
    }

    /// Where the neck's generator at angle `phi` meets the host's
    /// mid-surface: the distance along the axis from the origin (on a course
    /// the outer root of |q + t·d − c|² = R² across the vessel axis, on a head
    /// [`HeadChart::meet`]), `None` if it misses.
    pub fn meet(&self, phi: f64) -> Option<f64> {
        let q = self.on_neck(phi, 0.0);
        match &self.chart {
            None => meet(q, self.axis, self.centre, self.big_r),
            Some(c) => c.meet(q, self.axis).map(|m| m.t),
        }
    }

    /// The intersection point at neck angle `phi` in the window's chart:
    /// (R·Δθ, Δz) on a course, (ρ·Δθ, Δσ) on a head.
    pub fn curve_uv(&self, phi: f64) -> DVec2 {
        let q = self.on_neck(phi, 0.0);
        match &self.chart {
            None => self.unroll(self.on_neck(phi, self.meet(phi).unwrap_or(0.0))),
            Some(c) => {
                let Some(m) = c.meet(q, self.axis) else {
                    return DVec2::ZERO;
                };
                let centre = (self.theta, self.z, self.big_r);
                super::head_window::uv(c, m.seg, m.s, q + self.axis * m.t, centre)
            }
        }
    }

    /// The exact point of the host's mid-surface at chart position `p`.
    pub fn surface(&self, mer: &Meridian, p: DVec2) -> DVec3 {
        let theta = self.theta + p.x / self.big_r;
        match &self.chart {
            None => {
                let seg = mer.segments[self.seg];
                seg.point(seg.piece.at_z(self.z + p.y), theta)
            }
            Some(c) => c.point(self.z + p.y, theta),
        }
    }

    /// The chart's second coordinate of station `i`: Δz on a course, Δσ on a head.
    pub fn station_v(&self, mer: &Meridian, i: usize) -> f64 {
        match &self.chart {
            None => station_z(mer, i) - self.z,
            Some(c) => {
                let (seg, s) = mer.stations[i];
                c.sigma(seg, s) - self.z
            }
        }
    }

    /// A point of the course unrolled about the window's centre: (R·Δθ, Δz).
    pub fn unroll(&self, p: DVec3) -> DVec2 {
        let rel = p.truncate() - self.centre;
        let dth = (rel.y.atan2(rel.x) - self.theta + PI).rem_euclid(TAU) - PI;
        DVec2::new(self.big_r * dth, p.z - self.z)
    }
}

/// The outer root t of |(q + t·d)ₕ − c|² = R² (ₕ: across the z axis).
fn meet(q: DVec3, d: DVec3, c: DVec2, radius: f64) -> Option<f64> {
    let qh = q.truncate() - c;
    let dh = d.truncate();
    let a = dh.length_squared();
    let half_b = qh.dot(dh);
    let cc = qh.length_squared() - radius * radius;
    let disc = half_b * half_b - a * cc;
    (a > 1e-12 && disc >= 0.0).then(|| (-half_b + disc.sqrt()) / a)
}

/// Neck angles φ of `count` curve nodes whose polar angles about the window's
/// centre, in the unrolled plane, are `targets` (increasing, within one turn of
/// each other): the inverse of the sampled polar angle of the curve, which is
/// increasing in φ when the opening is star-shaped about its centre (`None`
/// when it is not).
pub fn phis_at(hole: &Hole, targets: &[f64]) -> Option<Vec<f64>> {
    let mut alpha = Vec::with_capacity(SAMPLES + 1);
    for k in 0..=SAMPLES {
        let phi = TAU * k as f64 / SAMPLES as f64;
        let p = hole.curve_uv(phi);
        let mut a = p.y.atan2(p.x);
        if let Some(&prev) = alpha.last() {
            while a < prev - PI {
                a += TAU;
            }
            while a > prev + PI {
                a -= TAU;
            }
            if a <= prev {
                return None;
            }
        }
        alpha.push(a);
    }
    if (alpha[SAMPLES] - alpha[0] - TAU).abs() > 1e-6 {
        return None;
    }
    Some(
        targets
            .iter()
            .map(|&t| {
                let turns = ((t - alpha[0]) / TAU).floor();
                let t = t - turns * TAU;
                let j = alpha.partition_point(|&a| a < t).clamp(1, SAMPLES);
                let f = (t - alpha[j - 1]) / (alpha[j] - alpha[j - 1]);
                TAU * ((j - 1) as f64 + f) / SAMPLES as f64 + turns * TAU
            })
            .collect(),
    )
}

/// Axial position of station `i`.
fn station_z(mer: &Meridian, i: usize) -> f64 {
    let (seg, s) = mer.stations[i];
    mer.segments[seg].rz(s).y
}

/// The windows [`plan`] found, and the largest pole-cap rim radius at the
/// chain's start and end that leaves room for the windows of off-centre head
/// nozzles (infinite where none asks for less than the cap has).
#[derive(Clone, Debug, PartialEq)]
pub struct Plan {
    /// The windows.
    pub holes: Vec<Hole>,
    /// Cap rim radius limits at the chain's start and end, mm.
    pub caps: [f64; 2],
}

/// The windows of the nozzles of `resolved` on cylindrical courses and off
/// the centre of heads, on the mesh of `n` divisions whose parts are `parts`;
/// nozzles whose marks are in `meshed` (centre head nozzles) are skipped, what
/// is left out goes to `notes`. A head nozzle whose window would reach its
/// head's pole cap is left out, and [`Plan::caps`] says how small the cap
/// must be for it ([`super::envelope`] plans again with that cap).
pub fn plan(
    resolved: &ResolvedVessel,
    mer: &Meridian,
    n: usize,
    parts: &[FePart],
    meshed: &[String],
    notes: &mut Vec<String>,
) -> Plan {
    let mut holes: Vec<Hole> = Vec::new();
    let mut caps = [f64::INFINITY; 2];
    for nz in &resolved.nozzles {
        if meshed.contains(&nz.mark) {
            continue;
        }
        let mut skip = |why: &str| notes.push(format!("nozzle {} left out: {why}", nz.mark));
        let host = &resolved.parts[nz.host];
        let Some(part) = parts.iter().position(|p| p.id == host.id) else {
            skip(&format!("its host {} is not in the envelope mesh", host.id));
            continue;
        };
        let o = nz.frame.translation;
        let d = (nz.frame.matrix3 * DVec3::Z).normalize();
        let g = nz.geometry;
        let (Ok(wall), Ok(flange)) = (pipe(g.nps).wall(g.schedule), g.flange_length()) else {
            skip("its pipe or flange is not in the tables");
            continue;
        };
        let r = 0.5 * (g.outside_diameter() - wall);
        let course = mer.segments.iter().position(|s| {
            s.part == part
                && matches!(s.piece, Piece::Line { r0, r1, z0, z1 }
                    if (r0 - r1).abs() <= 1e-9 * r0.abs().max(1.0)
                        && o.z > z0.min(z1) && o.z < z0.max(z1))
        });
        let mut hole = Hole {
            mark: nz.mark.clone(),
            part,
            seg: 0,
            i0: 0,
            i1: 0,
            k0: 0,
            a: 0,
            theta: 0.0,
            z: 0.0,
            centre: DVec2::ZERO,
            big_r: 0.0,
            r,
            wall,
            origin: o,
            axis: d,
            e1: DVec3::X,
            e2: DVec3::Y,
            end: g.projection - flange,
            pad: nz.pad,
            growth: super::grading::RING_GROWTH,
            chart: None,
        };
        let segs: Vec<usize>;
        if let Some(seg) = course {
            let segment = mer.segments[seg];
            hole.seg = seg;
            hole.centre = segment.centre.at(o.z);
            hole.big_r = segment.rz(segment.s0).x;
            let Some(tc) = meet(o, d, hole.centre, hole.big_r) else {
                skip("its axis misses its course's mid-surface");
                continue;
            };
            let pc = o + d * tc;
            hole.theta = (pc.y - hole.centre.y)
                .atan2(pc.x - hole.centre.x)
                .rem_euclid(TAU);
            hole.z = pc.z;
            hole.e2 = (DVec3::Z - d * d.z).normalize();
            // Every piece of the course: a saddle's or skirt's ring splits it.
            segs = (0..mer.segments.len())
                .filter(|&t| mer.segments[t].part == part && mer.segments[t].piece == segment.piece)
                .collect();
        } else if matches!(host.geometry, PartGeometry::Head(_)) {
            let chart = HeadChart::new(mer, part);
            segs = chart.segments();
            let (Some(&s_first), Some(&s_last)) = (segs.first(), segs.last()) else {
                skip("its head has no rows");
                continue;
            };
            // The pole cap on this head, if any: (end, rim radius).
            let cap = match (mer.start_cap, mer.end_cap) {
                (Some(c), _) if c.seg == s_first => Some((0, c.radius)),
                (_, Some(c)) if c.seg == s_last => Some((1, c.radius)),
                _ => None,
            };
            if let Some((side, rim)) = cap {
                let sg = mer.segments[s_first];
                let rho = (o.truncate() - sg.centre.at(o.z)).length();
                let cell = TAU * rho / n as f64;
                let ext = nz.pad.map_or(r, |(od, _)| (0.5 * od * 1.15).max(r));
                // The ring's reach ([`plan`]'s `reach_at` below) with the
                // window's edge count taken generously (more edges, more reach).
                let edges = (8.0 * MARGIN * ext / cell).max(MIN_LOOP as f64);
                let reach = ((cell - TAU * r / edges) / super::grading::RING_GROWTH).max(0.0);
                let room = (MARGIN * ext).max(ext + reach) - r;
                let Some(limit) = head_window::cap_limit(rho, rho - r, room, cell) else {
                    skip(
                        "it is too near its head's centre for a window (nozzles on the \
                         centre, and off it by more than their window, are meshed)",
                    );
                    continue;
                };
                if rim > limit * (1.0 + 1e-9) {
                    caps[side] = caps[side].min(limit);
                    skip(&format!(
                        "its window reaches its head's pole cap (rim radius {rim:.1} mm, \
                         {limit:.1} mm leaves room)"
                    ));
                    continue;
                }
            }
            let Some((theta, sigma, rho, m)) = head_window::centre(&chart, o, d) else {
                skip("its axis meets its head nowhere on the head's rows");
                continue;
            };
            hole.seg = m.seg;
            hole.theta = theta;
            hole.z = sigma;
            hole.big_r = rho;
            hole.centre = chart.segment(m.seg).centre.at(o.z);
            let tangent = chart.tangent(m.seg, m.s, theta);
            hole.e2 = (tangent - d * tangent.dot(d)).normalize();
            hole.chart = Some(chart);
        } else {
            skip(&format!(
                "nozzles on a {} are not meshed (only on cylindrical courses and heads)",
                host.geometry.kind()
            ));
            continue;
        }
        if r >= 0.8 * hole.big_r {
            skip("a neck wider than 0.8 of its host's radius there is not meshed yet");
            continue;
        }
        hole.e1 = hole.e2.cross(d);
        // The opening's extent about its centre, in the chart, and the pad's.
        let mut lo = DVec2::splat(f64::INFINITY);
        let mut hi = DVec2::splat(f64::NEG_INFINITY);
        let mut deepest = f64::NEG_INFINITY;
        let mut missed = false;
        for k in 0..SAMPLES {
            let phi = TAU * k as f64 / SAMPLES as f64;
            let Some(t) = hole.meet(phi) else {
                missed = true;
                break;
            };
            deepest = deepest.max(t);
            let p = hole.curve_uv(phi);
            lo = lo.min(p);
            hi = hi.max(p);
        }
        if missed || hole.end <= deepest || phis_at(&hole, &[0.0]).is_none() {
            skip(
                "its neck does not cross its host's mid-surface wholly before its end, \
                 or its opening is not star-shaped about its centre",
            );
            continue;
        }
        let (raw_lo, raw_hi) = (lo, hi);
        if let Some((od, _)) = nz.pad {
            let grow = (0.5 * od * 1.15 / r).max(1.0);
            lo *= grow;
            hi *= grow;
        }
        // Room round the opening for the ring to grade from the curve's
        // spacing to the cells' width: at least (w − spacing)/GROWTH.
        let big_r = hole.big_r;
        let w = TAU * big_r / n as f64;
        let reach_at = |growth: f64| {
            let mut reach = 0.0;
            for _ in 0..3 {
                let perimeter = 2.0 * ((hi - lo).x + (hi - lo).y) + 8.0 * reach;
                let edges = (perimeter / w).max(MIN_LOOP as f64);
                reach = ((w - TAU * r / edges) / growth).max(0.0);
            }
            reach
        };
        // Stations of the host's segments.
        let on_seg: Vec<usize> = (0..mer.intervals.len())
            .filter(|&i| segs.contains(&mer.intervals[i].seg))
            .collect();
        let (Some(&first), Some(&last)) = (on_seg.first(), on_seg.last()) else {
            skip("its host has no elements");
            continue;
        };
        let top = last + 1;
        let v = |i: usize| hole.station_v(mer, i);
        // Where the host's end cuts the slow ring's room short, the ring
        // grows faster, as the room allows (a slow growth there squeezes its
        // layers on that side).
        let slow = reach_at(hole.growth);
        let growth = if v(first) > (lo.y * MARGIN).min(lo.y - slow)
            || v(top) < (hi.y * MARGIN).max(hi.y + slow)
        {
            super::grading::GROWTH
        } else {
            hole.growth
        };
        let reach = reach_at(growth);
        let lo = (lo * MARGIN).min(lo - DVec2::splat(reach));
        let hi = (hi * MARGIN).max(hi + DVec2::splat(reach));
        let cell = TAU / n as f64;
        let kc = hole.theta / cell;
        let mut k0 = (kc + lo.x / (big_r * cell)).floor() as i64;
        let mut k1 = (kc + hi.x / (big_r * cell)).ceil() as i64;
        // The window's stations.
        let mut i0 = (first..=top).rev().find(|&i| v(i) <= lo.y).unwrap_or(first);
        let mut i1 = (first..=top).find(|&i| v(i) >= hi.y).unwrap_or(top);
        if v(i0) > 1.1 * raw_lo.y || v(i1) < 1.1 * raw_hi.y {
            skip("its opening is too near its host's end for a window");
            continue;
        }
        // Widen to MIN_LOOP edges, keeping the window as square as it can be
        // (its width and height in mm), the nearer side first.
        while (k1 - k0) as usize + (i1 - i0) < MIN_LOOP / 2 {
            let width = (k1 - k0) as f64 * big_r * cell;
            let height = v(i1) - v(i0);
            let (below, above) = (-v(i0), v(i1));
            let grow_z = height < width && (i0 > first || i1 < top);
            if grow_z {
                if (below <= above && i0 > first) || i1 == top {
                    i0 -= 1;
                } else {
                    i1 += 1;
                }
            } else if kc - k0 as f64 <= k1 as f64 - kc {
                k0 -= 1;
            } else {
                k1 += 1;
            }
        }
        let a = (k1 - k0) as usize;
        if 2 * a > n {
            skip("its window would span half the circumference");
            continue;
        }
        (hole.i0, hole.i1, hole.k0, hole.a) = (i0, i1, k0, a);
        hole.growth = growth;
        let clash = holes.iter().find(|h| {
            h.part == part
                && h.i0 < i1
                && i0 < h.i1
                && (0..a)
                    .any(|dk| h.covers(h.i0, (k0 + dk as i64).rem_euclid(n as i64) as usize, n))
        });
        if let Some(other) = clash {
            let why = format!("its window overlaps nozzle {}'s", other.mark);
            skip(&why);
            continue;
        }
        holes.push(hole);
    }
    Plan { holes, caps }
}
