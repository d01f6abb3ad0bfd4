//! The one error type of the exporters: why a scene could not be built from a
//! design, or written as a file.
//!
//! Builders ([`build_scene`](super::build_scene)) fail on an invalid design, bad
//! tessellation options or a part that cannot be built; writers
//! ([`write_glb`](super::write_glb)) fail on meshes that cannot be written (non-finite
//! numbers, indices out of range, a file over the format's 4 GiB limit) or on I/O.

use std::path::PathBuf;

use thiserror::Error;

use crate::design::DesignError;
use crate::mesh::OptionsError;
use crate::parts::PartError;

/// Why an export failed.
#[derive(Debug, Error)]
pub enum ExportError {
    /// The design breaks its rules; every violation is listed.
    #[error("invalid design: {0}")]
    Design(#[from] DesignError),
    /// The tessellation options are out of range.
    #[error("{0}")]
    Options(#[from] OptionsError),
    /// A part or nozzle of a resolved design could not build its patches.
    #[error("{entity}: cannot build patches: {source}")]
    Part {
        /// Stable id of the part or nozzle, `tag/id`.
        entity: String,
        /// The part builder's error.
        source: PartError,
    },
    /// A nozzle opening could not be cut, or a patch could not be meshed.
    #[error("{entity}: cannot mesh: {message}")]
    Mesh {
        /// Stable id of the part or nozzle, `tag/id`.
        entity: String,
        /// What went wrong.
        message: String,
    },
    /// A mesh holds a NaN or infinite position or normal, or a zero normal.
    #[error("{entity}/{patch}: vertex {vertex} has a non-finite position or a degenerate normal")]
    NonFiniteVertex {
        /// Stable id of the part or nozzle, `tag/id`.
        entity: String,
        /// Patch name.
        patch: String,
        /// Index of the vertex in the patch mesh.
        vertex: usize,
    },
    /// A mesh's normals and positions differ in count, its index count is not a
    /// multiple of 3, or an index points past its vertices.
    #[error("{entity}/{patch}: malformed mesh: {rule}")]
    MalformedMesh {
        /// Stable id of the part or nozzle, `tag/id`.
        entity: String,
        /// Patch name.
        patch: String,
        /// What is wrong.
        rule: String,
    },
    /// The binary data or the whole file exceeds the GLB limit of 4 GiB.
    #[error("GLB too large: {bytes} bytes (the format's limit is 4 GiB)")]
    TooLarge {
        /// Size that would have been written, bytes.
        bytes: u64,
    },
    /// The glTF JSON could not be serialized.
    #[error("cannot serialize glTF JSON: {0}")]
    Json(#[from] serde_json::Error),
    /// The levels of detail of a tileset are not a run of tolerances from
    /// coarse to fine, or a level's scene does not hold the same vessels.
    #[error("levels of detail: {rule}")]
    Levels {
        /// What is wrong, naming the level and value.
        rule: String,
    },
    /// Writing the file failed.
    #[error("cannot write {}: {source}", path.display())]
    Io {
        /// The file.
        path: PathBuf,
        /// The I/O error.
        source: std::io::Error,
    },
}
