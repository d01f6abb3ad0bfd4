//! The conforming shell mesh of a vessel's pressure envelope: the stations of
//! [`super::meridian`] swept about the axis into rings of quadrilaterals, one
//! circumferential division count for the whole vessel (so every junction ring
//! is shared node for node), poles closed by [`super::cap`]. Corner and
//! mid-side nodes are exact points of the mid-surface: mid-side nodes at the
//! parameter midpoint of their piece and the angle midpoint.
//!
//! This module is the first of two steps: the [`Plan`] (the parts, the
//! meridian's stations, the division count, the nozzles' windows, the skirt's
//! ring, each saddle's course: closed forms, redone on every build). Then the
//! pieces of [`super::piece`] — one per envelope part with its windows'
//! nozzles, saddles and pads, and the skirt — are each meshed from their own
//! inputs or taken from a [`super::cache::FemCache`] when those are unchanged,
//! and welded on their shared rings ([`super::assemble`]).

use std::f64::consts::TAU;

use super::head_nozzle::CentreNeck;
use super::meridian::{self, Meridian, Segment};
use super::saddle::SaddleShell;
use super::skirt::SkirtShell;
use super::window::Hole;
use super::{FePart, FemError};
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

/// What the pieces are meshed from: the vessel's parts, meridian stations,
/// division count and nozzle windows, with its skirt's ring and each saddle's
/// course.
#[derive(Clone, Debug)]
pub struct Plan {
    /// Vessel tag.
    pub tag: String,
    /// Whether elements are quadratic.
    pub quadratic: bool,
    /// Target element size, mm.
    pub size: f64,
    /// Circumferential divisions.
    pub divisions: usize,
    /// The envelope's parts (courses, heads, cones, centre necks).
    pub parts: Vec<FePart>,
    /// The stations.
    pub mer: Meridian,
    /// Nozzle windows.
    pub holes: Vec<Hole>,
    /// Necks on heads' centres (parts of the chain).
    pub centre_necks: Vec<CentreNeck>,
    /// The skirt and the station of the envelope's ring it hangs from.
    pub skirt: Option<(SkirtShell, usize)>,
    /// The saddles and the part of the course each stands under.
    pub saddles: Vec<(SaddleShell, usize)>,
    /// What the plan leaves out.
    pub notes: Vec<String>,
}

/// Plans the mesh of the pressure envelope (courses, reducers, heads) of
/// `design`, resolved as `resolved`, and of its skirt or saddles.
///
/// # Errors
///
/// As [`super::build_envelope`].
pub fn plan(
    design: &VesselDesign,
    resolved: &ResolvedVessel,
    options: &FemOptions,
) -> Result<Plan, FemError> {
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
    let mut windows = super::window::plan(resolved, &mer, n, &parts, &meshed, &mut planned);
    if windows.caps.iter().any(|c| c.is_finite()) {
        planned.clear();
        mer = meridian::stations(chain, size, n, windows.caps);
        windows = super::window::plan(resolved, &mer, n, &parts, &meshed, &mut planned);
    }
    notes.extend(planned);
    let skirt = skirt.and_then(|s| match skirt_station(&mer, s.top) {
        Some(i) => Some((s, i)),
        None => {
            notes.push(format!(
                "skirt {} left out: the envelope has no ring at its top (z {} mm)",
                s.id, s.top
            ));
            None
        }
    });
    let saddles = saddles
        .into_iter()
        .filter_map(|s| match super::saddle::host(&s, &mer) {
            Some(part) => Some((s, part)),
            None => {
                notes.push(format!(
                    "saddle {} left out: the envelope has no rings at its plate's edges and web",
                    s.id
                ));
                None
            }
        })
        .collect();
    Ok(Plan {
        tag: design.tag.clone(),
        quadratic: options.order == 2,
        size,
        divisions: n,
        parts,
        mer,
        holes: windows.holes,
        centre_necks,
        skirt,
        saddles,
        notes,
    })
}

/// The station of the widest ring of `mer` at height `z` (a skirt's top).
fn skirt_station(mer: &Meridian, z: f64) -> Option<usize> {
    let tol = 1e-6 * z.abs().max(1.0);
    let at = |i: usize| {
        let (seg, p) = mer.stations[i];
        mer.segments[seg].rz(p)
    };
    (0..mer.stations.len())
        .filter(|&i| (at(i).y - z).abs() <= tol)
        .max_by(|&x, &y| at(x).x.total_cmp(&at(y).x))
}
