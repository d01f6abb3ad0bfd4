//! The `vesselcad/1` data model: the serde types a designer writes ([`schema`]),
//! the errors that name a value by its JSON path ([`error`]) and the inch to mm
//! conversion ([`units`]).
//!
//! A leaf of the data flow: the rules ([`crate::constraints`]) and the operating
//! figures ([`crate::operating`]) read these types, and [`crate::design`], which
//! loads, checks and saves design files, re-exports them under its own name.

pub mod error;
pub mod schema;
pub mod units;

pub use error::{DesignError, RuleViolation};
pub use schema::*;
