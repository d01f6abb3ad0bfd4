//! Outputs: the exchange files written from the model.
//!
//! The model assembles a [`Scene`] — the plant → vessel → part/nozzle → patch tree
//! with frames, metadata and meshes — and each exporter writes it. Exporters know
//! nothing of ECS.
//!
//! - [`build_scene`] builds a scene directly from a design (resolve, patches, meshes
//!   in parallel): the non-incremental reference and benchmark baseline. Node
//!   metadata comes from [`vessel_extras`], [`part_extras`] and [`nozzle_extras`].
//! - [`write_glb`] / [`write_glb_to`] write a scene as binary glTF 2.0 (Y-up,
//!   metres, deterministic bytes); [`stream_glb`] / [`stream_glb_to`] write the
//!   same bytes straight from the meshes, without a second copy of them. Equal
//!   meshes are written once; [`GlbOptions`] adds `KHR_mesh_quantization` and
//!   `EXT_meshopt_compression` ([`write_glb_with`], [`stream_glb_with`]).
//! - [`write_tiles`] / [`TilesWriter`] write 3D Tiles 1.1: a GLB per vessel and
//!   level of detail (coarse to fine, `REPLACE` refinement) and a `tileset.json`.
//! - [`write_delta_glb`] writes only the changed parts of a scene, keyed by their
//!   stable ids, for live viewers.

mod coloured;
mod delta;
mod direct;
mod error;
mod extras;
mod glb;
mod glb_options;
mod glb_stream;
mod gltf_buffers;
mod gltf_document;
mod gltf_encoding;
mod gltf_instancing;
mod gltf_materials;
mod gltf_welding;
mod granularity;
mod openings;
mod scene;
mod tiles;

pub use coloured::{ColouredMesh, coloured_glb};
pub use delta::{delta_scene, node_id, scene_ids, write_delta_glb};
pub use direct::{build_scene, patch_name};
pub use error::ExportError;
pub use extras::{nozzle_extras, part_extras, vessel_extras};
pub use glb::{glb_container, write_glb, write_glb_to, write_glb_with};
pub use glb_options::{Compression, GlbOptions, Normals, quantization_budget};
pub use glb_stream::{stream_glb, stream_glb_to, stream_glb_with, stream_glb_with_to};
pub use gltf_document::{PLANT_NODE, PLANT_ROTATION};
pub use gltf_encoding::quantization_bound;
pub use granularity::{Granularity, MERGED_PATCH, merge_scene};
pub use openings::{Opening, SharedMarches, cut_opening, openings};
pub use scene::{Scene, SceneNode, SceneNodeKind, ScenePatch, SceneVessel};
pub use tiles::{TILESET, TilesWriter, write_tiles};
