//! Standard dimension tables for nozzle necks and flanges, used by the nozzle
//! part builder: ASME B36.10M wrought steel pipe (outside diameter and wall
//! thickness per schedule) and ASME B16.5 pipe flanges (Classes 150, 300, 600
//! and 900, NPS 1/2 through 24). Sizes are looked up through the validated
//! [`Nps`] type; combinations the standards do not list come back as a
//! [`TableError`] instead of a guess. All lengths are in millimetres.

mod flange;
mod pipe;

pub use flange::{FlangeClass, FlangeDimensions, flange, raised_face_height};
pub use pipe::{Nps, PipeDimensions, PipeSchedule, TableError, pipe};
