//! The exporters' view of a plant: a tree of vessels, their parts and nozzles, and
//! the meshed patches of each, with frames and metadata. Built by the model from
//! ECS data (or directly from resolved designs); read by the glTF writer.

use std::sync::Arc;

use glam::DAffine3;
use serde_json::Value;

use crate::mesh::PackedMesh;

/// A whole plant, vessels in design order.
#[derive(Clone, Debug, Default)]
pub struct Scene {
    /// The vessels.
    pub vessels: Vec<SceneVessel>,
}

/// One vessel.
#[derive(Clone, Debug)]
pub struct SceneVessel {
    /// Tag: the node name and stable id.
    pub tag: String,
    /// Vessel local frame → plant frame, mm.
    pub frame: DAffine3,
    /// Metadata for `extras`: kind, design conditions, resolved figures (mm).
    pub extras: Value,
    /// Parts then nozzles, in design order.
    pub nodes: Vec<SceneNode>,
}

/// What a scene node stands for.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SceneNodeKind {
    /// A part (shell, head, reducer, support, boot).
    Part,
    /// A nozzle.
    Nozzle,
}

/// One part or nozzle.
#[derive(Clone, Debug)]
pub struct SceneNode {
    /// Part id or nozzle mark: the node name; the stable id is `tag/id`.
    pub id: String,
    /// Part or nozzle.
    pub kind: SceneNodeKind,
    /// Local frame → vessel frame, mm.
    pub frame: DAffine3,
    /// Metadata for `extras`: kind and resolved parameters (mm).
    pub extras: Value,
    /// Meshed patches in build order.
    pub patches: Vec<ScenePatch>,
}

/// One meshed patch.
#[derive(Clone, Debug)]
pub struct ScenePatch {
    /// Patch name within its part, e.g. `"crown"` (with its index if > 0).
    pub name: String,
    /// The mesh, in the part's local frame, mm.
    pub mesh: Arc<PackedMesh>,
}
