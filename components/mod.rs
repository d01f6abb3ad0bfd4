//! ECS components: the parameter components users set, the relations between
//! entities, and the derived components only systems write.
//!
//! Parameters are the design-file types themselves (one component per entity
//! kind), so an entity's parameters and its design-file entry can never disagree.
//! Derived components are written with `set_if_neq`, so an unchanged value stops a
//! cascade. See `ARCHITECTURE.md` (*ECS stages*) for which system writes what.

mod calc;
mod derived;
mod params;
mod relations;
mod views;

pub use calc::{NozzleCalculation, PartCalculation, VesselCalculation};
pub use derived::{
    NoteAnchor, Opening, PartFrame, PartSpan, PatchCavities, PatchMesh, PatchRegion, PatchSurface,
    Shape, VesselFrame, VesselSummary,
};
pub use params::{
    DesignOrder, NoteSpec, NozzleSpec, OperatingSpec, PartSpec, VesselSpec, same_in_order,
};
pub use relations::{AnnotatedBy, Annotates, MountedOn, Mounts, PadOf, PadPatch, PatchOf, Patches};
pub use views::{EntityViews, Footprint, VesselViews};
