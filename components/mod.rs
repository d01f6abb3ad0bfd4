//! Everything the ECS world holds: the parameter components users set, the
//! relations between entities, the derived components only systems write, and
//! the resources (options, dirty lists, stores, counters) the stages share.
//!
//! Parameters are the design-file types themselves (one component per entity
//! kind), so an entity's parameters and its design-file entry can never disagree.
//! Derived components are written with `set_if_neq`, so an unchanged value stops a
//! cascade. See `ARCHITECTURE.md` (*ECS stages*) for which system writes what.
//! The systems that read and write them are in [`crate::systems`].

mod calc;
mod change_log;
mod counters;
mod derived;
mod dirty;
mod failures;
mod host_sides;
mod opening_input;
mod operating;
mod params;
mod process;
mod relations;
mod resolutions;
mod stage_times;
mod stores;
mod tessellation;
mod views;

pub use calc::{Materials, NozzleCalculation, PartCalculation, VesselCalculation};
pub use change_log::ChangeLog;
pub use counters::WorkCounters;
pub use derived::{
    NoteAnchor, Opening, PartFrame, PartSpan, PatchCavities, PatchMesh, PatchRegion, PatchSurface,
    Shape, VesselFrame, VesselSummary,
};
pub(crate) use dirty::unique;
pub use dirty::{DirtyParts, DirtyPatches, EditedVessels};
pub use failures::{BuildCause, BuildFailure, ModelErrors, ModelFailure};
pub use host_sides::HostSides;
pub(crate) use host_sides::{Laid, Trim};
pub use opening_input::OpeningInput;
pub use operating::{OperatingProblem, OperatingState};
pub use params::{
    DesignOrder, NoteSpec, NozzleSpec, OperatingSpec, PartSpec, VesselSpec, same_in_order,
};
pub use process::{ProcessPlanning, VesselFabPlan, VesselProcessPlan};
pub use relations::{AnnotatedBy, Annotates, MountedOn, Mounts, PadOf, PadPatch, PatchOf, Patches};
pub use resolutions::{CheckedResolutions, PendingResolutions};
pub use stage_times::{STAGES, StageTimes};
pub(crate) use stores::VesselIndex;
pub use stores::{CutTable, Instances, OpeningHosts};
pub use tessellation::{RequestedTessellation, StorageExtents, Tessellation};
pub use views::{EntityViews, Footprint, VesselViews, Views};
