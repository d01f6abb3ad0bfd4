//! Derived components of fabrication planning: a vessel's process plan (BOM,
//! weld map, operations in levels; `fab::process_plan`), kept live only while
//! the model has [`ProcessPlanning`] (its shop rules). Written by
//! `systems::update_process_plans`, for the vessels an edit resolved again.

use std::sync::Arc;

use bevy_ecs::component::Component;
use bevy_ecs::resource::Resource;

use crate::fab::{ProcessPlan, ShopRules};

/// The shop rules the process plans follow; while present, every vessel keeps
/// a [`VesselProcessPlan`].
#[derive(Resource, Clone, Debug)]
pub struct ProcessPlanning(pub Arc<ShopRules>);

/// A vessel's process plan, or why it could not be made.
#[derive(Component, Clone, Debug, PartialEq)]
pub struct VesselProcessPlan(pub Result<Arc<ProcessPlan>, String>);
