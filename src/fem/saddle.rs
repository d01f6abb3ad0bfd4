//! A horizontal vessel's saddles as shell parts of the model, so the vessel
//! rests where it really does (each saddle's base plate on the foundation)
//! rather than on a held arc of the shell.
//!
//! The course is meshed with node lines where a saddle meets it: the chain is
//! split at the saddle's mid-plane (the web's plane) and at the two edges of
//! its top plate, z ± width/2, so rings stand there (graded as junctions,
//! 0.5·√(R·t), where the horn stresses peak), and the horns fall on the
//! envelope's circumferential node columns: the contact angle is taken to the
//! nearest whole number of divisions each side of the bottom (noted when that
//! changes it; n a multiple of 24 keeps 120° and 150° exact).
//!
//! The shell idealisation (the one [`super::nozzle::pads`] uses for pads):
//! - the saddle's top plate (as thick as the web) and a design's wear plate
//!   are bonded to the shell: the course's elements under the top plate (the
//!   band between the two edge rings, horn to horn) become the part
//!   `TAG/ID/wear plate` of the shell's plus the plates' thickness; a design's
//!   wear plate reaches R/10 beyond each horn ([`crate::calc::zick`]'s
//!   condition for counting it), those elements the part `TAG/ID/doubler`;
//! - the web is a plane shell in the saddle's mid-plane from the shell's
//!   mid-surface (its top edge *is* the ring's arc from horn to horn, shared
//!   node for node, mid-side nodes included) down to the base plate's
//!   mid-plane, its sides straight from the horns to the base plate's ends;
//! - the base plate is a plane shell at its mid-plane, `base_length` across
//!   the vessel and `base_width` along it, its middle line shared with the
//!   web's bottom edge. Held on all its nodes (see [`super::conditions`]).
//!
//! Web and base plate are structural (no pressure, no liquid); they carry
//! their own weight under gravity.

use std::f64::consts::{FRAC_PI_2, TAU};

use glam::DVec3;

use super::builder::Builder;
use super::meridian::{self, GROWTH};
use super::window::Hole;
use super::{FePart, grading};
use crate::constraints::ResolvedVessel;
use crate::design::{PartDesign, VesselDesign, VesselKind};
use crate::parts::PartGeometry;

/// A saddle of the vessel, in the vessel frame (local −Y down, +Z the axis).
#[derive(Clone, Debug, PartialEq)]
pub struct SaddleShell {
    /// Part id.
    pub id: String,
    /// The web's plane: axial position, vessel frame, mm.
    pub z: f64,
    /// Half the contact angle, radians.
    pub half: f64,
    /// Width of the top plate along the axis, mm.
    pub width: f64,
    /// From the axis down to the bearing plane, mm.
    pub height: f64,
    /// Web (and top plate) thickness, mm.
    pub web: f64,
    /// Base plate length across the vessel, mm.
    pub base_length: f64,
    /// Base plate width along the axis, mm.
    pub base_width: f64,
    /// Base plate thickness, mm.
    pub base_thickness: f64,
    /// A design's wear plate on the shell, mm.
    pub wear_plate: Option<f64>,
}

impl SaddleShell {
    /// The axial positions where the course needs a ring: the top plate's
    /// edges and the web's plane.
    pub fn planes(&self) -> [f64; 3] {
        [self.z - self.width / 2.0, self.z, self.z + self.width / 2.0]
    }
}

/// The saddles of horizontal vessel `design` (resolved as `resolved`); none
/// for other kinds.
pub fn find(design: &VesselDesign, resolved: &ResolvedVessel) -> Vec<SaddleShell> {
    if design.kind != VesselKind::Horizontal {
        return Vec::new();
    }
    resolved
        .parts
        .iter()
        .filter_map(|part| match &part.geometry {
            PartGeometry::Saddle(s) => Some(SaddleShell {
                id: part.id.clone(),
                z: part.frame.translation.z,
                half: (s.contact_angle.to_radians() / 2.0).min(FRAC_PI_2),
                width: s.width,
                height: s.height,
                web: s.web_thickness,
                base_length: s.base_length,
                base_width: s.base_width,
                base_thickness: s.base_thickness,
                wear_plate: design.parts.iter().find_map(|d| match d {
                    PartDesign::Saddle(d) if d.id == part.id => d.wear_plate,
                    _ => None,
                }),
            }),
            _ => None,
        })
        .collect()
}

/// The parts a meshed saddle adds, by their id's suffix after `ID/`.
pub const WEB: &str = "web";
/// See [`WEB`].
pub const BASE_PLATE: &str = "base plate";
/// See [`WEB`].
pub const WEAR_PLATE: &str = "wear plate";
/// See [`WEB`].
pub const DOUBLER: &str = "doubler";

/// The stations of `mer` at the planes of saddle `s` (top plate's edges and
/// web), if it has rings at all three.
fn stations(s: &SaddleShell, mer: &meridian::Meridian) -> Option<[usize; 3]> {
    let at = |i: usize| {
        let (seg, p) = mer.stations[i];
        mer.segments[seg].rz(p)
    };
    let tol = 1e-6 * s.z.abs().max(1.0);
    let station = |z: f64| (0..mer.stations.len()).find(|&i| (at(i).y - z).abs() <= tol);
    let [Some(a), Some(i), Some(c)] = s.planes().map(station) else {
        return None;
    };
    Some([a, i, c])
}

/// The part (index into the envelope's parts) of the course under saddle
/// `s`: that of the first element row under its top plate; `None` when
/// `mer` has no rings at the plate's edges and web.
pub fn host(s: &SaddleShell, mer: &meridian::Meridian) -> Option<usize> {
    let [a, _, c] = stations(s, mer)?;
    let iv = mer.intervals.get(a.min(c))?;
    Some(mer.segments[iv.seg].part)
}

/// Meshes saddle `s` into `b` on the envelope of `mer` (corner rings
/// `rings`, `n` divisions round, windows `holes`) at element size `size`.
/// Returns why the saddle was left out, if it was.
pub fn attach(
    b: &mut Builder,
    s: &SaddleShell,
    mer: &meridian::Meridian,
    rings: &[Vec<usize>],
    holes: &[Hole],
    size: f64,
    tag: &str,
) -> Result<(), String> {
    let n = rings.iter().map(Vec::len).max().unwrap_or(0);
    let at = |i: usize| {
        let (seg, p) = mer.stations[i];
        mer.segments[seg].rz(p)
    };
    let Some([i0, i, i1]) = stations(s, mer) else {
        return Err(format!(
            "saddle {} left out: the envelope has no rings at its plate's edges and web",
            s.id
        ));
    };
    let (i0, i1) = (i0.min(i1), i0.max(i1));
    let host = mer.segments[mer.intervals[i0].seg];
    if (i0..i1).any(|j| mer.segments[mer.intervals[j].seg].part != host.part) {
        return Err(format!(
            "saddle {} left out: its top plate spans two parts",
            s.id
        ));
    }
    let radius = at(i).x;
    let step = TAU / n as f64;
    // Horns: whole divisions each side of the bottom (angle 3π/2, node 3n/4).
    let bottom = 3 * n / 4;
    let hk = ((s.half / step).round() as usize).clamp(1, n / 4);
    let wk = match s.wear_plate {
        Some(_) => (((s.half + 0.1) / step).round() as usize).clamp(hk, n / 4),
        None => hk,
    };
    if holes
        .iter()
        .any(|h| (i0..i1).any(|j| (bottom - wk..bottom + wk).any(|k| h.covers(j, k, n))))
    {
        return Err(format!(
            "saddle {} left out: a nozzle's window reaches under it",
            s.id
        ));
    }
    let used = 2.0 * hk as f64 * step;
    if (used - 2.0 * s.half).abs() > 1e-9 {
        b.mesh.notes.push(format!(
            "saddle {}: contact angle {:.2}° meshed as {:.2}° ({} of {n} divisions)",
            s.id,
            (2.0 * s.half).to_degrees(),
            used.to_degrees(),
            2 * hk
        ));
    }
    // The band under the top plate (and the wear plate beyond the horns).
    let host_t = host.thickness;
    let plate = s.wear_plate.unwrap_or(0.0);
    let under = b.mesh.parts.len();
    b.mesh.parts.push(FePart {
        name: format!("{tag}/{}/{WEAR_PLATE}", s.id),
        id: format!("{}/{WEAR_PLATE}", s.id),
        thickness: host_t + s.web + plate,
        offset: -(s.web + plate) / (2.0 * (host_t + s.web + plate)),
    });
    let beyond = (wk > hk).then(|| {
        b.mesh.parts.push(FePart {
            name: format!("{tag}/{}/{DOUBLER}", s.id),
            id: format!("{}/{DOUBLER}", s.id),
            thickness: host_t + plate,
            offset: -plate / (2.0 * (host_t + plate)),
        });
        b.mesh.parts.len() - 1
    });
    // An element's column, if it is a plain quadrilateral of the band.
    let column = |nodes: &[usize]| -> Option<usize> {
        let j = (i0..i1).find(|&j| rings[j].contains(&nodes[0]))?;
        let k = rings[j].iter().position(|&q| q == nodes[0])?;
        let k1 = (k + 1) % n;
        (nodes[1] == rings[j][k1] && nodes[2] == rings[j + 1][k1] && nodes[3] == rings[j + 1][k])
            .then_some(k)
    };
    for e in b.mesh.elements.iter_mut() {
        if e.part != host.part {
            continue;
        }
        let Some(k) = column(&e.nodes) else {
            continue;
        };
        if (bottom - hk..bottom + hk).contains(&k) {
            e.part = under;
        } else if let Some(p) = beyond
            && (bottom - wk..bottom + wk).contains(&k)
        {
            e.part = p;
        }
    }
    // The web: columns j = 0..=m under the arc's nodes, rows graded from the
    // shell's ring spacing at the arc to the base plate's at the bottom.
    let m = 2 * hk;
    let centre = {
        let (seg, _) = mer.stations[i];
        let c = mer.segments[seg].centre.at(s.z);
        DVec3::new(c.x, c.y, s.z)
    };
    let arc: Vec<usize> = (0..=m).map(|j| rings[i][bottom - hk + j]).collect();
    let base_y = -(s.height - s.base_thickness / 2.0);
    let base_at = |x: f64, z: f64| centre + DVec3::new(x, base_y, z - s.z);
    let across = s.base_length / m as f64;
    let foot: Vec<DVec3> = (0..=m)
        .map(|j| base_at(-s.base_length / 2.0 + across * j as f64, s.z))
        .collect();
    let nodes = &b.mesh.nodes;
    let heights: Vec<f64> = (0..=m).map(|j| nodes[arc[j]].distance(foot[j])).collect();
    let (lo, hi) = heights
        .iter()
        .fold((f64::INFINITY, 0.0f64), |(a, c), &h| (a.min(h), c.max(h)));
    if lo <= 1e-6 * radius {
        return Err(format!(
            "saddle {} left out: its base plate touches the shell",
            s.id
        ));
    }
    // Ring spacing along the axis next to the web's plane.
    let first = [i.checked_sub(1), (i + 1 < rings.len()).then_some(i + 1)]
        .into_iter()
        .flatten()
        .map(|j| nodes[rings[i][bottom]].distance(nodes[rings[j][bottom]]))
        .fold(size, f64::min);
    // Columns scale the rows of the geometric mean height: neighbours across
    // the arc then differ by at most √(hi/lo)^½ in √area.
    let mean = (lo * hi).sqrt();
    let rows = grading::layers_at(mean, first, across.min(size), size, GROWTH);
    let q = rows.len() - 1;
    let web = b.mesh.parts.len();
    b.mesh.parts.push(FePart {
        name: format!("{tag}/{}/{WEB}", s.id),
        id: format!("{}/{WEB}", s.id),
        thickness: s.web,
        offset: 0.0,
    });
    let web_point = |b: &Builder, r: f64, j: usize| {
        let top = b.mesh.nodes[arc[j]];
        top + (foot[j] - top) * r
    };
    let mut grid: Vec<Vec<usize>> = vec![arc.clone()];
    for &r in &rows[1..] {
        let row: Vec<usize> = (0..=m)
            .map(|j| {
                let p = web_point(b, r, j);
                b.node(p, None)
            })
            .collect();
        grid.push(row);
    }
    // Normals: a web faces away from midspan (−z corners this way round), a
    // base plate faces the foundation, as the saddle's patches do.
    let (z_lo, z_hi) = (0..mer.stations.len())
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, c), j| {
            (a.min(at(j).y), c.max(at(j).y))
        });
    let towards_minus = s.z <= 0.5 * (z_lo + z_hi);
    for r in 0..q {
        for j in 0..m {
            let c = if towards_minus {
                [
                    grid[r][j],
                    grid[r][j + 1],
                    grid[r + 1][j + 1],
                    grid[r + 1][j],
                ]
            } else {
                [
                    grid[r][j],
                    grid[r + 1][j],
                    grid[r + 1][j + 1],
                    grid[r][j + 1],
                ]
            };
            b.quad(web, c, &mut |b, x, y| {
                let (px, py) = (b.mesh.nodes[x], b.mesh.nodes[y]);
                b.mid(x, y, || 0.5 * (px + py))
            });
        }
    }
    // Sides of the web below the arc: open edges.
    for row in &grid[1..] {
        b.mesh.boundary.push(row[0]);
        b.mesh.boundary.push(row[m]);
    }
    b.mesh.boundary.push(arc[0]);
    b.mesh.boundary.push(arc[m]);
    // The base plate: the web's bottom row is its middle line.
    let half_rows = ((s.base_width / 2.0) / across.min(size)).ceil().max(1.0) as usize;
    let base = b.mesh.parts.len();
    b.mesh.parts.push(FePart {
        name: format!("{tag}/{}/{BASE_PLATE}", s.id),
        id: format!("{}/{BASE_PLATE}", s.id),
        thickness: s.base_thickness,
        offset: 0.0,
    });
    let mut plate: Vec<Vec<usize>> = Vec::with_capacity(2 * half_rows + 1);
    for r in 0..=2 * half_rows {
        if r == half_rows {
            plate.push(grid[q].clone());
            continue;
        }
        let z = s.z - s.base_width / 2.0 + s.base_width * r as f64 / (2 * half_rows) as f64;
        plate.push(
            (0..=m)
                .map(|j| b.node(base_at(-s.base_length / 2.0 + across * j as f64, z), None))
                .collect(),
        );
    }
    for r in 0..2 * half_rows {
        for j in 0..m {
            let c = [
                plate[r][j],
                plate[r][j + 1],
                plate[r + 1][j + 1],
                plate[r + 1][j],
            ];
            b.quad(base, c, &mut |b, x, y| {
                let (px, py) = (b.mesh.nodes[x], b.mesh.nodes[y]);
                b.mid(x, y, || 0.5 * (px + py))
            });
        }
    }
    let last = 2 * half_rows;
    b.mesh.boundary.extend(plate[0].iter().copied());
    b.mesh.boundary.extend(plate[last].iter().copied());
    b.mesh
        .boundary
        .extend(plate.iter().flat_map(|row| [row[0], row[m]]));
    b.mesh.structural.push(web);
    b.mesh.structural.push(base);
    Ok(())
}
