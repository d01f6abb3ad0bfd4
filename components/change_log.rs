//! The stable ids (`tag`, `tag/id`) that changed or were removed, recorded by
//! `systems::collect_changes` for exporters and viewers.

use std::collections::BTreeSet;

use bevy_ecs::resource::Resource;

/// Stable ids changed and removed since the log was last drained.
#[derive(Resource, Default, Debug, Clone, PartialEq, Eq)]
pub struct ChangeLog {
    /// Ids of vessels, parts and nozzles whose frame or geometry changed.
    pub changed: BTreeSet<String>,
    /// Ids of entities that were removed.
    pub removed: BTreeSet<String>,
}
