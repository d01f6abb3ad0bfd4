//! Drawing sheets: a vessel's four views laid out on a standard sheet with border,
//! title block, design-data block, nozzle schedule, notes with leaders, north
//! arrow, revision triangle and automatic dimensions; written as SVG and DXF.
//!
//! The last consumer in the data flow: it reads the views the Project stage keeps
//! per entity (`crate::project`) and the resolved figures of the model, builds a
//! [`Sheet`] (a display list in paper millimetres) and hands it to a writer.

mod data;

pub use data::{NoteData, NozzleData, PartData, VesselData, vessel_data, vessel_views};

use thiserror::Error;

/// Why a sheet could not be drawn.
#[derive(Debug, Error)]
pub enum DrawingError {
    /// No vessel has this tag.
    #[error("no vessel has the tag {tag:?}")]
    UnknownVessel {
        /// The tag given.
        tag: String,
    },
    /// The vessel's views have not been built (the model was not updated).
    #[error("vessel {tag} has no views yet: update the model first")]
    NotBuilt {
        /// The vessel's tag.
        tag: String,
    },
}
