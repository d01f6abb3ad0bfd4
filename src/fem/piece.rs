//! One piece of a vessel's FE mesh, meshed apart from the others: an envelope
//! part (course, head, cone, centre neck) with the rings of its stations, its
//! caps, its windows' nozzles (ring and neck), the saddles standing under it
//! and its pads; or the skirt, hanging from the envelope's ring at its top.
//!
//! A piece is meshed from its [`PieceKey`] alone (with the plan's meridian,
//! read only at the stations and segments the key holds), so equal keys give
//! equal pieces bit for bit and [`super::cache::FemCache`] reuses a piece
//! while its key is unchanged. The nodes of the rings it shares with its
//! neighbours carry a [`NodeKey`], by which [`super::assemble`] welds them.
//! In the data flow: [`super::envelope::plan`] → [`inputs`] → the cache
//! ([`mesh`] for what changed) → [`super::assemble`].

use std::f64::consts::TAU;

use glam::{DVec2, DVec3};

use super::builder::{Builder, NodeKey};
use super::envelope::Plan;
use super::head_nozzle::CentreNeck;
use super::meridian::{Cap, Interval, Meridian, Segment};
use super::nozzle::PadSite;
use super::saddle::SaddleShell;
use super::skirt::SkirtShell;
use super::window::Hole;
use super::{FeMesh, FePart};

/// Everything a piece is meshed from. Stations, segments and intervals carry
/// their index in the vessel's meridian.
#[derive(Clone, Debug, PartialEq)]
pub struct PieceKey {
    /// Vessel tag (in part and set names).
    pub tag: String,
    /// Whether elements are quadratic.
    pub quadratic: bool,
    /// Target element size, mm.
    pub size: f64,
    /// Circumferential divisions.
    pub divisions: usize,
    /// How many parts the envelope has (the parts a piece adds follow them).
    pub part_count: usize,
    /// The envelope part the piece meshes, by index; `None` for the skirt.
    pub part: Option<usize>,
    /// That part (a pad's thickness adds to its own).
    pub own: Option<FePart>,
    /// The stations whose rings the piece holds.
    pub stations: Vec<(usize, (usize, f64))>,
    /// The segments those stations and the intervals lie on.
    pub segments: Vec<(usize, Segment)>,
    /// The element rows the piece meshes.
    pub intervals: Vec<(usize, Interval)>,
    /// Whether the meridian's first and last station carry a cap's rim
    /// (their nodes get plane coordinates).
    pub capped: [bool; 2],
    /// The caps the piece closes: at the chain's start, at its end.
    pub caps: [Option<Cap>; 2],
    /// Open ends of the envelope the piece holds: its first, its last station.
    pub open: [bool; 2],
    /// Stations at tangent lines (between two segments) among its own.
    pub tangents: Vec<usize>,
    /// Its nozzles' windows.
    pub holes: Vec<Hole>,
    /// Centre necks whose open end is the piece's end ring.
    pub centre_necks: Vec<CentreNeck>,
    /// Saddles under it.
    pub saddles: Vec<SaddleShell>,
    /// Pads on it.
    pub pads: Vec<PadSite>,
    /// The skirt and the station of its top ring.
    pub skirt: Option<(SkirtShell, usize)>,
}

/// A meshed piece: its mesh in the vessel frame, node indices its own, parts
/// the envelope's followed by those it adds (necks, pads, saddle plates,
/// skirt), and the key of each node shared across pieces.
#[derive(Clone, Debug, PartialEq)]
pub struct Piece {
    /// The mesh.
    pub mesh: FeMesh,
    /// How many of `mesh.parts` are the envelope's.
    pub envelope_parts: usize,
    /// Each node's key, if it is a ring node or a mid-side node between two.
    pub keys: Vec<Option<NodeKey>>,
}

/// The pieces of `plan`: its name (the part id) and key, one per envelope
/// part, then the skirt.
pub fn inputs(plan: &Plan) -> Vec<(String, PieceKey)> {
    let mer = &plan.mer;
    let last = mer.stations.len() - 1;
    let base = |part: Option<usize>| PieceKey {
        tag: plan.tag.clone(),
        quadratic: plan.quadratic,
        size: plan.size,
        divisions: plan.divisions,
        part_count: plan.parts.len(),
        part,
        own: part.map(|p| plan.parts[p].clone()),
        stations: Vec::new(),
        segments: Vec::new(),
        intervals: Vec::new(),
        capped: [mer.start_cap.is_some(), mer.end_cap.is_some()],
        caps: [None, None],
        open: [false, false],
        tangents: Vec::new(),
        holes: Vec::new(),
        centre_necks: Vec::new(),
        saddles: Vec::new(),
        pads: Vec::new(),
        skirt: None,
    };
    let with_stations = |key: &mut PieceKey, range: std::ops::RangeInclusive<usize>| {
        for i in range {
            let (seg, s) = mer.stations[i];
            key.stations.push((i, (seg, s)));
            if !key.segments.iter().any(|x| x.0 == seg) {
                key.segments.push((seg, mer.segments[seg]));
            }
        }
    };
    let mut out = Vec::new();
    for (p, part) in plan.parts.iter().enumerate() {
        let rows: Vec<usize> = (0..mer.intervals.len())
            .filter(|&i| mer.segments[mer.intervals[i].seg].part == p)
            .collect();
        let (Some(&first), Some(&end)) = (rows.first(), rows.last()) else {
            continue;
        };
        let mut key = base(Some(p));
        with_stations(&mut key, first..=end + 1);
        for &i in &rows {
            let iv = mer.intervals[i];
            key.intervals.push((i, iv));
            if !key.segments.iter().any(|x| x.0 == iv.seg) {
                key.segments.push((iv.seg, mer.segments[iv.seg]));
            }
        }
        key.tangents = (first.max(1)..=end + 1)
            .filter(|&i| i < last && mer.intervals[i - 1].seg != mer.intervals[i].seg)
            .collect();
        let on_part = |cap: Option<Cap>| cap.filter(|c| mer.segments[c.seg].part == p);
        key.caps = [on_part(mer.start_cap), on_part(mer.end_cap)];
        key.open = [
            first == 0 && mer.start_cap.is_none(),
            end + 1 == last && mer.end_cap.is_none(),
        ];
        key.holes = plan.holes.iter().filter(|h| h.part == p).cloned().collect();
        key.centre_necks = plan
            .centre_necks
            .iter()
            .filter(|c| c.part == p)
            .cloned()
            .collect();
        key.saddles = plan
            .saddles
            .iter()
            .filter(|s| s.1 == p)
            .map(|s| s.0.clone())
            .collect();
        key.pads = plan
            .holes
            .iter()
            .filter_map(|h| h.pad_site())
            .chain(plan.centre_necks.iter().filter_map(|c| c.pad_site()))
            .filter(|s| s.part == p)
            .collect();
        out.push((part.id.clone(), key));
    }
    if let Some((skirt, i)) = &plan.skirt {
        let mut key = base(None);
        with_stations(&mut key, i.saturating_sub(1)..=(i + 1).min(last));
        key.skirt = Some((skirt.clone(), *i));
        out.push((skirt.id.clone(), key));
    }
    out
}

/// Meshes the piece of `key` on the meridian `mer` of its plan.
pub fn mesh(key: &PieceKey, mer: &Meridian) -> Piece {
    let n = key.divisions;
    let last = mer.stations.len() - 1;
    let theta = |k: f64| TAU * k / n as f64;
    let mut b = Builder::new(key.quadratic);
    // The envelope's parts by index: the piece's own, and the others' slots,
    // which it never reads (their elements are other pieces') and
    // [`super::assemble`] replaces with the plan's.
    b.mesh.parts = (0..key.part_count)
        .map(|j| match (&key.own, key.part == Some(j)) {
            (Some(own), true) => own.clone(),
            _ => FePart {
                name: String::new(),
                id: String::new(),
                thickness: f64::NAN,
                offset: 0.0,
            },
        })
        .collect();
    // Rings of corner nodes; the rims of caps carry plane coordinates.
    let mut rings: Vec<Vec<usize>> = vec![Vec::new(); mer.stations.len()];
    for &(i, (seg, s)) in &key.stations {
        let segment = mer.segments[seg];
        let capped = (i == 0 && key.capped[0]) || (i == last && key.capped[1]);
        rings[i] = (0..n)
            .map(|k| {
                let th = theta(k as f64);
                let r = segment.rz(s).x;
                let plane = capped.then(|| DVec2::new(th.cos(), th.sin()) * r);
                b.ring_node(segment.point(s, th), plane, i, k)
            })
            .collect();
    }
    for &i in &key.tangents {
        b.mesh.junctions.extend(rings[i].iter().copied());
    }
    for &(i, iv) in &key.intervals {
        let seg = mer.segments[iv.seg];
        let (lower, upper) = (mer.stations[i], mer.stations[i + 1]);
        let smid = 0.5 * (iv.sa + iv.sb);
        for k in 0..n {
            if key.holes.iter().any(|h| h.covers(i, k, n)) {
                continue;
            }
            let k1 = (k + 1) % n;
            let c = [rings[i][k], rings[i][k1], rings[i + 1][k1], rings[i + 1][k]];
            let segs = &mer.segments;
            b.quad(seg.part, c, &mut |b, x, y| {
                // Which edge: along a ring (same station) or along the meridian.
                let (kx, ky) = (
                    c.iter().position(|&q| q == x).unwrap_or(0),
                    c.iter().position(|&q| q == y).unwrap_or(0),
                );
                let station = |corner: usize| if corner < 2 { lower } else { upper };
                let kk = |corner: usize| if corner == 0 || corner == 3 { k } else { k + 1 };
                if station(kx) == station(ky) && kx / 2 == ky / 2 {
                    let (sg, s) = station(kx);
                    let th = theta(kk(kx).min(kk(ky)) as f64 + 0.5);
                    b.mid(x, y, || segs[sg].point(s, th))
                } else {
                    let th = theta(kk(kx) as f64);
                    b.mid(x, y, || seg.point(smid, th))
                }
            });
        }
    }
    if let Some(cap) = key.caps[0] {
        let seg = mer.segments[cap.seg];
        let ring = rings[0].clone();
        super::cap::cap(&mut b, &ring, cap.radius, seg.part, false, &|p| {
            seg.point_over(p)
        });
    }
    if key.open[0] {
        b.mesh.boundary.extend(rings[0].iter().copied());
    }
    if let Some(cap) = key.caps[1] {
        let seg = mer.segments[cap.seg];
        let ring = rings[last].clone();
        super::cap::cap(&mut b, &ring, cap.radius, seg.part, true, &|p| {
            seg.point_over(p)
        });
    }
    if key.open[1] {
        b.mesh.boundary.extend(rings[last].iter().copied());
    }
    for hole in &key.holes {
        let end = super::nozzle::mesh(&mut b, hole, mer, &rings, key.size, &key.tag);
        b.mesh.necks.push(end);
    }
    for neck in &key.centre_necks {
        let ring = if neck.at_start {
            rings[0].clone()
        } else {
            rings[last].clone()
        };
        let mids = if b.quadratic {
            (0..ring.len())
                .map(|j| {
                    let (x, y) = (ring[j], ring[(j + 1) % ring.len()]);
                    b.mid(x, y, || DVec3::ZERO)
                })
                .collect()
        } else {
            Vec::new()
        };
        b.mesh.necks.push(neck.end(ring, mids));
    }
    if let Some((s, i)) = &key.skirt {
        skirt_shell(&mut b, s, *i, mer, &rings, key.size, &key.tag);
    }
    for s in &key.saddles {
        if let Err(note) =
            super::saddle::attach(&mut b, s, mer, &rings, &key.holes, key.size, &key.tag)
        {
            b.mesh.notes.push(note);
        }
    }
    super::nozzle::pads(&mut b, &key.pads, &key.tag);
    let (mesh, keys) = b.finish();
    Piece {
        mesh,
        envelope_parts: key.part_count,
        keys,
    }
}

/// Hangs skirt `s` from the ring of `mer` at station `i` (its top), its base
/// an open boundary and the part structural.
fn skirt_shell(
    b: &mut Builder,
    s: &SkirtShell,
    i: usize,
    mer: &Meridian,
    rings: &[Vec<usize>],
    size: f64,
    tag: &str,
) {
    let at = |i: usize| {
        let (seg, p) = mer.stations[i];
        mer.segments[seg].rz(p)
    };
    let nodes = &b.mesh.nodes;
    let first = [i.checked_sub(1), (i + 1 < rings.len()).then_some(i + 1)]
        .into_iter()
        .flatten()
        .map(|j| nodes[rings[i][0]].distance(nodes[rings[j][0]]))
        .fold(size, f64::min);
    let (seg, _) = mer.stations[i];
    let c = mer.segments[seg].centre.at(s.top);
    let top = super::skirt::TopRing {
        nodes: rings[i].clone(),
        centre: DVec3::new(c.x, c.y, s.top),
        radius: at(i).x,
        first,
    };
    let (part, base) = super::skirt::mesh(b, s, &top, size, tag);
    b.mesh.structural.push(part);
    b.mesh.boundary.extend(base);
}
