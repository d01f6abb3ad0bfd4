//! What the exchange writers read: each vessel's exact patches in their part
//! frames and every opening cut into its host, built from a design without
//! meshing.
//!
//! This is the first half of [`build_scene`](crate::export::build_scene): resolve,
//! build every part's and nozzle's patches, cut every boot's and nozzle's opening
//! with [`cut_opening`] over the list [`openings`] gives (the routines the scene
//! build cuts with, so the GLB and the exchange cut the same openings alike), all
//! in parallel and assembled in design order. The openings are cut to the
//! exchange tolerance, not a mesh tolerance: the same exact curve, sampled more
//! finely; heads keep their seam where the design puts it (the scene turns it
//! away from the openings; the exchange cuts across seams itself).

use glam::DAffine3;
use rayon::prelude::*;

use super::error::ExchangeError;
use crate::constraints::{PartGeometry, ResolvedVessel};
use crate::design::{Design, resolve};
use crate::export::{Opening, SharedMarches, cut_opening, openings};
use crate::mesh::{Cut, PadCut};
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
    let shared = SharedMarches::default();
    chosen
        .par_iter()
        .map(|vessel| vessel_source(vessel, tolerance, &shared))
        .collect()
}

/// One vessel's patches and openings.
/// `shared` keeps the canonical marches of the export's openings, for the
/// next vessels' (see [`SharedMarches`]).
pub(super) fn vessel_source(
    vessel: &ResolvedVessel,
    tolerance: f64,
    shared: &SharedMarches,
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
    let mut cuts = Vec::new();
    for Opening { neck, host, pad_od } in openings(vessel) {
        let cut = cut_opening(
            nodes[neck].patches.first(),
            pad_od,
            (&nodes[neck].frame, &nodes[host].frame),
            &nodes[host].patches,
            tolerance,
            shared,
        )
        .map_err(|message| ExchangeError::Opening {
            entity: entity(&nodes[neck].id),
            message,
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

#[cfg(test)]
mod tests {
    use std::path::Path;

    use glam::DVec3;

    use super::*;
    use crate::design::load;

    /// Largest distance from the points `a` to the closed polyline through `b`.
    fn farthest(a: &[DVec3], b: &[DVec3]) -> f64 {
        a.iter()
            .map(|&p| {
                (0..b.len())
                    .map(|i| {
                        let (s, e) = (b[i], b[(i + 1) % b.len()]);
                        let d = e - s;
                        let t = ((p - s).dot(d) / d.length_squared().max(1e-300)).clamp(0.0, 1.0);
                        p.distance(s + d * t)
                    })
                    .fold(f64::INFINITY, f64::min)
            })
            .fold(0.0, f64::max)
    }

    /// The exchange cuts the openings the scene build cuts (one list, one
    /// cutter: `export::openings`), and on the same curves: each loop of the
    /// example drum and of a repro with a nozzle on a head's seam, cut in the
    /// exchange's unturned head frames and in the scene's turned ones, lies in
    /// the vessel frame within the tolerance of the other's samples.
    #[test]
    fn the_exchange_and_the_scene_cut_the_same_loops() {
        let designs = [
            "examples/designs/horizontal-drum.json",
            "tests/repros/D2-ellipsoidal-head-seam-nozzle.json",
        ];
        let mut turned = 0;
        for path in designs {
            let path = Path::new(env!("CARGO_MANIFEST_DIR")).join(path);
            turned += turned_loops(&load(&path).expect("design"));
        }
        assert!(turned > 0, "no opening in a turned head");
    }

    /// Checks the loops of `design` as above; returns how many were cut in a
    /// turned head.
    fn turned_loops(design: &Design) -> usize {
        let tolerance = 0.01;
        let resolved = resolve(design).expect("resolves");
        let sources = vessel_sources(design, &[], tolerance).expect("cuts");
        let shared = SharedMarches::default();
        let mut turned = 0;
        for (vessel, source) in resolved.iter().zip(&sources) {
            // The scene's frames: heads turned.
            let frames: Vec<DAffine3> = vessel
                .parts
                .iter()
                .map(|p| p.frame)
                .chain(vessel.nozzles.iter().map(|n| n.frame))
                .collect();
            let list = openings(vessel);
            assert_eq!(list.len(), source.cuts.len(), "{}", vessel.tag);
            for (opening, cut) in list.iter().zip(&source.cuts) {
                let (neck, host) = (opening.neck, opening.host);
                assert_eq!(
                    (neck, host, opening.pad_od),
                    (cut.neck, cut.host, cut.pad_od)
                );
                let scene = cut_opening(
                    source.nodes[neck].patches.first(),
                    opening.pad_od,
                    (&frames[neck], &frames[host]),
                    &source.nodes[host].patches,
                    tolerance,
                    &shared,
                )
                .expect("the scene's cut");
                let exchange_frame = source.nodes[host].frame;
                turned += usize::from(exchange_frame != frames[host]);
                let pairs = [
                    (Some(&cut.cut.neck), Some(&scene.cut.neck)),
                    (cut.cut.pad.as_ref(), scene.cut.pad.as_ref()),
                ];
                for (ours, theirs) in pairs {
                    assert_eq!(
                        ours.is_some(),
                        theirs.is_some(),
                        "{}",
                        source.nodes[neck].id
                    );
                    let (Some(ours), Some(theirs)) = (ours, theirs) else {
                        continue;
                    };
                    let a: Vec<DVec3> = ours
                        .points
                        .iter()
                        .map(|&p| exchange_frame.transform_point3(p))
                        .collect();
                    let b: Vec<DVec3> = theirs
                        .points
                        .iter()
                        .map(|&p| frames[host].transform_point3(p))
                        .collect();
                    let gap = farthest(&a, &b).max(farthest(&b, &a));
                    assert!(
                        gap <= tolerance,
                        "{}: loops {gap} mm apart",
                        source.nodes[neck].id
                    );
                }
            }
        }
        turned
    }
}
