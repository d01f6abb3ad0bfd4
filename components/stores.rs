//! What the model keeps between runs to redo less: the meshes in use by content
//! ([`Instances`]), the canonical cuts ([`CutTable`]), the hosts each opening was
//! cut in ([`OpeningHosts`]) and the vessels by tag ([`VesselIndex`]).

use std::collections::HashMap;

use bevy_ecs::entity::Entity;
use bevy_ecs::resource::Resource;
use rustc_hash::FxHashMap;

use crate::mesh::{MeshInstances, SharedCuts};

/// The meshes in use by content (see [`MeshInstances`]): the Tessellate stage's
/// memory of what it has meshed.
#[derive(Resource, Debug, Default)]
pub struct Instances(pub MeshInstances);

/// The host patches each nozzle's opening was last cut in (to re-lay-out a host
/// patch whose opening moved away or disappeared).
#[derive(Resource, Default, Debug)]
pub struct OpeningHosts(pub FxHashMap<Entity, Vec<Entity>>);

/// The canonical cuts the model's openings keep, shared by every opening cut
/// from the same march (see `mesh::shared_cuts`).
#[derive(Resource, Default, Debug)]
pub struct CutTable(pub SharedCuts);

/// Vessel entities by tag.
#[derive(Resource, Default, Debug)]
pub(crate) struct VesselIndex(pub HashMap<String, Entity>);
