//! Fabrication: from the design model to the shop floor.
//!
//! The process plan of one vessel ([`process::process_plan`]): its bill of materials ([`bom`]),
//! the weld map ([`welds`]: UW-3 categories, lengths on the exact curves of
//! [`weld_curves`], weld metal by the preparations of [`weld_prep`]), and its
//! operations in precedence levels ([`operations`], [`levels`]) from the shop
//! rules as data ([`shop_rules`], `data/shop_rules.json`); written as a
//! traveler ([`traveler`]), a weld-map GLB ([`weld_glb`]) and sheet
//! ([`weld_svg`]).

pub mod bom;
pub mod levels;
pub mod operations;
pub mod plan_error;
pub mod plate_size;
pub mod process;
pub mod process_files;
pub mod shop_rules;
pub mod traveler;
pub mod weld_curves;
pub mod weld_glb;
pub mod weld_prep;
pub mod weld_svg;
pub mod welds;

pub use plan_error::PlanError;
pub use process::{ProcessPlan, process_plan};
pub use shop_rules::ShopRules;
