//! Content-keyed stores: results shared by the exact bits of their inputs.
//!
//! `key` hashes inputs into 128-bit keys; `weak_table` keeps values by key as long
//! as something else holds them; `instances` is the Tessellate stage's table of
//! meshes equal by content. (The Geometry stage's table of canonical opening
//! marches is `cut::SharedCuts`; a patch's kept cavities, which only the mesher reads, are
//! `cdt::KeptCavities`.)

mod instances;
mod key;
mod weak_table;

pub use instances::{MeshInstances, mesh_key, mesh_key_of, surface_key};
pub(crate) use key::Key;
pub use weak_table::WeakTable;
