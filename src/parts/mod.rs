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
mod check;
mod error;
mod patch;

pub mod heads;
mod reducer;
mod shell;
pub mod tables;

pub use analytic::Analytic;
pub use check::{MAX_DIMENSION, MIN_DIMENSION};
pub use error::PartError;
pub use patch::Patch;
pub use reducer::{Reducer, ReducerAlignment};
pub use shell::Shell;
