//! Exact part geometry: functions from vessel-part parameters (mm, degrees) to the
//! rational NURBS patches of the part's outside surface, in the part's local frame.
//!
//! This sits between the parameters and the kernel in the data flow: the ECS
//! Geometry stage calls these builders for dirty parts, and every patch they return
//! carries the [`Analytic`] surface it lies on, which tests check points against and
//! later stages (views, intersections) can use exactly.
//!
//! Local frames: the part's axis is +Z. Every builder documents where its origin is.
//! Thickness is carried in the parameters for later use; the geometry is the outside
//! surface (plates such as saddle webs are their mid-surfaces).

mod analytic;
mod boot;
mod check;
mod error;
mod geometry;
mod patch;

pub mod heads;
mod legs;
mod lugs;
mod measure;
mod nozzle;
mod reducer;
mod saddle;
mod shell;
mod skirt;
pub mod tables;

pub use analytic::Analytic;
pub use boot::Boot;
pub use check::{MAX_DIMENSION, MIN_DIMENSION};
pub use error::PartError;
pub use geometry::PartGeometry;
pub use legs::{Legs, MAX_LEGS};
pub use lugs::{Lugs, MAX_LUGS};
pub use measure::{enclosed_volume, surface_area};
pub use nozzle::{Facing, FlangeType, Nozzle};
pub use patch::Patch;
pub use reducer::{Reducer, ReducerAlignment};
pub use saddle::Saddle;
pub use shell::Shell;
pub use skirt::Skirt;
