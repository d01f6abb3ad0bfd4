//! Design files: the human-writable JSON format (`"format": "vesselcad/1"`), its
//! loading with exact error paths and unit conversion, its rule checks, and its
//! canonical save.
//!
//! This is where edits enter the data flow: a [`Design`] is checked here, then
//! spawned as ECS entities by the model; saving reads the entities back into a
//! [`Design`].

mod error;
mod io;
mod schema;
pub mod units;
mod validate;

pub use error::{DesignError, RuleViolation};
pub use io::{
    MAX_DESIGN_BYTES, decode_design, load, parse, parse_unchecked, read_design_bytes, save,
    to_canonical_json,
};
pub use schema::*;
pub use validate::{resolve, validate};
