//! The streaming GLB writer: the same bytes as [`super::write_glb`], written
//! straight from the scene's meshes to the output without assembling the binary
//! buffer in memory — a plant's meshes are never held twice.
//!
//! Last stage of the data flow for large plants. Two passes over the scene: the
//! first lays the document out ([`super::gltf_document`] with buffers that only
//! count bytes, checking and encoding every distinct mesh on the way); the second
//! writes the header, the JSON chunk and the `BIN` chunk's views — stream by
//! stream (all positions, all normals, all indices, in scene order) — converting
//! each mesh's `f64` mm to `f32` m (or quantizing it) as it goes through a
//! buffered writer.

use std::io::{BufWriter, Write};
use std::path::Path;

use super::error::ExportError;
use super::glb::write_glb_with;
use super::glb::{
    CHUNK_BIN, CHUNK_HEADER_LEN, CHUNK_JSON, HEADER_LEN, MAGIC, VERSION, padded, temporary_path,
};
use super::glb_options::{Compression, GlbOptions};
use super::gltf_buffers::MeshBuffers;
use super::gltf_document::document_with;
use super::gltf_encoding::Stream;
use super::scene::Scene;

/// Writes the scene as GLB to `out`, streaming the mesh data; returns the bytes
/// written. The bytes equal [`super::write_glb`]'s.
///
/// # Errors
///
/// As [`super::write_glb`], and [`ExportError::Io`] (naming `name`) when `out`
/// fails.
pub fn stream_glb(scene: &Scene, out: impl Write, name: &Path) -> Result<u64, ExportError> {
    stream_glb_with(scene, &GlbOptions::default(), out, name)
}

/// Writes the scene as GLB with `options` to `out`; returns the bytes written,
/// which equal [`super::write_glb_with`]'s. Uncompressed files stream the mesh
/// data; a compressed file, whose layout depends on the encoded bytes, is
/// assembled in memory first (it is a fraction of the meshes' size).
///
/// # Errors
///
/// As [`stream_glb`].
pub fn stream_glb_with(
    scene: &Scene,
    options: &GlbOptions,
    mut out: impl Write,
    name: &Path,
) -> Result<u64, ExportError> {
    let io = |source| ExportError::Io {
        path: name.to_path_buf(),
        source,
    };
    if options.compress != Compression::None {
        let bytes = write_glb_with(scene, options)?;
        out.write_all(&bytes).map_err(io)?;
        return Ok(bytes.len() as u64);
    }
    let document = document_with(scene, MeshBuffers::layout_only(*options))?;
    let bin_len: usize = document
        .root
        .buffers
        .first()
        .map_or(0, |b| b.byte_length.0 as usize);
    let json = document.json_bytes()?;
    let json_padded = padded(json.len());
    let bin_padded = padded(bin_len);
    let mut total = HEADER_LEN + CHUNK_HEADER_LEN + json_padded;
    if bin_len > 0 {
        total += CHUNK_HEADER_LEN + bin_padded;
    }
    let total_u32 = u32::try_from(total).map_err(|_| ExportError::TooLarge {
        bytes: total as u64,
    })?;
    let mut w = BufWriter::with_capacity(1 << 20, out);
    let mut write = |bytes: &[u8]| w.write_all(bytes);
    (|| -> std::io::Result<()> {
        for word in [MAGIC, VERSION, total_u32] {
            write(&word.to_le_bytes())?;
        }
        write(&(json_padded as u32).to_le_bytes())?;
        write(&CHUNK_JSON.to_le_bytes())?;
        write(&json)?;
        write(&vec![b' '; json_padded - json.len()])?;
        if bin_len == 0 {
            return Ok(());
        }
        write(&(bin_padded as u32).to_le_bytes())?;
        write(&CHUNK_BIN.to_le_bytes())?;
        let mut chunk: Vec<u8> = Vec::with_capacity(1 << 16);
        let mut written = 0;
        // Stream by stream, as the views lie in the buffer, each padded to 4.
        for stream in Stream::ALL {
            if stream == Stream::Instances {
                let instances = &document.buffers.instances;
                write(instances)?;
                write(&vec![0; padded(instances.len()) - instances.len()])?;
                written += padded(instances.len());
                continue;
            }
            let mut length = 0;
            for (mesh, encoding) in &document.meshes {
                chunk.clear();
                encoding.write(stream, mesh, &mut chunk);
                length += chunk.len();
                write(&chunk)?;
            }
            write(&vec![0; padded(length) - length])?;
            written += padded(length);
        }
        write(&vec![0; bin_padded - written])?;
        Ok(())
    })()
    .map_err(io)?;
    w.flush().map_err(io)?;
    Ok(total as u64)
}

/// Streams the scene's GLB to `path` atomically (a temporary file beside it,
/// renamed over `path`); returns the bytes written.
///
/// # Errors
///
/// As [`stream_glb`].
pub fn stream_glb_to(scene: &Scene, path: &Path) -> Result<u64, ExportError> {
    stream_glb_with_to(scene, &GlbOptions::default(), path)
}

/// [`stream_glb_with`] to `path` atomically; returns the bytes written.
///
/// # Errors
///
/// As [`stream_glb`].
pub fn stream_glb_with_to(
    scene: &Scene,
    options: &GlbOptions,
    path: &Path,
) -> Result<u64, ExportError> {
    let tmp = temporary_path(path);
    let io = |path: &Path| {
        let path = path.to_path_buf();
        move |source| ExportError::Io { path, source }
    };
    let file = std::fs::File::create(&tmp).map_err(io(&tmp))?;
    let written = stream_glb_with(scene, options, &file, &tmp).and_then(|n| {
        file.sync_all().map_err(io(&tmp))?;
        Ok(n)
    });
    match written {
        Ok(n) => {
            std::fs::rename(&tmp, path).map_err(io(path))?;
            Ok(n)
        }
        Err(e) => {
            // Best effort: the temporary file is useless now.
            let _ = std::fs::remove_file(&tmp);
            Err(e)
        }
    }
}
