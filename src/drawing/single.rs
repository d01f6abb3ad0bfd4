//! The model a single sheet is drawn from: only the vessel drawn, built with its
//! views. A sheet of one vessel of a plant then costs what that vessel costs —
//! its parts meshed and projected once — not what the plant costs (a model of
//! the whole plant projects every vessel's views: 13.7 s for one sheet of a
//! 300-vessel plant whose build takes 1.5 s). Vessels do not depend on each
//! other (tags are unique, placements absolute), so the vessel's model is the
//! same as its part of the plant's.

use crate::design::Design;
use crate::mesh::TessellationOptions;
use crate::model::{Edit, Model, ModelError, Views};
use crate::systems::WorkCounters;

/// Why the model of one vessel could not be built.
#[derive(Debug, thiserror::Error)]
pub enum SheetModelError {
    /// No vessel of the design has the tag; the tags it has are listed.
    #[error("no vessel has the tag {tag:?}; the design's vessels are: {}", list_tags(.known))]
    UnknownVessel {
        /// The tag asked for.
        tag: String,
        /// Every tag of the design, in design order.
        known: Vec<String>,
    },
    /// The vessel could not be built.
    #[error(transparent)]
    Model(#[from] ModelError),
}

/// How many tags an unknown-vessel error lists.
pub const LISTED_TAGS: usize = 20;

/// The first [`LISTED_TAGS`] tags, comma-separated, then how many more (for an
/// unknown-vessel error in a plant of thousands).
pub fn list_tags(tags: &[String]) -> String {
    const SHOWN: usize = LISTED_TAGS;
    let mut text = tags
        .iter()
        .take(SHOWN)
        .cloned()
        .collect::<Vec<_>>()
        .join(", ");
    if tags.len() > SHOWN {
        text.push_str(&format!(" and {} more", tags.len() - SHOWN));
    }
    if tags.is_empty() {
        text.push_str("(none)");
    }
    text
}

/// The model of vessel `tag` of `design` alone, views kept, updated once; and
/// the work that update did.
///
/// # Errors
///
/// [`SheetModelError::UnknownVessel`] listing the design's tags, or the model's
/// refusal of the vessel.
pub fn sheet_model(
    design: &Design,
    tag: &str,
    options: TessellationOptions,
) -> Result<(Model, WorkCounters), SheetModelError> {
    let Some(vessel) = design.vessels.iter().find(|v| v.tag == tag) else {
        return Err(SheetModelError::UnknownVessel {
            tag: tag.to_string(),
            known: design.vessels.iter().map(|v| v.tag.clone()).collect(),
        });
    };
    let single = Design {
        format: design.format.clone(),
        units: design.units,
        vessels: vec![vessel.clone()],
    };
    let mut model = Model::new(options)?;
    model.set_views(Views::Kept);
    model.apply(Edit::ReplaceDesign(single))?;
    let work = model.try_update()?;
    Ok((model, work))
}
