//! Where a nozzle opens into the structured course mesh: each radial nozzle on a
//! cylindrical course takes a window of whole cells (station intervals ×
//! circumferential divisions) around its opening, which [`super::nozzle`]
//! re-meshes as a ring of quadrilaterals from the window's edges to the exact
//! intersection curve, and then the neck. The window reaches at least
//! [`MARGIN`] times the opening's half-extents (and past the pad), holds at
//! least [`MIN_LOOP`] cell edges round its boundary (so the opening gets as many
//! nodes), and stays on its course. Nozzles the mesh cannot take yet (on heads,
//! hillside, tangential or inclined, or a window that would overlap another)
//! are left out with a note saying so.

use std::f64::consts::TAU;

use glam::{DVec2, DVec3};

use super::FePart;
use super::meridian::Meridian;
use crate::constraints::ResolvedVessel;
use crate::operating::profile::Piece;
use crate::parts::tables::pipe;

/// Window half-extent over the opening's half-extent, at least.
pub const MARGIN: f64 = 1.6;
/// Cell edges round a window (the opening's node count), at least.
pub const MIN_LOOP: usize = 16;

/// A radial nozzle on a cylindrical course and the window it re-meshes, in the
/// vessel frame.
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
    /// Angle of the nozzle axis about the vessel axis, radians from +x.
    pub theta: f64,
    /// Axial position of the nozzle axis, mm.
    pub z: f64,
    /// Centre of the course's cross-section at `z` (vessel frame x, y).
    pub centre: DVec2,
    /// Course mid-surface radius, mm.
    pub big_r: f64,
    /// Neck mid-surface radius, mm.
    pub r: f64,
    /// Neck wall, mm.
    pub wall: f64,
    /// Distance of the neck's end (the flange's back) from the course axis, mm.
    pub end: f64,
    /// Pad (outside diameter, thickness), mm.
    pub pad: Option<(f64, f64)>,
}

impl Hole {
    /// The nozzle axis direction (radial, vessel frame).
    pub fn axis(&self) -> DVec3 {
        DVec3::new(self.theta.cos(), self.theta.sin(), 0.0)
    }

    /// The point where the axis meets the course axis.
    pub fn origin(&self) -> DVec3 {
        DVec3::new(self.centre.x, self.centre.y, self.z)
    }

    /// Whether cell (interval `i`, division `k` in 0..n) lies in the window.
    pub fn covers(&self, i: usize, k: usize, n: usize) -> bool {
        let dk = (k as i64 - self.k0).rem_euclid(n as i64) as usize;
        (self.i0..self.i1).contains(&i) && dk < self.a
    }
}

/// Axial position of station `i`.
fn station_z(mer: &Meridian, i: usize) -> f64 {
    let (seg, s) = mer.stations[i];
    mer.segments[seg].rz(s).y
}

/// The windows of the radial shell nozzles of `resolved`, on the mesh of `n`
/// divisions whose parts are `parts`; what is left out goes to `notes`.
pub fn plan(
    resolved: &ResolvedVessel,
    mer: &Meridian,
    n: usize,
    parts: &[FePart],
    notes: &mut Vec<String>,
) -> Vec<Hole> {
    let mut holes: Vec<Hole> = Vec::new();
    for nz in &resolved.nozzles {
        let mut skip = |why: &str| notes.push(format!("nozzle {} left out: {why}", nz.mark));
        let host = &resolved.parts[nz.host];
        let Some(part) = parts.iter().position(|p| p.id == host.id) else {
            skip(&format!("its host {} is not in the envelope mesh", host.id));
            continue;
        };
        let o = nz.frame.translation;
        let d = (nz.frame.matrix3 * DVec3::Z).normalize();
        let seg = mer.segments.iter().position(|s| {
            s.part == part
                && matches!(s.piece, Piece::Line { r0, r1, z0, z1 }
                    if (r0 - r1).abs() <= 1e-9 * r0.abs().max(1.0)
                        && o.z > z0.min(z1) && o.z < z0.max(z1))
        });
        let Some(seg) = seg else {
            skip("only nozzles on cylindrical courses are meshed yet (head nozzles are not)");
            continue;
        };
        let segment = mer.segments[seg];
        let centre = segment.centre.at(o.z);
        if d.z.abs() > 1e-9 || (o.truncate() - centre).length() > 1e-6 {
            skip("hillside, tangential and inclined nozzles are not meshed yet");
            continue;
        }
        let big_r = segment.rz(segment.s0).x;
        let g = nz.geometry;
        let (Ok(wall), Ok(flange)) = (pipe(g.nps).wall(g.schedule), g.flange_length()) else {
            skip("its pipe or flange is not in the tables");
            continue;
        };
        let r = 0.5 * (g.outside_diameter() - wall);
        if r >= 0.8 * big_r {
            skip("a neck wider than 0.8 of its course is not meshed yet");
            continue;
        }
        let theta = d.y.atan2(d.x).rem_euclid(TAU);
        let half_u = big_r * (r / big_r).asin();
        let pad_r = nz.pad.map_or(0.0, |(od, _)| 0.5 * od * 1.15);
        let ext_u = (MARGIN * half_u).max(pad_r);
        let ext_z = (MARGIN * r).max(pad_r);
        let cell = TAU / n as f64;
        let kc = theta / cell;
        let mut k0 = (kc - ext_u / (big_r * cell)).floor() as i64;
        let mut k1 = (kc + ext_u / (big_r * cell)).ceil() as i64;
        // Stations of this segment, and the window's.
        let on_seg: Vec<usize> = (0..mer.intervals.len())
            .filter(|&i| mer.intervals[i].seg == seg)
            .collect();
        let (Some(&lo), Some(&hi)) = (on_seg.first(), on_seg.last()) else {
            skip("its course has no elements");
            continue;
        };
        let hi = hi + 1;
        let mut i0 = (lo..=hi)
            .rev()
            .find(|&i| station_z(mer, i) <= o.z - ext_z)
            .unwrap_or(lo);
        let mut i1 = (lo..=hi)
            .find(|&i| station_z(mer, i) >= o.z + ext_z)
            .unwrap_or(hi);
        if station_z(mer, i0) > o.z - 1.1 * r || station_z(mer, i1) < o.z + 1.1 * r {
            skip("its opening is too near its course's end for a window");
            continue;
        }
        // Widen to MIN_LOOP edges, keeping the window as square as it can be
        // (its width and height in mm), the nearer side first.
        while (k1 - k0) as usize + (i1 - i0) < MIN_LOOP / 2 {
            let width = (k1 - k0) as f64 * big_r * cell;
            let height = station_z(mer, i1) - station_z(mer, i0);
            let below = o.z - station_z(mer, i0);
            let above = station_z(mer, i1) - o.z;
            let grow_z = height < width && (i0 > lo || i1 < hi);
            if grow_z {
                if (below <= above && i0 > lo) || i1 == hi {
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
        let hole = Hole {
            mark: nz.mark.clone(),
            part,
            seg,
            i0,
            i1,
            k0,
            a,
            theta,
            z: o.z,
            centre,
            big_r,
            r,
            wall,
            end: g.projection - flange,
            pad: nz.pad,
        };
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
    holes
}
