//! The export entry point and its cache of vessel blocks.
//!
//! A vessel's STEP block depends only on its own design (a vessel is resolved
//! on its own) and the exchange options, and is written in the vessel's own
//! frame, so [`StepBlocks`] keeps each block under the XXH3-128 of the
//! options and of the vessel's canonical JSON less what does not shape it (its
//! position, which the plant assembly writes; its drawing title block, notes
//! and operating state): an export after an edit builds and writes only the
//! vessels whose geometry changed, and copies the others' text (rebased to
//! their new ids), a moved vessel's included.

use std::collections::HashMap;
use std::sync::Arc;

use rayon::prelude::*;
use xxhash_rust::xxh3::Xxh3;

use super::error::ExchangeError;
use super::source::vessel_source;
use super::step::{StepBlock, vessel_block};
use super::step_file::{PlacedBlock, write_step};
use super::topology::vessel_brep_with;
use crate::design::{Design, DrawingInfo, Placement, VesselDesign, resolve};
use crate::export::SharedMarches;

/// What an exchange export is built to.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ExchangeOptions {
    /// Largest distance, mm, between an opening's exact intersection curve and
    /// the sampled curve written for it (and between its pcurves' images on
    /// both faces and that curve). Finite and > 0.
    pub tolerance: f64,
    /// Close each nozzle's bore with a disk in its gasket plane and write every
    /// closed shell as a solid (`MANIFOLD_SOLID_BREP`): the vessel's
    /// displacement solid.
    pub solids: bool,
}

impl ExchangeOptions {
    /// 0.001 mm, surfaces only.
    pub const DEFAULT: Self = Self {
        tolerance: 1e-3,
        solids: false,
    };

    /// Checks the options.
    ///
    /// # Errors
    ///
    /// [`ExchangeError::Options`] for a tolerance that is not finite and > 0.
    pub fn validate(&self) -> Result<(), ExchangeError> {
        if self.tolerance.is_finite() && self.tolerance > 0.0 {
            Ok(())
        } else {
            Err(ExchangeError::Options {
                field: "tolerance",
                value: self.tolerance,
                rule: "must be finite and > 0",
            })
        }
    }
}

impl Default for ExchangeOptions {
    fn default() -> Self {
        Self::DEFAULT
    }
}

/// Vessel blocks kept by the content of their design.
#[derive(Clone, Debug, Default)]
pub struct StepBlocks {
    blocks: HashMap<u128, Arc<StepBlock>>,
    /// Blocks built by the last export (the others were reused).
    pub built: usize,
    /// Blocks reused by the last export.
    pub reused: usize,
}

/// The key of a vessel's block: the options and the vessel's JSON without the
/// fields that do not shape its block.
fn block_key(vessel: &VesselDesign, options: &ExchangeOptions) -> u128 {
    let shaping = VesselDesign {
        // Nozzle orientations are bearings from plant north, so a turn of the
        // vessel moves its nozzles in its own frame; a move does not.
        placement: Placement {
            position: [0.0; 3],
            ..vessel.placement
        },
        drawing: DrawingInfo::default(),
        notes: Vec::new(),
        operating: None,
        ..vessel.clone()
    };
    let mut hasher = Xxh3::new();
    hasher.update(&options.tolerance.to_bits().to_le_bytes());
    hasher.update(&[u8::from(options.solids)]);
    hasher.update(
        serde_json::to_string(&shaping)
            .unwrap_or_default()
            .as_bytes(),
    );
    hasher.digest128()
}

/// Writes the vessels of `design` tagged in `tags` (all when empty) as one STEP
/// file named `name`, taking unchanged vessels' blocks from `cache` and keeping
/// the new ones there (only the blocks of this export are kept).
///
/// # Errors
///
/// See [`ExchangeError`]: an invalid design or options, an unknown tag, a part,
/// opening or trim that cannot be built.
pub fn export_step(
    design: &Design,
    tags: &[String],
    options: &ExchangeOptions,
    name: &str,
    cache: &mut StepBlocks,
) -> Result<String, ExchangeError> {
    options.validate()?;
    let resolved = resolve(design)?;
    for tag in tags {
        if !resolved.iter().any(|v| &v.tag == tag) {
            return Err(ExchangeError::UnknownVessel { tag: tag.clone() });
        }
    }
    let chosen: Vec<(usize, u128)> = design
        .vessels
        .iter()
        .enumerate()
        .filter(|(_, v)| tags.is_empty() || tags.contains(&v.tag))
        .map(|(i, v)| (i, block_key(v, options)))
        .collect();
    // Openings of one canonical march (across vessels) are placed from one.
    let shared = SharedMarches::default();
    let blocks: Vec<Result<(Arc<StepBlock>, bool), ExchangeError>> = chosen
        .par_iter()
        .map(|&(i, key)| {
            if let Some(block) = cache.blocks.get(&key) {
                return Ok((block.clone(), false));
            }
            let source = vessel_source(&resolved[i], options.tolerance, &shared)?;
            let brep = vessel_brep_with(&source, options.solids)?;
            Ok((Arc::new(vessel_block(&brep, options.solids)), true))
        })
        .collect();
    let mut placed = Vec::with_capacity(blocks.len());
    let mut kept = HashMap::with_capacity(blocks.len());
    let (mut built, mut reused) = (0, 0);
    for (&(i, key), block) in chosen.iter().zip(blocks) {
        let (block, new) = block?;
        if new {
            built += 1;
        } else {
            reused += 1;
        }
        kept.insert(key, block.clone());
        placed.push(PlacedBlock {
            tag: resolved[i].tag.clone(),
            frame: resolved[i].frame,
            block,
        });
    }
    cache.blocks = kept;
    cache.built = built;
    cache.reused = reused;
    Ok(write_step(name, &placed))
}
