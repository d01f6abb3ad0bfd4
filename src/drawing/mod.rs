//! Drawing sheets: a vessel's four views laid out on a standard sheet with border,
//! title block, design-data block, nozzle schedule, notes with leaders, north
//! arrow, revision triangle and automatic dimensions; written as SVG and DXF.
//! When one sheet would be illegible the drawing goes to several ([`sheets`]):
//! the elevation, the other views, and enlarged detail views.
//!
//! The last consumer in the data flow: it reads the views the Project stage keeps
//! per entity (`crate::project`) and the resolved figures of the model
//! ([`vessel_data`]), composes a [`Sheet`] (a display list in paper millimetres)
//! and hands it to a writer ([`to_svg`], [`to_dxf`]).
//!
//! ```no_run
//! # use vesselcad::{drawing::{sheet_svg, SheetOptions}, model::Model};
//! # fn f(model: &Model) -> Result<(), vesselcad::drawing::DrawingError> {
//! let svg: String = sheet_svg(model, "C-201", &SheetOptions::default())?;
//! # Ok(()) }
//! ```

pub mod chromium;
mod compose;
mod data;
mod detail;
mod dimensions;
mod dxf;
mod dxf_fixup;
mod dxf_spaces;
mod labels;
mod layout;
mod legibility;
mod orientation;
mod sheet;
mod sheets;
mod single;
mod svg;
mod tables;
mod text;

pub use compose::compose;
pub use data::{
    NoteData, NozzleData, PartData, VesselData, vessel_data, vessel_views, view_inputs,
};
pub use detail::clip_to_circle;
pub use dimensions::format_mm;
pub use dxf::{cad_text, to_dxf, to_dxf_bytes};
pub use labels::{collisions, item_box, layout_problems};
pub use legibility::{
    MAX_ONE_SHEET_SCALE, MIN_DETAIL_NOZZLE_PAPER, MIN_NOZZLE_PAPER, legibility_problems,
};
pub use sheet::{
    Align, DetailMark, DetailView, HiddenLines, Item, Layer, Measure, PlacedDimension, Rect,
    ScheduleRow, Sheet, SheetOptions, SheetSize,
};
pub use sheets::compose_sheets;
pub use single::{LISTED_TAGS, SheetModelError, list_tags, sheet_model};
pub use svg::to_svg;
pub use tables::{SCHEDULE_COLUMNS, design_data};
pub use text::{text_box, text_width};

use thiserror::Error;

use crate::model::Model;

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
    /// The DXF writer failed.
    #[error("writing DXF: {0}")]
    Dxf(String),
}

/// The sheet of vessel `tag` as of the model's last update.
pub fn sheet(model: &Model, tag: &str, options: &SheetOptions) -> Result<Sheet, DrawingError> {
    Ok(compose(&vessel_data(model, tag)?, options))
}

/// Every sheet of vessel `tag`'s drawing (one when one is legible; see
/// [`compose_sheets`]).
pub fn sheets(
    model: &Model,
    tag: &str,
    options: &SheetOptions,
) -> Result<Vec<Sheet>, DrawingError> {
    Ok(compose_sheets(&vessel_data(model, tag)?, options))
}

/// The sheet of vessel `tag` as an SVG document.
pub fn sheet_svg(model: &Model, tag: &str, options: &SheetOptions) -> Result<String, DrawingError> {
    Ok(to_svg(&sheet(model, tag, options)?))
}

/// The sheet of vessel `tag` as DXF (R2000) bytes.
pub fn sheet_dxf(
    model: &Model,
    tag: &str,
    options: &SheetOptions,
) -> Result<Vec<u8>, DrawingError> {
    to_dxf_bytes(&sheet(model, tag, options)?)
}
