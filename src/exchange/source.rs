//! What the exchange writers read: each vessel's exact patches in their part
//! frames and every opening cut into its host, built from a design without
//! meshing.
//!
//! This is the first half of [`build_scene`](crate::export::build_scene): resolve,
//! build every part's and nozzle's patches, cut every boot's and nozzle's opening
//! with [`cut_opening_reusing`] (the routine the mesher's regions come from), all
//! in parallel and assembled in design order. The openings are cut to the
//! exchange tolerance, not a mesh tolerance: the same exact curve, sampled more
//! finely.

use glam::DAffine3;
use rayon::prelude::*;

use super::error::ExchangeError;
use crate::constraints::{PartGeometry, ResolvedVessel};
use crate::design::{Design, resolve};
use crate::mesh::{Cut, PadCut, cut_opening_reusing};
use crate::parts::{Nozzle, Patch};

/// Whether a node is a part of the vessel or a nozzle.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum NodeKind {
    /// A part of the envelope (course, head, reducer, boot).
    Part,
    /// A support (skirt, saddle, legs, lugs): its own shells, apart from the
    /// envelope even where an edge of it lies on one of the envelope's.
    Support,
    /// A nozzle.
    Nozzle,
}

/// One part or nozzle with its patches in its local frame.
#[derive(Clone, Debug)]
pub struct NodeSource {
    /// Part id or nozzle mark.
    pub id: String,
    /// Part or nozzle.
    pub kind: NodeKind,
    /// Local frame → vessel frame.
    pub frame: DAffine3,
    /// The exact patches, local frame.
    pub patches: Vec<Patch>,
    /// The nozzle's parameters (for its connection point).
    pub nozzle: Option<Nozzle>,
}

/// One opening: a nozzle's neck (or a boot's shell) cut into its host.
#[derive(Clone, Debug)]
pub struct CutSource {
    /// Index in [`VesselSource::nodes`] of the nozzle (or boot).
    pub neck: usize,
    /// Index of its host part.
    pub host: usize,
    /// The cut, host part frame.
    pub cut: Cut,
    /// The reinforcing pad, nozzle frame.
    pub pad: Option<PadCut>,
    /// The reinforcing pad's outside diameter, mm.
    pub pad_od: Option<f64>,
}

/// A vessel's exact model, as the writers read it.
#[derive(Clone, Debug)]
pub struct VesselSource {
    /// Tag.
    pub tag: String,
    /// Vessel frame → plant frame.
    pub frame: DAffine3,
    /// Parts in design order, then nozzles in design order.
    pub nodes: Vec<NodeSource>,
    /// Openings: boots first, then nozzles, in design order.
    pub cuts: Vec<CutSource>,
    /// The exchange tolerance the openings were cut to, mm: the loops' fit
    /// keeps within it too.
    pub tolerance: f64,
}

/// Builds the exact model of the vessels of `design` whose tags are in `tags`
/// (every vessel when `tags` is empty), cutting openings to `tolerance` mm.
///
/// # Errors
///
/// [`ExchangeError::Design`] for a design breaking a rule,
/// [`ExchangeError::UnknownVessel`] for a tag not in the design,
/// [`ExchangeError::Part`] / [`ExchangeError::Opening`] where a part's patches
/// or an opening cannot be built.
pub fn vessel_sources(
    design: &Design,
    tags: &[String],
    tolerance: f64,
) -> Result<Vec<VesselSource>, ExchangeError> {
    let resolved = resolve(design)?;
    for tag in tags {
        if !resolved.iter().any(|v| &v.tag == tag) {
            return Err(ExchangeError::UnknownVessel { tag: tag.clone() });
        }
    }
    let chosen: Vec<&ResolvedVessel> = resolved
        .iter()
        .filter(|v| tags.is_empty() || tags.contains(&v.tag))
        .collect();
    chosen
        .par_iter()
        .map(|vessel| vessel_source(vessel, tolerance))
        .collect()
}

/// One vessel's patches and openings.
pub(super) fn vessel_source(
    vessel: &ResolvedVessel,
    tolerance: f64,
) -> Result<VesselSource, ExchangeError> {
    let entity = |id: &str| format!("{}/{}", vessel.tag, id);
    let mut nodes = Vec::with_capacity(vessel.parts.len() + vessel.nozzles.len());
    for part in &vessel.parts {
        let patches = part
            .geometry
            .patches()
            .map_err(|source| ExchangeError::Part {
                entity: entity(&part.id),
                source,
            })?;
        nodes.push(NodeSource {
            id: part.id.clone(),
            kind: if matches!(
                part.geometry,
                PartGeometry::Skirt(_)
                    | PartGeometry::Saddle(_)
                    | PartGeometry::Legs(_)
                    | PartGeometry::Lugs(_)
            ) {
                NodeKind::Support
            } else {
                NodeKind::Part
            },
            // Heads with their seam where the design puts it: the exchange
            // cuts openings across a seam itself.
            frame: crate::constraints::unturned_frame(part),
            patches,
            nozzle: None,
        });
    }
    for nozzle in &vessel.nozzles {
        let patches = nozzle
            .geometry
            .patches()
            .map_err(|source| ExchangeError::Part {
                entity: entity(&nozzle.mark),
                source,
            })?;
        nodes.push(NodeSource {
            id: nozzle.mark.clone(),
            kind: NodeKind::Nozzle,
            frame: nozzle.frame,
            patches,
            nozzle: Some(nozzle.geometry),
        });
    }
    let parts = vessel.parts.len();
    let boots = vessel
        .parts
        .iter()
        .enumerate()
        .filter_map(|(i, part)| part.host.map(|h| (i, h, None)));
    let necks = vessel
        .nozzles
        .iter()
        .enumerate()
        .map(|(i, nozzle)| (parts + i, nozzle.host, nozzle.pad.map(|p| p.0)));
    let mut cuts = Vec::new();
    for (neck, host, pad_od) in boots.chain(necks) {
        let hosts: Vec<&Patch> = nodes[host].patches.iter().collect();
        let Some(neck_patch) = nodes[neck].patches.first() else {
            continue;
        };
        let cut = cut_opening_reusing(
            neck_patch,
            pad_od,
            &nodes[neck].frame,
            &nodes[host].frame,
            &hosts,
            tolerance,
            None,
        )
        .map_err(|e| ExchangeError::Opening {
            entity: entity(&nodes[neck].id),
            message: e.to_string(),
        })?;
        cuts.push(CutSource {
            neck,
            host,
            cut: cut.cut,
            pad: cut.pad,
            pad_od,
        });
    }
    Ok(VesselSource {
        tag: vessel.tag.clone(),
        frame: vessel.frame,
        nodes,
        cuts,
        tolerance,
    })
}
