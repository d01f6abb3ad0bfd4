//! The as-built surfaces as STEP (AP214): each fitted patch a face, in the
//! vessel's frame, the vessel placed in the plant as the design's export places
//! it.
//!
//! The fitted patches are NURBS like the design's ([`fit`](super::fit)), so
//! they take the exchange pipeline unchanged: a [`VesselSource`] of the
//! envelope's parts holding the fitted surfaces in place of the design's →
//! [`vessel_brep`] (faces bounded by their isocurves; a closed patch's seam is
//! one edge, a pole is left out) → [`vessel_block`] → [`write_step`]. Without
//! openings: a fit covers the shell round a nozzle, and nozzles are not fitted.
//! Neighbouring patches are fitted apart, so their common edges differ by the
//! fits' residuals and each patch is an open shell of its own unless the two
//! edges coincide within the exchange's match distance. A patch no point fell
//! on has no fit and no face. The product is named `<tag> as-built`, faces
//! `<tag> as-built/<part>/<patch>`.

use std::sync::Arc;

use super::ScanError;
use super::envelope::Envelope;
use super::fit::PatchFit;
use crate::exchange::{
    NodeKind, NodeSource, PlacedBlock, VesselSource, vessel_block, vessel_brep, write_step,
};
use crate::parts::Patch;

/// The tolerance handed to the exchange pipeline, mm: it bounds only the fit of
/// opening loops, and the fitted model has none.
const TOLERANCE: f64 = 0.01;

/// The fitted surfaces of `envelope` (`fits[i]` the fit of
/// `envelope.surfaces[i]`) as a STEP file named `name`.
///
/// # Errors
///
/// [`ScanError::Exchange`] where the B-rep of the fitted patches cannot be
/// built; [`ScanError::TooFewPoints`] when no patch was fitted.
pub fn fitted_step(
    envelope: &Envelope,
    fits: &[Option<PatchFit>],
    name: &str,
) -> Result<String, ScanError> {
    let tag = format!("{} as-built", envelope.tag);
    let mut nodes: Vec<NodeSource> = Vec::new();
    for (index, part) in envelope.parts.iter().enumerate() {
        if !part.role.is_envelope() {
            continue;
        }
        let patches: Vec<Patch> = envelope
            .surfaces
            .iter()
            .zip(fits)
            .filter(|(s, _)| s.part == index)
            .filter_map(|(s, fit)| {
                fit.as_ref().map(|f| Patch {
                    surface: f.surface.clone(),
                    ..s.patch.clone()
                })
            })
            .collect();
        if patches.is_empty() {
            continue;
        }
        nodes.push(NodeSource {
            id: part.id.clone(),
            kind: NodeKind::Part,
            frame: part.frame,
            patches,
            nozzle: None,
        });
    }
    if nodes.is_empty() {
        return Err(ScanError::TooFewPoints {
            what: "the as-built STEP".to_string(),
            found: 0,
            needed: 1,
        });
    }
    let source = VesselSource {
        tag: tag.clone(),
        frame: envelope.frame,
        nodes,
        cuts: Vec::new(),
        tolerance: TOLERANCE,
    };
    let brep = vessel_brep(&source).map_err(|source| ScanError::Exchange {
        entity: tag.clone(),
        source: Box::new(source),
    })?;
    let block = vessel_block(&brep, false);
    Ok(write_step(
        name,
        &[PlacedBlock {
            tag,
            frame: envelope.frame,
            block: Arc::new(block),
        }],
    ))
}
