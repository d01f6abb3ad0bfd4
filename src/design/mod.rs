//! Design files: the human-writable JSON format (`"format": "vesselcad/1"`), its
//! loading with exact error paths and unit conversion, its rule checks, and its
//! canonical save. The types themselves live in [`crate::format`], below the rules
//! that check them, and are re-exported here.
//!
//! This is where edits enter the data flow: a [`Design`] is checked here, then
//! spawned as ECS entities by the model; saving reads the entities back into a
//! [`Design`].

mod io;
mod validate;

pub use crate::format::schema::*;
pub use crate::format::units;
pub use crate::format::{DesignError, RuleViolation};
pub use io::{
    MAX_DESIGN_BYTES, decode_design, load, parse, parse_unchecked, read_design_bytes, save,
    to_canonical_json,
};
pub use validate::{resolve, validate};
