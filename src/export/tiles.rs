//! 3D Tiles 1.1: a plant as one GLB per vessel and level of detail, and a
//! `tileset.json` that places them and says when each level is fine enough.
//!
//! The tileset's frame is the plant's, in metres, Z-up: the glTF content is
//! Y-up (the writer's root node turns the plant's Z-up into glTF's), and 3D
//! Tiles turns glTF's Y-up back into Z-up. The root tile has no content, a
//! bounding box holding every vessel, `ADD` refinement and a geometric error of
//! its largest vessel's diagonal (showing nothing misses at most that).
//!
//! Each vessel is a chain of tiles, one per level of detail, coarse to fine:
//! the coarsest is a child of the root, each finer level the only child of the
//! one before with `REPLACE` refinement (a viewer shows a level, or its child
//! instead once the level's error would be seen). A tile's content is the
//! vessel meshed at the level's chordal tolerance (`<tag>.glb` with one level,
//! `<tag>.lod<i>.glb` with several, 0 the coarsest), its geometric error that
//! tolerance (the most any point of the drawn surface is off the exact one),
//! and its box the box of the vessel's vertices over all levels (so a parent's
//! box holds its children's).
//!
//! Levels are written one at a time by [`TilesWriter`] (the caller may build
//! each level's model, write it and drop it); [`write_tiles`] writes one level.
//!
//! Choice: one file per level in the tileset, not `MSFT_lod` in one GLB. A
//! viewer then fetches only the levels it shows (a far plant never downloads
//! its fine meshes, the point of levels on a plant); the tileset is the standard
//! index of 3D Tiles viewers (CesiumJS, 3DTilesRendererJS, the bundled
//! `tiles.js`), while `MSFT_lod` is a vendor extension three.js's `GLTFLoader`
//! ignores, and one GLB would hold every level.

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
    let mut writer = TilesWriter::new(dir, &[tolerance])?;
    writer.add_level(scene, options)?;
    writer.finish()
}

/// Writes a tileset level by level: [`new`](Self::new) with the tolerances,
/// [`add_level`](Self::add_level) once per tolerance in that order (coarse to
/// fine), then [`finish`](Self::finish) writes `tileset.json`.
#[derive(Debug)]
pub struct TilesWriter {
    /// The directory written into.
    dir: PathBuf,
    /// The levels' chordal tolerances, mm, coarse to fine.
    tolerances: Vec<f64>,
    /// The vessels, in the first level's order.
    vessels: Vec<VesselTiles>,
    /// The files written so far.
    files: Vec<PathBuf>,
    /// How many levels are written.
    written: usize,
}

/// What the tileset says of one vessel.
#[derive(Debug)]
struct VesselTiles {
    /// Its tag.
    tag: String,
    /// The box of its vertices over the levels written, plant frame, m.
    bounds: Option<(DVec3, DVec3)>,
    /// Per level, the file holding it (`None`: no vertices at that level).
    uris: Vec<Option<String>>,
}

impl TilesWriter {
    /// A writer into `dir` (created if missing) for levels of these chordal
    /// tolerances, mm, coarse to fine.
    ///
    /// # Errors
    ///
    /// [`ExportError::Levels`] when there is no level, a tolerance is not a
    /// positive number, or one is not smaller than the one before;
    /// [`ExportError::Io`] when the directory cannot be made.
    pub fn new(dir: &Path, tolerances: &[f64]) -> Result<Self, ExportError> {
        if tolerances.is_empty() {
            return Err(ExportError::Levels {
                rule: "at least one tolerance is needed".into(),
            });
        }
        for (i, &t) in tolerances.iter().enumerate() {
            if !(t.is_finite() && t > 0.0) {
                return Err(ExportError::Levels {
                    rule: format!("level {i}: tolerance {t} mm is not a positive number"),
                });
            }
            if i > 0 && t >= tolerances[i - 1] {
                return Err(ExportError::Levels {
                    rule: format!(
                        "level {i}: tolerance {t} mm is not finer than level {}'s {} mm \
                         (levels go from coarse to fine)",
                        i - 1,
                        tolerances[i - 1]
                    ),
                });
            }
        }
        std::fs::create_dir_all(dir).map_err(|source| ExportError::Io {
            path: dir.to_path_buf(),
            source,
        })?;
        Ok(Self {
            dir: dir.to_path_buf(),
            tolerances: tolerances.to_vec(),
            vessels: Vec::new(),
            files: Vec::new(),
            written: 0,
        })
    }

    /// The tolerance of the next level to add, mm; `None` once all are added.
    pub fn next_tolerance(&self) -> Option<f64> {
        self.tolerances.get(self.written).copied()
    }

    /// Writes the next level: one GLB per vessel of `scene` (meshed at that
    /// level's tolerance; `options` should quantize within the level's budget).
    ///
    /// # Errors
    ///
    /// [`ExportError::Levels`] when every level is written already or `scene`'s
    /// vessels are not the first level's (same tags, same order); as
    /// [`write_glb_with`] and [`ExportError::Io`] for a file.
    pub fn add_level(&mut self, scene: &Scene, options: &GlbOptions) -> Result<(), ExportError> {
        let level = self.written;
        let Some(tolerance) = self.next_tolerance() else {
            return Err(ExportError::Levels {
                rule: format!("all {} level(s) are written already", self.tolerances.len()),
            });
        };
        if level == 0 {
            self.vessels = scene
                .vessels
                .iter()
                .map(|v| VesselTiles {
                    tag: v.tag.clone(),
                    bounds: None,
                    uris: Vec::new(),
                })
                .collect();
        } else {
            let same = scene.vessels.len() == self.vessels.len()
                && scene
                    .vessels
                    .iter()
                    .zip(&self.vessels)
                    .all(|(a, b)| a.tag == b.tag);
            if !same {
                return Err(ExportError::Levels {
                    rule: format!(
                        "level {level} ({tolerance} mm) has vessels [{}], level 0 [{}]",
                        tags(scene.vessels.iter().map(|v| v.tag.as_str())),
                        tags(self.vessels.iter().map(|v| v.tag.as_str())),
                    ),
                });
            }
        }
        let several = self.tolerances.len() > 1;
        for (vessel, tiles) in scene.vessels.iter().zip(&mut self.vessels) {
            let Some((lo, hi)) = bounds(vessel) else {
                tiles.uris.push(None);
                continue;
            };
            let stem = file_stem(&vessel.tag);
            let uri = if several {
                format!("{stem}.lod{level}.glb")
            } else {
                format!("{stem}.glb")
            };
            let one = Scene {
                vessels: vec![vessel.clone()],
            };
            let path = self.dir.join(&uri);
            write_bytes_to(&write_glb_with(&one, options)?, &path)?;
            self.files.push(path);
            tiles.bounds = Some(match tiles.bounds {
                Some((l, h)) => (l.min(lo), h.max(hi)),
                None => (lo, hi),
            });
            tiles.uris.push(Some(uri));
        }
        self.written += 1;
        Ok(())
    }

    /// Writes `tileset.json`; returns every file written, the tileset last.
    ///
    /// # Errors
    ///
    /// [`ExportError::Levels`] when a level was not added; [`ExportError::Io`]
    /// when the file cannot be written.
    pub fn finish(mut self) -> Result<Vec<PathBuf>, ExportError> {
        if let Some(t) = self.next_tolerance() {
            return Err(ExportError::Levels {
                rule: format!(
                    "level {} ({t} mm) was not written ({} of {} are)",
                    self.written,
                    self.written,
                    self.tolerances.len()
                ),
            });
        }
        let (mut lo, mut hi) = (DVec3::INFINITY, DVec3::NEG_INFINITY);
        let mut largest = 0.0f64;
        let mut children = Vec::new();
        for vessel in &self.vessels {
            let Some((vlo, vhi)) = vessel.bounds else {
                continue;
            };
            (lo, hi) = (lo.min(vlo), hi.max(vhi));
            largest = largest.max((vhi - vlo).length());
            if let Some(tile) = chain(vessel, &self.tolerances, box_of(vlo, vhi)) {
                children.push(tile);
            }
        }
        let mut root = json!({
            "refine": "ADD",
            "geometricError": largest,
            "children": children,
        });
        root["boundingVolume"] = if lo.x <= hi.x {
            json!({ "box": box_of(lo, hi) })
        } else {
            json!({ "box": box_of(DVec3::ZERO, DVec3::ZERO) })
        };
        let tileset = json!({
            "asset": { "version": "1.1", "generator": format!("vesselcad {}", env!("CARGO_PKG_VERSION")) },
            "geometricError": largest,
            "root": root,
        });
        let path = self.dir.join(TILESET);
        write_bytes_to(&serde_json::to_vec_pretty(&tileset)?, &path)?;
        self.files.push(path);
        Ok(self.files)
    }
}

/// A vessel's tiles, coarse to fine, each finer one the child of the one
/// before (`REPLACE`); levels without vertices are left out. `None` when no
/// level has any.
fn chain(vessel: &VesselTiles, tolerances: &[f64], bounding: Value) -> Option<Value> {
    let mut tile: Option<Value> = None;
    for (uri, &tolerance) in vessel.uris.iter().zip(tolerances).rev() {
        let Some(uri) = uri else {
            continue;
        };
        let mut t = json!({
            "boundingVolume": { "box": bounding.clone() },
            "geometricError": tolerance * 1e-3,
            "content": { "uri": uri },
            "extras": { "tag": vessel.tag, "tolerance": tolerance },
        });
        if let Some(finer) = tile.take() {
            t["refine"] = json!("REPLACE");
            t["children"] = json!([finer]);
        }
        tile = Some(t);
    }
    tile
}

/// Tags for an error message, comma-separated.
fn tags<'a>(tags: impl Iterator<Item = &'a str>) -> String {
    tags.collect::<Vec<_>>().join(", ")
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
