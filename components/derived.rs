//! Derived components: written only by systems, always with `set_if_neq` (or
//! inserted once), so that equal values do not mark anything changed.

use std::sync::Arc;

use bevy_ecs::component::Component;
use glam::{DAffine3, DVec3};

use bevy_ecs::entity::Entity;

use crate::constraints::PartGeometry;
use crate::mesh::cdt::{KeptCavities, Region};
use crate::mesh::{HostTrim, PackedMesh};
use crate::nurbs::intersect::IntersectionLoop;
use crate::parts::{Nozzle, Patch};

/// Vessel local frame → plant frame (mm).
#[derive(Component, Clone, Copy, Debug, PartialEq)]
pub struct VesselFrame(pub DAffine3);

/// Resolved whole-vessel figures.
#[derive(Component, Clone, Copy, Debug, PartialEq)]
pub struct VesselSummary {
    /// Tangent-to-tangent length, mm.
    pub tangent_length: f64,
    /// Axial extent including heads and supports, mm.
    pub extent: (f64, f64),
    /// Largest course OD, mm.
    pub max_diameter: f64,
}

/// Part (or nozzle) local frame → vessel local frame. Changing it never rebuilds a
/// patch: patches live in the part's local frame.
#[derive(Component, Clone, Copy, Debug, PartialEq)]
pub struct PartFrame(pub DAffine3);

/// Axial extent `[start, end]` of a part in its vessel's frame, mm.
#[derive(Component, Clone, Copy, Debug, PartialEq)]
pub struct PartSpan(pub f64, pub f64);

/// The resolved parameters that determine a part's or nozzle's patches. The
/// Geometry stage rebuilds patches exactly when this changes.
#[derive(Component, Clone, Debug, PartialEq)]
pub enum Shape {
    /// A part of the vessel.
    Part(PartGeometry),
    /// A nozzle, with its pad `(od, thickness)`.
    Nozzle(Nozzle, Option<(f64, f64)>),
}

/// A note's resolved anchor and text position, vessel frame, mm.
#[derive(Component, Clone, Copy, Debug, PartialEq)]
pub struct NoteAnchor {
    /// The target's anchor point.
    pub anchor: DVec3,
    /// Where the text sits.
    pub position: DVec3,
}

/// The exact surface of a patch, in its part's local frame (shared, immutable).
#[derive(Component, Clone, Debug, PartialEq)]
pub struct PatchSurface(pub Arc<Patch>);

/// The triangle mesh of a patch, in its part's local frame, packed (exact
/// positions, octahedral normals, narrow indices).
///
/// In a sparse set, like the other components later stages add to a patch or
/// a nozzle: adding it leaves the entity's table row in place, so a full build
/// that adds one to every patch moves no table rows.
#[derive(Component, Clone, Debug, PartialEq)]
#[component(storage = "SparseSet")]
pub struct PatchMesh(pub Arc<PackedMesh>);

/// The cavities round a patch's openings as its last meshing triangulated them
/// (see [`KeptCavities`]): handed to its next meshing, which takes those that
/// come out the same instead of triangulating them again. Absent on a patch
/// without openings.
#[derive(Component, Clone, Debug)]
#[component(storage = "SparseSet")]
pub struct PatchCavities(pub Arc<KeptCavities>);

/// A nozzle's (or a boot's) opening: where its neck (the boot's shell) meets its
/// host, computed once and used to trim both (the host patch gets a hole, the neck
/// its bottom edge).
#[derive(Component, Clone, Debug, PartialEq)]
#[component(storage = "SparseSet")]
pub struct Opening {
    /// The host patches the neck cuts, with how it trims each: one patch with a
    /// hole, or the two patches whose seam the opening crosses, with notches.
    pub hosts: Vec<(Entity, HostTrim)>,
    /// The nozzle's neck patch (the boot's shell patch).
    pub neck_patch: Entity,
    /// The intersection loop, in the host part's frame, with (u, v) on both patches.
    pub curve: Arc<IntersectionLoop>,
    /// The reinforcing pad's outer loop on the host, in the host part's frame.
    pub pad: Option<Arc<IntersectionLoop>>,
    /// The pad patch's trim: its outer loop and the neck's, with host (u, v) on
    /// the pad patch (a straight course's canonical copy, for a pad on a course:
    /// see `mesh::axial`).
    pub pad_trim: Option<(Arc<IntersectionLoop>, Arc<IntersectionLoop>)>,
}

/// The (u, v) region a patch is meshed within: its sides sampled from the edge
/// curves, with openings as holes or a trimmed bottom.
///
/// Change detection compares the fingerprint; the loops themselves are only
/// needed afterwards by the drawing views (silhouettes are cut by them), so they
/// are kept only while the model keeps views (see `Views`): a plant build does
/// not hold a second copy of every mesh boundary.
#[derive(Component, Clone, Debug, PartialEq)]
#[component(storage = "SparseSet")]
pub struct PatchRegion {
    /// 128-bit fingerprint of the loops' exact coordinates
    /// ([`Region::fingerprint`]).
    pub fingerprint: u128,
    /// The region, while views are kept.
    pub region: Option<Arc<Region>>,
}
