//! 3D Tiles 1.1: a plant as one GLB per vessel and a `tileset.json` that
//! places them.
//!
//! The tileset's frame is the plant's, in metres, Z-up: the glTF content is
//! Y-up (the writer's root node turns the plant's Z-up into glTF's), and 3D
//! Tiles turns glTF's Y-up back into Z-up. The root tile has no content, a
//! bounding box holding every vessel, `ADD` refinement and a geometric error of
//! its largest vessel's diagonal (showing nothing misses at most that); each
//! vessel is a child tile with its GLB (`<tag>.glb`), the box of its vertices,
//! and a geometric error of the meshing tolerance (a leaf: nothing finer).
//! One level of detail: a coarser tolerance would be another file per vessel.

use std::path::{Path, PathBuf};

use glam::DVec3;
use serde_json::{Value, json};

use super::error::ExportError;
use super::glb::{write_bytes_to, write_glb_with};
use super::glb_options::GlbOptions;
use super::scene::{Scene, SceneVessel};

/// Name of the tileset file.
pub const TILESET: &str = "tileset.json";

/// Writes one GLB per vessel of `scene` (with `options`) and `tileset.json`
/// into `dir` (created if missing); `tolerance` (mm) is each vessel tile's
/// geometric error. Returns the files written, the tileset last.
///
/// # Errors
///
/// As [`write_glb_with`], and [`ExportError::Io`] when a file or the directory
/// cannot be written.
pub fn write_tiles(
    scene: &Scene,
    options: &GlbOptions,
    tolerance: f64,
    dir: &Path,
) -> Result<Vec<PathBuf>, ExportError> {
    std::fs::create_dir_all(dir).map_err(|source| ExportError::Io {
        path: dir.to_path_buf(),
        source,
    })?;
    let mut files = Vec::new();
    let mut children = Vec::new();
    let (mut lo, mut hi) = (DVec3::INFINITY, DVec3::NEG_INFINITY);
    let mut largest = 0.0f64;
    for vessel in &scene.vessels {
        let Some((vlo, vhi)) = bounds(vessel) else {
            continue;
        };
        let uri = format!("{}.glb", file_stem(&vessel.tag));
        let one = Scene {
            vessels: vec![vessel.clone()],
        };
        let path = dir.join(&uri);
        write_bytes_to(&write_glb_with(&one, options)?, &path)?;
        files.push(path);
        (lo, hi) = (lo.min(vlo), hi.max(vhi));
        largest = largest.max((vhi - vlo).length());
        children.push(json!({
            "boundingVolume": { "box": box_of(vlo, vhi) },
            "geometricError": tolerance * 1e-3,
            "content": { "uri": uri },
            "extras": { "tag": vessel.tag },
        }));
    }
    let mut root = json!({
        "refine": "ADD",
        "geometricError": largest,
        "children": children,
    });
    if lo.x <= hi.x {
        root["boundingVolume"] = json!({ "box": box_of(lo, hi) });
    } else {
        root["boundingVolume"] = json!({ "box": box_of(DVec3::ZERO, DVec3::ZERO) });
    }
    let tileset = json!({
        "asset": { "version": "1.1", "generator": format!("vesselcad {}", env!("CARGO_PKG_VERSION")) },
        "geometricError": largest,
        "root": root,
    });
    let path = dir.join(TILESET);
    write_bytes_to(&serde_json::to_vec_pretty(&tileset)?, &path)?;
    files.push(path);
    Ok(files)
}

/// The box of a vessel's vertices in the plant frame, metres; `None` without
/// vertices.
fn bounds(vessel: &SceneVessel) -> Option<(DVec3, DVec3)> {
    let (mut lo, mut hi) = (DVec3::INFINITY, DVec3::NEG_INFINITY);
    for node in &vessel.nodes {
        let frame = vessel.frame * node.frame;
        for patch in &node.patches {
            if patch.mesh.index_count() == 0 {
                continue;
            }
            for p in patch.mesh.positions() {
                let q = frame.transform_point3(p) * 1e-3;
                (lo, hi) = (lo.min(q), hi.max(q));
            }
        }
    }
    (lo.x <= hi.x).then_some((lo, hi))
}

/// A 3D Tiles box: centre, then the three half-axes.
fn box_of(lo: DVec3, hi: DVec3) -> Value {
    let c = (lo + hi) / 2.0;
    // A flat box is widened a hair so it still has a volume.
    let h = ((hi - lo) / 2.0).max(DVec3::splat(1e-6));
    json!([c.x, c.y, c.z, h.x, 0.0, 0.0, 0.0, h.y, 0.0, 0.0, 0.0, h.z])
}

/// A tag as a file stem: characters outside `[A-Za-z0-9._-]` become `_`.
fn file_stem(tag: &str) -> String {
    tag.chars()
        .map(|c| {
            if c.is_ascii_alphanumeric() || matches!(c, '.' | '_' | '-') {
                c
            } else {
                '_'
            }
        })
        .collect()
}
