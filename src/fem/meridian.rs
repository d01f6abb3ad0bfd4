//! The mid-surface meridian of a vessel's envelope as one chain of exact pieces
//! (lines, circular and elliptical arcs from [`crate::operating::profile`]) from
//! the lower end to the upper end, and the stations the mesh rings stand on.
//!
//! Stations are placed by a size field along the meridian's arc length σ: the
//! target `size` away from junctions, `0.5·√(r·t)` within `√(r·t)` of every
//! junction (part ends and the tangent lines inside a head, where bending
//! stresses peak), the rim's circumferential spacing at a cap's rim, growing
//! linearly at slope [`GROWTH`] in between, so adjacent
//! elements differ by less than a factor 1.5. Each segment gets the element
//! count that integrates `1/h` over it (rounded up) and its stations
//! equidistribute that integral. Every station is an exact point of its piece;
//! where two parts' mid-surfaces miss each other at a junction (a change of
//! thickness, a cone offset normal to itself) the shared ring lies on the end of
//! the lower part and the gap, at most about half the thickness difference, is
//! the usual shell idealisation's.

use glam::{DVec2, DVec3};

use crate::operating::profile::{Lateral, Piece};

/// Slope of the size field away from a junction: h grows by this per mm of arc,
/// so an element of size h is followed by one of at most h·(1 + GROWTH)/(1 − GROWTH·…) < 1.5 h.
pub const GROWTH: f64 = 0.35;

/// Samples per segment of the arc-length tables.
const SAMPLES: usize = 400;

/// One oriented piece of the chain: parameter from `s0` to `s1`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Segment {
    /// The exact piece.
    pub piece: Piece,
    /// Parameter at the segment's start (chain order).
    pub s0: f64,
    /// Parameter at its end.
    pub s1: f64,
    /// Index of the part it belongs to (in the caller's part list).
    pub part: usize,
    /// Centre line of its cross-sections.
    pub centre: Lateral,
    /// Wall thickness, mm.
    pub thickness: f64,
}

impl Segment {
    /// (r, z) at parameter `s`.
    pub fn rz(&self, s: f64) -> DVec2 {
        let (r, z) = self.piece.point(s);
        DVec2::new(r.max(0.0), z)
    }

    /// The vessel-frame point at parameter `s`, angle `theta` (radians from +x).
    pub fn point(&self, s: f64, theta: f64) -> DVec3 {
        let rz = self.rz(s);
        let c = self.centre.at(rz.y);
        let (sin, cos) = theta.sin_cos();
        DVec3::new(c.x + rz.x * cos, c.y + rz.x * sin, rz.y)
    }

    /// The vessel-frame point over the plane offset `xy` from the centre line
    /// (a cap's projection: radius |xy|).
    pub fn point_over(&self, xy: DVec2) -> DVec3 {
        let s = self.piece.at_r(xy.length());
        let z = self.rz(s).y;
        let c = self.centre.at(z);
        DVec3::new(c.x + xy.x, c.y + xy.y, z)
    }
}

/// Span of one element along the meridian: segment and its parameter range.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Interval {
    /// Segment index.
    pub seg: usize,
    /// Parameter at the lower station.
    pub sa: f64,
    /// Parameter at the upper station.
    pub sb: f64,
}

/// A pole closed by a cap: the segment it lies on and the cap's rim radius.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Cap {
    /// Segment index.
    pub seg: usize,
    /// Radius of the rim (the first or last station), mm.
    pub radius: f64,
}

/// The stations of a chain.
#[derive(Clone, Debug, PartialEq)]
pub struct Meridian {
    /// The chain's segments, lower end first.
    pub segments: Vec<Segment>,
    /// Station positions: segment and parameter giving the ring (a junction
    /// station is the end of the lower segment).
    pub stations: Vec<(usize, f64)>,
    /// `stations.len() - 1` intervals.
    pub intervals: Vec<Interval>,
    /// Cap at the lower end (a pole), if any.
    pub start_cap: Option<Cap>,
    /// Cap at the upper end, if any.
    pub end_cap: Option<Cap>,
}

/// Orders the parts' pieces into one chain, lower end first. `parts` holds each
/// part's pieces (rim to rim or rim to pole, in the profile's order), with part
/// index, centre line and thickness.
pub fn chain(parts: &[(usize, Vec<Piece>, Lateral, f64)]) -> Vec<Segment> {
    let oriented = |pieces: &[Piece], part: usize, centre: Lateral, t: f64, flip: bool| {
        let mut out: Vec<Segment> = pieces
            .iter()
            .map(|p| {
                let (a, b) = p.range();
                Segment {
                    piece: *p,
                    s0: if flip { b } else { a },
                    s1: if flip { a } else { b },
                    part,
                    centre,
                    thickness: t,
                }
            })
            .collect();
        if flip {
            out.reverse();
        }
        out
    };
    let ends = |pieces: &[Piece]| -> (DVec2, DVec2) {
        let first = pieces[0];
        let last = pieces[pieces.len() - 1];
        let (a, _) = first.range();
        let (_, b) = last.range();
        (DVec2::from(first.point(a)), DVec2::from(last.point(b)))
    };
    let mut out: Vec<Segment> = Vec::new();
    let parts: Vec<_> = parts.iter().filter(|p| !p.1.is_empty()).collect();
    for (i, (part, pieces, centre, t)) in parts.iter().enumerate() {
        let (a, b) = ends(pieces);
        let flip = if let Some(last) = out.last() {
            let end = last.rz(last.s1);
            a.distance(end) > b.distance(end)
        } else if let Some(next) = parts.get(i + 1) {
            let (na, nb) = ends(&next.1);
            a.distance(na).min(a.distance(nb)) < b.distance(na).min(b.distance(nb))
        } else {
            false
        };
        out.extend(oriented(pieces, *part, *centre, *t, flip));
    }
    if let (Some(f), Some(l)) = (out.first(), out.last())
        && f.rz(f.s0).y > l.rz(l.s1).y
    {
        out.reverse();
        for s in &mut out {
            std::mem::swap(&mut s.s0, &mut s.s1);
        }
    }
    out
}

/// Cumulative arc length over `[s0, s1]` sampled at [`SAMPLES`] + 1 points:
/// (parameter, arc length) pairs.
pub(super) fn arc_table(seg: &Segment, s0: f64, s1: f64) -> Vec<(f64, f64)> {
    let mut out = Vec::with_capacity(SAMPLES + 1);
    let mut acc = 0.0;
    let mut prev = seg.rz(s0);
    out.push((s0, 0.0));
    for k in 1..=SAMPLES {
        let s = s0 + (s1 - s0) * k as f64 / SAMPLES as f64;
        let p = seg.rz(s);
        acc += p.distance(prev);
        prev = p;
        out.push((s, acc));
    }
    out
}

/// Whether (r, z) is on the axis (a pole), relative to `scale`.
fn on_axis(rz: DVec2, scale: f64) -> bool {
    rz.x <= 1e-9 * scale.max(1.0)
}

/// Places the stations of `segments` for element size `size`, on a mesh of
/// `divisions` circumferential divisions (a cap's rim is a junction whose size is the
/// rim's circumferential spacing, which the cap's outer layer also takes). A
/// pole's cap takes half its head's radius, at most `caps[0]` at the chain's
/// start and `caps[1]` at its end (room for off-centre nozzles' windows).
pub fn stations(segments: Vec<Segment>, size: f64, divisions: usize, caps: [f64; 2]) -> Meridian {
    let scale = segments
        .iter()
        .map(|s| s.rz(s.s0).x.max(s.rz(s.s1).x))
        .fold(0.0, f64::max);
    let mut segs = segments;
    // Poles: cut the cap off its segment where r = rim radius.
    let cap_radius = |seg: &Segment, rim: f64| -> f64 {
        let other = seg.rz(seg.s0).x.max(seg.rz(seg.s1).x);
        (0.5 * rim).min(0.9 * other)
    };
    let part_rim = |segs: &[Segment], part: usize| -> f64 {
        segs.iter()
            .filter(|s| s.part == part)
            .map(|s| s.rz(s.s0).x.max(s.rz(s.s1).x))
            .fold(0.0, f64::max)
    };
    let mut start_cap = None;
    let mut end_cap = None;
    if let Some(first) = segs.first().copied()
        && on_axis(first.rz(first.s0), scale)
    {
        let rc = cap_radius(&first, part_rim(&segs, first.part)).min(caps[0]);
        segs[0].s0 = first.piece.at_r(rc);
        start_cap = Some(Cap { seg: 0, radius: rc });
    }
    let n = segs.len();
    if let Some(last) = segs.last().copied()
        && on_axis(last.rz(last.s1), scale)
    {
        let rc = cap_radius(&last, part_rim(&segs, last.part)).min(caps[1]);
        segs[n - 1].s1 = last.piece.at_r(rc);
        end_cap = Some(Cap {
            seg: n - 1,
            radius: rc,
        });
    }
    let tables: Vec<Vec<(f64, f64)>> = segs.iter().map(|s| arc_table(s, s.s0, s.s1)).collect();
    let lengths: Vec<f64> = tables
        .iter()
        .map(|t| t.last().map_or(0.0, |x| x.1))
        .collect();
    // Junctions: every interior segment boundary, at arc position σ.
    let mut junctions = Vec::new();
    let mut sigma = 0.0;
    for (k, seg) in segs.iter().enumerate() {
        sigma += lengths[k];
        if k + 1 < segs.len() {
            let r = seg.rz(seg.s1).x;
            let t = seg.thickness.min(segs[k + 1].thickness).max(1e-3);
            let rt = (r.max(t) * t).sqrt();
            junctions.push((sigma, 0.5 * rt, rt));
        }
    }
    let spacing =
        |cap: Option<Cap>| cap.map(|c| std::f64::consts::TAU * c.radius / divisions as f64);
    if let Some(w) = spacing(start_cap) {
        junctions.push((0.0, w, 0.0));
    }
    if let Some(w) = spacing(end_cap) {
        junctions.push((sigma, w, 0.0));
    }
    let h = |x: f64| -> f64 {
        junctions
            .iter()
            .map(|&(sj, hj, zone)| hj.min(size) + GROWTH * ((x - sj).abs() - zone).max(0.0))
            .fold(size, f64::min)
    };
    let mut stations = vec![(0usize, segs[0].s0)];
    let mut intervals = Vec::new();
    let mut start = 0.0;
    for (k, table) in tables.iter().enumerate() {
        // ∫ dσ / h over the segment, on the table's samples.
        let mut cum = vec![0.0];
        for w in table.windows(2) {
            let mid = start + 0.5 * (w[0].1 + w[1].1);
            let last = *cum.last().unwrap_or(&0.0);
            cum.push(last + (w[1].1 - w[0].1) / h(mid));
        }
        let total = *cum.last().unwrap_or(&0.0);
        let count = (total - 1e-6).ceil().max(1.0) as usize;
        let mut prev = segs[k].s0;
        for i in 1..=count {
            let s = if i == count {
                segs[k].s1
            } else {
                let target = total * i as f64 / count as f64;
                let j = cum.partition_point(|&c| c < target).clamp(1, cum.len() - 1);
                let f = (target - cum[j - 1]) / (cum[j] - cum[j - 1]).max(f64::MIN_POSITIVE);
                table[j - 1].0 + f * (table[j].0 - table[j - 1].0)
            };
            intervals.push(Interval {
                seg: k,
                sa: prev,
                sb: s,
            });
            stations.push((k, s));
            prev = s;
        }
        start += lengths[k];
    }
    Meridian {
        segments: segs,
        stations,
        intervals,
        start_cap,
        end_cap,
    }
}

/// The largest distance, mm, between the mid-surface taken for an ellipsoidal
/// head and its true mid-surface. The head's outside is the ellipse of
/// semi-axes `a` (radial) and `b` (axial) revolved; its true mid-surface is that
/// surface offset inwards by `h` = t/2 along its normal (not an ellipsoid); the
/// mesh takes the ellipsoid of semi-axes a − h, b − h instead, which meets it
/// exactly at the equator and the pole. Both are surfaces of revolution, so the
/// distance is that of their meridians, and both meridians are convex (the
/// offset has no cusp while h < b²/a, the least radius of curvature), so it is
/// the largest difference of their support functions over the normal angle β:
/// with c = cos²β, H(c) = √(a²c + b²(1 − c)) for the outside (H − h for the
/// true mid-surface) and H′(c) = √((a−h)²c + (b−h)²(1 − c)) for the one taken.
/// H − h − H′ vanishes at c = 0 and 1 and has one extremum, where
/// H′ = k·H with k = (a + b − 2h)/(a + b), at
/// c* = (k²b² − (b − h)²) / ((a² − b²)·k·(1 − k)); the bound is
/// |(1 − k)·H(c*) − h|. For a 2:1 head of OD 1000, t = 10 (a = 500, b = 250,
/// h = 5) it is 0.29 mm, 0.029 t; exact (0) for a sphere. `None` when h ≥ b²/a
/// or a, b, h are not positive.
pub fn ellipsoid_mid_surface_error(a: f64, b: f64, h: f64) -> Option<f64> {
    if !(a > 0.0 && b > 0.0 && h > 0.0) || h >= b * b / a || h >= a * a / b {
        return None;
    }
    if (a - b).abs() <= 1e-12 * a.max(b) {
        return Some(0.0);
    }
    let k = (a + b - 2.0 * h) / (a + b);
    let c = ((k * k * b * b - (b - h).powi(2)) / ((a * a - b * b) * k * (1.0 - k))).clamp(0.0, 1.0);
    let outside = (a * a * c + b * b * (1.0 - c)).sqrt();
    let inside = ((a - h).powi(2) * c + (b - h).powi(2) * (1.0 - c)).sqrt();
    Some((outside - h - inside).abs())
}
