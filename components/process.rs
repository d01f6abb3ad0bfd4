//! Derived components of fabrication planning, kept live only while the model
//! has [`ProcessPlanning`] (its shop rules): a vessel's flat patterns and seam
//! layout ([`VesselFabPlan`]: developments, openings, seams, plates;
//! `fab::plan_vessel`, which keeps what an edit left unchanged from the
//! previous one) and its process plan on that layout (BOM, weld map,
//! operations in levels; `fab::process_plan`). Written by
//! `systems::update_process_plans`, for the vessels an edit resolved again.

use std::sync::Arc;

use bevy_ecs::component::Component;
use bevy_ecs::resource::Resource;

use crate::fab::{FabPlan, ProcessPlan, ShopRules};

/// The shop rules the process plans follow; while present, every vessel keeps
/// a [`VesselProcessPlan`].
#[derive(Resource, Clone, Debug)]
pub struct ProcessPlanning(pub Arc<ShopRules>);

/// A vessel's process plan, or why it could not be made.
#[derive(Component, Clone, Debug, PartialEq)]
pub struct VesselProcessPlan(pub Result<Arc<ProcessPlan>, String>);

/// A vessel's flat patterns and seam layout (plates by the rules' `plates`),
/// or why they could not be made.
#[derive(Component, Clone, Debug, PartialEq)]
pub struct VesselFabPlan(pub Result<Arc<FabPlan>, String>);
