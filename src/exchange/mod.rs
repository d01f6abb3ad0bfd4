//! Exchange files of the exact model: STEP (AP214) and IGES 5.3 for CAD and
//! plant tools.
//!
//! Pipeline: design → [`vessel_sources`] (resolved vessels, exact patches in part
//! frames, openings cut to the exchange tolerance) → [`vessel_brep`] (faces on
//! the patches, shared edges with pcurves, shells, nozzle connection points, in
//! the vessel frame) → [`vessel_block`] (one vessel's STEP entities, numbered
//! locally) → [`write_step`] (header, the blocks rebased into one file, the plant
//! assembly placing each vessel). [`export_step`] runs it all; [`StepBlocks`]
//! keeps each vessel's block by the content of its design so that an export
//! after an edit writes only the vessels that changed. [`export_iges`] writes
//! the same B-rep as IGES 5.3 (`iges_model` on the record layout of `iges`):
//! manifold solid B-rep entities by default, trimmed surfaces on request.

mod blocks;
mod brep;
mod error;
mod fit;
mod iges;
mod iges_brep;
mod iges_entities;
mod iges_model;
mod iges_trimmed;
mod loops;
mod measure;
mod notch;
mod seam;
mod source;
mod step;
mod step_file;
mod topology;

pub use blocks::{ExchangeOptions, StepBlocks, export_step};
pub use brep::{Edge, EdgeCurve, Face, OrientedEdge, Port, Shell, VesselBrep};
pub use error::ExchangeError;
pub use iges_model::{IgesEntities, export_iges, export_iges_as, write_iges};
pub use measure::{FaceMeasures, ORDER, face_measures, face_measures_with};
pub use source::{CutSource, NodeKind, NodeSource, VesselSource, vessel_sources};
pub use step::{LOCAL_BASE, StepBlock, rebase, vessel_block};
pub use step_file::{PlacedBlock, write_step};
pub use topology::{vessel_brep, vessel_brep_with};
