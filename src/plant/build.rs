//! Building a large plant in chunks, reporting progress between them.
//!
//! The same model as [`Model::from_design`] (vessels in design order, the same
//! entities and meshes): the vessels are added a chunk at a time, each chunk one
//! checked edit followed by one update, whose stages run in parallel over the
//! chunk's patches. Chunks of about 1 % keep the per-update overhead negligible and
//! let a caller draw a progress bar.

use rayon::prelude::*;

use super::super::design::{Design, resolve, units};
use crate::mesh::{TessellationOptions, check_storable, patch_extent};
use crate::model::{Edit, Model, ModelError, Views};

/// Builds `design` into a model, calling `progress(done, total)` after each chunk
/// of vessels.
///
/// # Errors
///
/// As [`Model::from_design`]: the first invalid chunk's violations, or the
/// geometry failures of the first chunk that cannot be built (nothing is built
/// past it); [`OptionsError::BelowStorageFloor`](crate::mesh::OptionsError::BelowStorageFloor) up front, naming the
/// design's largest part, for a tolerance finer than its `f32` storage allows.
pub fn build_plant(
    design: &Design,
    options: TessellationOptions,
    progress: &mut dyn FnMut(usize, usize),
) -> Result<Model, ModelError> {
    let mut design = design.clone();
    units::to_millimetres(&mut design);
    design.units = crate::design::Units::Mm;
    if check_storable(&options, None).is_err() {
        // One options error before any meshing, naming the design's size.
        let extent = largest_part_extent(&design);
        check_storable(&options, extent)?;
    }
    let total = design.vessels.len();
    let chunk = (total / 100).clamp(32, 200);
    let mut model = Model::new(options)?;
    // A plant build draws nothing: drawing views are built when asked for.
    model.set_views(Views::Off);
    // An empty design first: checks the format tag like `from_design` does.
    model.apply(Edit::ReplaceDesign(Design {
        vessels: Vec::new(),
        ..design.clone()
    }))?;
    let mut done = 0;
    progress(0, total);
    for vessels in design.vessels.chunks(chunk) {
        model.apply(Edit::Batch(
            vessels.iter().cloned().map(Edit::SetVessel).collect(),
        ))?;
        model.try_update()?;
        done += vessels.len();
        progress(done, total);
    }
    Ok(model)
}

/// The largest coordinate magnitude, mm, of any part or nozzle patch of
/// `design` in its part's frame (what `f32` storage is budgeted for), without
/// meshing; `None` when the design cannot be resolved or a part not built.
fn largest_part_extent(design: &Design) -> Option<f64> {
    let resolved = resolve(design).ok()?;
    let extents: Result<Vec<f64>, _> = resolved
        .par_iter()
        .flat_map_iter(|v| {
            let parts = v.parts.iter().map(|p| p.geometry.patches());
            let nozzles = v.nozzles.iter().map(|n| n.geometry.patches());
            parts.chain(nozzles)
        })
        .map(|patches| Ok(patches?.iter().map(patch_extent).fold(0.0, f64::max)))
        .collect::<Result<Vec<f64>, crate::parts::PartError>>();
    Some(extents.ok()?.into_iter().fold(0.0, f64::max))
}
