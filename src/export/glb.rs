//! The GLB writer: a [`Scene`] as one binary glTF 2.0 file.
//!
//! The last stage of the data flow for viewers. The document (node tree, meshes,
//! materials, buffer) comes from [`super::gltf_document`]; this file frames it as a
//! GLB container: a 12-byte header (`glTF`, version 2, total length), a `JSON` chunk
//! padded with spaces to 4 bytes and, when the scene has triangles, a `BIN` chunk
//! padded with zeros. Nothing in the bytes depends on time or hashing: the same
//! scene always gives the same file.

use std::io::Write;
use std::path::{Path, PathBuf};

use super::error::ExportError;
use super::glb_options::GlbOptions;
use super::gltf_document::document;
use super::scene::Scene;

/// `glTF`, the GLB magic.
pub(super) const MAGIC: u32 = 0x4654_6C67;
/// The container version.
pub(super) const VERSION: u32 = 2;
/// Chunk type of the JSON chunk, `JSON`.
pub(super) const CHUNK_JSON: u32 = 0x4E4F_534A;
/// Chunk type of the binary chunk, `BIN\0`.
pub(super) const CHUNK_BIN: u32 = 0x004E_4942;
/// Bytes of the file header.
pub(super) const HEADER_LEN: usize = 12;
/// Bytes of a chunk header.
pub(super) const CHUNK_HEADER_LEN: usize = 8;

/// The scene as GLB bytes with the default [`GlbOptions`] (equal meshes
/// shared, `f32` data): Y-up, metres, one buffer, deterministic.
///
/// # Errors
///
/// [`ExportError::MalformedMesh`] or [`ExportError::NonFiniteVertex`] for a mesh
/// that cannot be written, [`ExportError::TooLarge`] past the format's 4 GiB,
/// [`ExportError::Json`] if the document cannot be serialized.
pub fn write_glb(scene: &Scene) -> Result<Vec<u8>, ExportError> {
    write_glb_with(scene, &GlbOptions::default())
}

/// The scene as GLB bytes written with `options` (reuse, quantization,
/// compression): Y-up, metres, deterministic.
///
/// # Errors
///
/// As [`write_glb`].
pub fn write_glb_with(scene: &Scene, options: &GlbOptions) -> Result<Vec<u8>, ExportError> {
    let document = document(scene, options)?;
    let json = document.json_bytes()?;
    glb_container(&json, &document.buffers.bin)
}

/// The GLB container of a glTF JSON text and its binary buffer: the 12-byte
/// header, the JSON chunk padded with spaces, and the BIN chunk (left out when
/// `bin` is empty) padded with zeros. Every GLB vesselcad writes is framed here.
///
/// # Errors
///
/// [`ExportError::TooLarge`] past the format's 4 GiB.
pub fn glb_container(json: &[u8], bin: &[u8]) -> Result<Vec<u8>, ExportError> {
    let json_len = padded(json.len());
    let bin_len = padded(bin.len());
    let mut total = HEADER_LEN + CHUNK_HEADER_LEN + json_len;
    if !bin.is_empty() {
        total += CHUNK_HEADER_LEN + bin_len;
    }
    let too_large = || ExportError::TooLarge {
        bytes: total as u64,
    };
    let total_u32 = u32::try_from(total).map_err(|_| too_large())?;
    let mut out = Vec::with_capacity(total);
    for word in [MAGIC, VERSION, total_u32] {
        out.extend_from_slice(&word.to_le_bytes());
    }
    push_chunk(&mut out, CHUNK_JSON, json, json_len, b' ');
    if !bin.is_empty() {
        push_chunk(&mut out, CHUNK_BIN, bin, bin_len, 0);
    }
    Ok(out)
}

/// Writes the scene's GLB to `path` atomically: the bytes go to a temporary file
/// beside it, which is then renamed over `path`.
///
/// # Errors
///
/// As [`write_glb`], and [`ExportError::Io`] when the file cannot be written.
pub fn write_glb_to(scene: &Scene, path: &Path) -> Result<(), ExportError> {
    write_bytes_to(&write_glb(scene)?, path)
}

/// Writes `bytes` to `path` atomically (a temporary file beside it, renamed
/// over `path`).
///
/// # Errors
///
/// [`ExportError::Io`] when the file cannot be written.
pub(super) fn write_bytes_to(bytes: &[u8], path: &Path) -> Result<(), ExportError> {
    let tmp = temporary_path(path);
    let io = |path: &Path| {
        let path = path.to_path_buf();
        move |source| ExportError::Io { path, source }
    };
    let written = std::fs::File::create(&tmp).and_then(|mut file| {
        file.write_all(bytes)?;
        file.sync_all()
    });
    if let Err(source) = written {
        // Best effort: the temporary file is useless now.
        let _ = std::fs::remove_file(&tmp);
        return Err(io(&tmp)(source));
    }
    std::fs::rename(&tmp, path).map_err(io(path))
}

/// `path` with `.tmp` appended to its file name, in the same directory (so the
/// rename stays on one file system).
pub(super) fn temporary_path(path: &Path) -> PathBuf {
    let mut name = path.file_name().unwrap_or_default().to_os_string();
    name.push(".tmp");
    path.with_file_name(name)
}

/// `len` rounded up to a multiple of 4.
pub(super) fn padded(len: usize) -> usize {
    len.div_ceil(4) * 4
}

/// Appends a chunk: length, type, data, padding to `len` with `pad`.
fn push_chunk(out: &mut Vec<u8>, kind: u32, data: &[u8], len: usize, pad: u8) {
    // `len` fits in u32: the whole file was checked to.
    out.extend_from_slice(&(len as u32).to_le_bytes());
    out.extend_from_slice(&kind.to_le_bytes());
    out.extend_from_slice(data);
    out.resize(out.len() + len - data.len(), pad);
}
