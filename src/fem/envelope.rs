//! The conforming shell mesh of a vessel's pressure envelope: the stations of
//! [`super::meridian`] swept about the axis into rings of quadrilaterals, one
//! circumferential division count for the whole vessel (so every junction ring
//! is shared node for node), poles closed by [`super::cap`]. Corner and
//! mid-side nodes are exact points of the mid-surface: mid-side nodes at the
//! parameter midpoint of their piece and the angle midpoint.

use std::f64::consts::TAU;

use glam::{DVec2, DVec3};

use super::builder::Builder;
use super::meridian::{self, Segment};
use super::{FeMesh, FePart, FemError};
use crate::constraints::{ResolvedVessel, stack_of};
use crate::design::VesselDesign;
use crate::operating::profile::{Surface, stack_profile};

/// Meshing options.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FemOptions {
    /// Target element size away from junctions, mm (`None`: √(R·t) of the
    /// widest part, R its mid-surface radius).
    pub size: Option<f64>,
    /// Element order: 1 (S4R) or 2 (S8R).
    pub order: u8,
}

impl Default for FemOptions {
    fn default() -> Self {
        FemOptions {
            size: None,
            order: 2,
        }
    }
}

/// The part list and the chain of a vessel's envelope.
fn parts_and_chain(
    design: &VesselDesign,
    resolved: &ResolvedVessel,
) -> Result<(Vec<FePart>, Vec<Segment>), FemError> {
    let stack = stack_of(design, resolved);
    let horizontal = design.kind == crate::design::VesselKind::Horizontal;
    let mut parts = Vec::new();
    let mut pieces = Vec::new();
    for sp in &stack {
        let one =
            stack_profile(std::slice::from_ref(sp), Surface::Middle, horizontal).map_err(|e| {
                FemError::Profile {
                    vessel: design.tag.clone(),
                    message: e.to_string(),
                }
            })?;
        if one.pieces.is_empty() {
            continue;
        }
        if sp.thickness <= 0.0 {
            let index = design
                .parts
                .iter()
                .position(|p| p.id() == sp.id)
                .unwrap_or(0);
            return Err(FemError::NoThickness {
                vessel: design.tag.clone(),
                index,
                id: sp.id.to_string(),
            });
        }
        let k = parts.len();
        parts.push(FePart {
            name: format!("{}/{}", design.tag, sp.id),
            id: sp.id.to_string(),
            thickness: sp.thickness,
            offset: 0.0,
        });
        pieces.push((
            k,
            one.pieces.iter().map(|p| p.0).collect::<Vec<_>>(),
            one.centre(0),
            sp.thickness,
        ));
    }
    if parts.is_empty() {
        return Err(FemError::Empty {
            vessel: design.tag.clone(),
        });
    }
    Ok((parts, meridian::chain(&pieces)))
}

/// The conforming shell mesh of the pressure envelope (courses, reducers,
/// heads) of `design`, resolved as `resolved`, in the plant frame.
///
/// # Errors
///
/// [`FemError`] for a part without thickness, a wall too thick for its shape,
/// a vessel with nothing to mesh, or options out of range.
pub fn build_envelope(
    design: &VesselDesign,
    resolved: &ResolvedVessel,
    options: &FemOptions,
) -> Result<FeMesh, FemError> {
    if !matches!(options.order, 1 | 2) {
        return Err(FemError::Option {
            field: "order",
            value: options.order.to_string(),
            rule: "element order is 1 (S4R) or 2 (S8R)".into(),
        });
    }
    let (mut parts, mut chain) = parts_and_chain(design, resolved)?;
    let mut notes = Vec::new();
    let centre_necks =
        super::head_nozzle::join(resolved, &mut chain, &mut parts, &design.tag, &mut notes);
    let mut skirt = super::skirt::find(resolved);
    if let Some(s) = &skirt
        && !super::skirt::split_at(&mut chain, s.top)
    {
        notes.push(format!(
            "skirt {} left out: the envelope has no ring at its top (z {} mm)",
            s.id, s.top
        ));
        skirt = None;
    }
    let mut saddles = super::saddle::find(design, resolved);
    saddles.retain(|s| {
        let split = s
            .planes()
            .iter()
            .all(|&z| super::skirt::split_at(&mut chain, z));
        if !split {
            notes.push(format!(
                "saddle {} left out: the envelope has no course under it (z {} mm)",
                s.id, s.z
            ));
        }
        split
    });
    let r_max = chain
        .iter()
        .map(|s| s.rz(s.s0).x.max(s.rz(s.s1).x))
        .fold(0.0, f64::max);
    let size = match options.size {
        Some(s) if s.is_finite() && s > 0.0 => s,
        Some(s) => {
            return Err(FemError::Option {
                field: "size",
                value: s.to_string(),
                rule: "the element size is a positive length in mm".into(),
            });
        }
        None => {
            let t = chain.iter().map(|s| s.thickness).fold(0.0, f64::max);
            (r_max * t).sqrt()
        }
    };
    if size < 1e-4 * r_max {
        return Err(FemError::Option {
            field: "size",
            value: size.to_string(),
            rule: format!("below 1e-4 of the vessel radius {r_max} mm"),
        });
    }
    // Divisions round: a multiple of 8 (quarter points on nodes), of 24 under
    // saddles (their horns at 120° and 150° on nodes).
    let unit = if saddles.is_empty() { 8 } else { 24 };
    let n = ((TAU * r_max / size).ceil() as usize)
        .div_ceil(unit)
        .max(16usize.div_ceil(unit))
        * unit;
    // Plan the nozzle windows; where an off-centre head nozzle's window
    // reaches a pole cap, shrink that cap and plan again.
    let meshed: Vec<String> = centre_necks.iter().map(|c| c.mark.clone()).collect();
    let mut planned = Vec::new();
    let mut mer = meridian::stations(chain.clone(), size, n, [f64::INFINITY; 2]);
    let mut plan = super::window::plan(resolved, &mer, n, &parts, &meshed, &mut planned);
    if plan.caps.iter().any(|c| c.is_finite()) {
        planned.clear();
        mer = meridian::stations(chain, size, n, plan.caps);
        plan = super::window::plan(resolved, &mer, n, &parts, &meshed, &mut planned);
    }
    notes.extend(planned);
    let holes = plan.holes;
    let theta = |k: f64| TAU * k / n as f64;
    let mut b = Builder::new(options.order == 2);
    b.mesh.parts = parts;
    b.mesh.notes = notes;
    // Rings of corner nodes; the rims of caps carry plane coordinates.
    let mut rings = Vec::with_capacity(mer.stations.len());
    for (i, &(seg, s)) in mer.stations.iter().enumerate() {
        let segment = mer.segments[seg];
        let capped = (i == 0 && mer.start_cap.is_some())
            || (i + 1 == mer.stations.len() && mer.end_cap.is_some());
        let ring: Vec<usize> = (0..n)
            .map(|k| {
                let th = theta(k as f64);
                let r = segment.rz(s).x;
                let plane = capped.then(|| DVec2::new(th.cos(), th.sin()) * r);
                b.node(segment.point(s, th), plane)
            })
            .collect();
        rings.push(ring);
    }
    // Tangent lines between pieces (of one part or two): the rings at segment changes.
    for (pair, ring) in mer.intervals.windows(2).zip(&rings[1..]) {
        if pair[0].seg != pair[1].seg {
            b.mesh.junctions.extend(ring.iter().copied());
        }
    }
    for (i, iv) in mer.intervals.iter().enumerate() {
        let seg = mer.segments[iv.seg];
        let (lower, upper) = (mer.stations[i], mer.stations[i + 1]);
        let smid = 0.5 * (iv.sa + iv.sb);
        for k in 0..n {
            if holes.iter().any(|h| h.covers(i, k, n)) {
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
    let last = rings.len() - 1;
    if let Some(cap) = mer.start_cap {
        let seg = mer.segments[cap.seg];
        let ring = rings[0].clone();
        super::cap::cap(&mut b, &ring, cap.radius, seg.part, false, &|p| {
            seg.point_over(p)
        });
    } else {
        b.mesh.boundary.extend(rings[0].iter().copied());
    }
    if let Some(cap) = mer.end_cap {
        let seg = mer.segments[cap.seg];
        let ring = rings[last].clone();
        super::cap::cap(&mut b, &ring, cap.radius, seg.part, true, &|p| {
            seg.point_over(p)
        });
    } else {
        b.mesh.boundary.extend(rings[last].iter().copied());
    }
    for hole in &holes {
        let end = super::nozzle::mesh(&mut b, hole, &mer, &rings, size, &design.tag);
        b.mesh.necks.push(end);
    }
    for neck in &centre_necks {
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
    if let Some(s) = &skirt {
        skirt_shell(&mut b, s, &mer, &rings, size, &design.tag);
    }
    for s in &saddles {
        if let Err(note) = super::saddle::attach(&mut b, s, &mer, &rings, &holes, size, &design.tag)
        {
            b.mesh.notes.push(note);
        }
    }
    let sites: Vec<_> = holes
        .iter()
        .filter_map(|h| h.pad_site())
        .chain(centre_necks.iter().filter_map(|c| c.pad_site()))
        .collect();
    super::nozzle::pads(&mut b, &sites, &design.tag);
    // Vessel frame → plant frame.
    let frame = resolved.frame;
    for p in &mut b.mesh.nodes {
        *p = frame.transform_point3(*p);
    }
    for end in &mut b.mesh.necks {
        end.centre = frame.transform_point3(end.centre);
        end.axis = frame.transform_vector3(end.axis).normalize();
    }
    b.mesh.axis = (
        frame.transform_point3(DVec3::ZERO),
        frame.transform_vector3(DVec3::Z).normalize(),
    );
    Ok(b.mesh)
}

/// Hangs skirt `s` from the ring of `mer` at its top (the widest ring at that
/// height), its base an open boundary and the part structural.
fn skirt_shell(
    b: &mut Builder,
    s: &super::skirt::SkirtShell,
    mer: &meridian::Meridian,
    rings: &[Vec<usize>],
    size: f64,
    tag: &str,
) {
    let tol = 1e-6 * s.top.abs().max(1.0);
    let at = |i: usize| {
        let (seg, p) = mer.stations[i];
        mer.segments[seg].rz(p)
    };
    let Some(i) = (0..mer.stations.len())
        .filter(|&i| (at(i).y - s.top).abs() <= tol)
        .max_by(|&x, &y| at(x).x.total_cmp(&at(y).x))
    else {
        b.mesh.notes.push(format!(
            "skirt {} left out: the envelope has no ring at its top (z {} mm)",
            s.id, s.top
        ));
        return;
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
