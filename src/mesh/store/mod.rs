//! Content-keyed stores: results shared by the exact bits of their inputs.
//!
//! `key` hashes inputs into 128-bit keys; `weak_table` keeps values by key as long
//! as something else holds them; `instances` is the Tessellate stage's table of
//! meshes equal by content; `shared_cuts` the Geometry stage's table of canonical
//! opening marches. (A patch's kept cavities, which only the mesher reads, are
//! `cdt::KeptCavities`.)

mod instances;
mod key;
mod shared_cuts;
mod weak_table;

pub use instances::{MeshInstances, mesh_key, mesh_key_of, surface_key};
pub(crate) use key::Key;
pub use shared_cuts::SharedCuts;
pub(in crate::mesh) use shared_cuts::shared_key;
pub use weak_table::WeakTable;
