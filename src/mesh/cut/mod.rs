//! Opening cuts: where a nozzle's neck meets its host, as exact intersection
//! loops on both (the Geometry stage's `cut_openings`).
//!
//! [`cut_opening`] marches the neck–host intersection (`opening`) with the neck
//! cut to the host's reach (`reach`); an opening in a straight one-patch course is
//! placed from a canonical march shared by content (`axial`, turned round the
//! course by `turn`); loops that cross a closed host's seam are split there
//! (`seams`). A cut that fails says why with a [`CutError`]. The loops go to the region layout (`mesh::layout`) as holes and as
//! the trimmed neck bottom.

mod axial;
mod error;
mod opening;
mod outcome;
mod reach;
mod seams;
mod shared_cuts;
mod turn;

pub use axial::AxialCut;
pub use error::{CutError, CutLoop};
pub use opening::{OpeningPlan, ReusableCut, cut_opening, cut_opening_reusing};
pub use outcome::{Cut, PAD_PATCH, PadCut};
pub use seams::{HostTrim, Notch};
pub use shared_cuts::SharedCuts;
pub(in crate::mesh) use shared_cuts::shared_key;
