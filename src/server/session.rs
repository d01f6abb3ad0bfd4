//! A live session: the model of one design file, its revision, its journal and the
//! current design as JSON — the state every request reads and every edit changes.
//!
//! Where it sits: the routes lock the session (one edit at a time), call
//! [`Session::apply_unflushed`] and take a place in the broadcast hub's order;
//! after letting the lock go they wait for the journal's flush and write the
//! returned [`Accepted`]'s delta GLB, so the next edit is staged meanwhile
//! and viewers still get deltas in revision order.
//!
//! An edit is a JSON Patch (RFC 6902) against the design's canonical JSON (mm, as
//! `GET /design.json` serves it). It is applied to a copy; the result is parsed and
//! checked as a design file would be, then given to the model as one
//! [`Edit::ReplaceDesign`](crate::model::Edit::ReplaceDesign), which touches only the vessels that differ and, inside
//! them, rebuilds only the parts whose parameters changed (the model's change
//! detection). The edit is then appended to the journal and given a revision;
//! it is acknowledged once the journal is flushed. Any failure before the
//! append leaves the model, the design and the journal as they were.

use axum::body::Bytes;
use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};
use std::sync::{Arc, OnceLock};

use serde_json::{Value, json};

mod inverse;
mod replay;
mod stage;

use self::stage::{Next, canonical_numbers, parse_patch};
use super::error::ApiError;
use super::flush::Pending;
use super::journal::{fingerprint, write_atomically};
use super::persist::{PersistError, Persistence, Record};
use super::progressive::{Bounds, bounds_json, coarse_scene, estimated_glb_bytes, vessel_bounds};
use super::scoped;
use crate::design::units::to_inches;
use crate::design::{self, Design, Units, to_canonical_json};
use crate::drawing::{SheetOptions, sheet_dxf, sheet_model, sheet_svg};
use crate::export::{Scene, delta_scene, node_id, scene_ids, write_glb};
use crate::mesh::TessellationOptions;
use crate::model::Model;
use crate::systems::WorkCounters;

/// An accepted edit: its revision, what changed and the delta for viewers.
#[derive(Debug, Clone)]
pub struct Accepted {
    /// The new revision.
    pub revision: u64,
    /// Stable ids whose frame or geometry changed.
    pub changed: Vec<String>,
    /// Stable ids removed.
    pub removed: Vec<String>,
    /// Work the model did for this edit.
    pub work: WorkCounters,
    /// The changed parts under their vessels (see
    /// [`crate::export::delta_scene`]): taken under the session lock (the
    /// meshes are shared, not copied), written as GLB by
    /// [`Accepted::delta_glb`] after the lock is let go.
    pub delta: Scene,
    /// The journal flush the edit waits for before it is acknowledged (group
    /// commit: waited for after the session lock is let go).
    pub durable: Option<Pending>,
}

impl Accepted {
    /// The JSON answer to the editor and the delta header for viewers.
    pub fn to_json(&self, kind: &str) -> Value {
        json!({
            "type": kind,
            "revision": self.revision,
            "changed": self.changed,
            "removed": self.removed,
            "work": work_json(&self.work),
        })
    }

    /// Returns once the edit is durable (at once if it already was).
    ///
    /// # Errors
    ///
    /// [`ApiError::Storage`] when the journal could not be flushed: the edit
    /// must not be acknowledged nor shown (the journal is stopped).
    pub fn wait_durable(&self) -> Result<(), ApiError> {
        match &self.durable {
            Some(pending) => pending.wait().map_err(ApiError::Storage),
            None => Ok(()),
        }
    }

    /// The GLB of the changed parts, or an empty scene's GLB if it cannot be
    /// written (viewers then see no geometry change; the error is printed).
    pub fn delta_glb(&self) -> Bytes {
        Bytes::from(write_glb(&self.delta).unwrap_or_else(|e| {
            eprintln!("vesselcad serve: cannot write a delta GLB: {e}");
            write_glb(&Scene::default()).unwrap_or_default()
        }))
    }
}

/// A full snapshot for a viewer: revision, every stable id, and the whole GLB
/// or, for a progressive viewer, each vessel's box (see [`super::progressive`]).
#[derive(Debug, Clone)]
pub struct Snapshot {
    /// The revision it shows.
    pub revision: u64,
    /// Every stable id in the model.
    pub ids: Vec<String>,
    /// The whole model as GLB (empty in a progressive snapshot).
    pub glb: Bytes,
    /// A progressive snapshot's vessels: `[{"tag", "min", "max"}, …]` (glTF
    /// frame, m), sent instead of the GLB.
    pub outline: Option<Value>,
    /// A pushed snapshot: `glb` is the coarse whole (each vessel's box,
    /// [`super::progressive::coarse_scene`]) and this model's vessels follow
    /// it one message each ([`FullModel::vessel_glb`]).
    pub pushed: Option<Arc<FullModel>>,
}

/// One vessel's GLB as `GET /vessel.glb` serves it.
#[derive(Debug, Clone)]
pub struct VesselGlb {
    /// The session's revision when it was written.
    pub revision: u64,
    /// The last revision that changed this vessel (0: none since the start).
    pub vessel_revision: u64,
    /// The vessel's node tree, as in the whole model's GLB.
    pub glb: Bytes,
}

/// The whole model at one revision: its scene (meshes shared with the
/// model), and its GLB once written.
#[derive(Debug)]
pub struct FullModel {
    revision: u64,
    ids: Vec<String>,
    scene: Scene,
    glb: OnceLock<Bytes>,
    /// The coarse whole of a pushed snapshot, once written.
    coarse: OnceLock<Bytes>,
    /// Each vessel's GLB of a pushed snapshot, once written (viewers
    /// connecting at one revision share them).
    vessel_glbs: Box<[OnceLock<Bytes>]>,
}

impl FullModel {
    fn new(revision: u64, scene: Scene) -> FullModel {
        FullModel {
            revision,
            ids: scene_ids(&scene),
            vessel_glbs: scene.vessels.iter().map(|_| OnceLock::new()).collect(),
            scene,
            glb: OnceLock::new(),
            coarse: OnceLock::new(),
        }
    }

    /// The revision it shows.
    pub fn revision(&self) -> u64 {
        self.revision
    }

    /// About how many bytes its whole GLB takes (without writing it).
    pub fn estimated_glb_bytes(&self) -> u64 {
        estimated_glb_bytes(&self.scene)
    }

    /// The pushed snapshot: every stable id and the coarse whole (each
    /// vessel's box), its vessels to follow one by one; the first call writes
    /// the coarse GLB.
    pub fn pushed(self: &Arc<Self>) -> Snapshot {
        let coarse = self.coarse.get_or_init(|| {
            Bytes::from(write_glb(&coarse_scene(&self.scene)).unwrap_or_else(|e| {
                eprintln!("vesselcad serve: cannot write the plant's boxes: {e}");
                Vec::new()
            }))
        });
        Snapshot {
            revision: self.revision,
            ids: self.ids.clone(),
            glb: coarse.clone(),
            outline: None,
            pushed: Some(self.clone()),
        }
    }

    /// Its vessels' tags, in design order.
    pub fn vessel_tags(&self) -> impl ExactSizeIterator<Item = &str> {
        self.scene.vessels.iter().map(|v| v.tag.as_str())
    }

    /// Vessel `k`'s node tree as GLB, as `/vessel.glb` serves it at this
    /// revision (written on first call; empty for `k` out of range).
    pub fn vessel_glb(&self, k: usize) -> Bytes {
        let (Some(vessel), Some(slot)) = (self.scene.vessels.get(k), self.vessel_glbs.get(k))
        else {
            return Bytes::new();
        };
        slot.get_or_init(|| {
            let scene = Scene {
                vessels: vec![vessel.clone()],
            };
            Bytes::from(write_glb(&scene).unwrap_or_else(|e| {
                eprintln!(
                    "vesselcad serve: cannot write the GLB of {}: {e}",
                    vessel.tag
                );
                Vec::new()
            }))
        })
        .clone()
    }

    /// The snapshot; the first call writes the GLB (others wait for it, so
    /// viewers connecting together share one writing).
    pub fn snapshot(&self) -> Snapshot {
        let glb = self.glb.get_or_init(|| {
            Bytes::from(write_glb(&self.scene).unwrap_or_else(|e| {
                eprintln!("vesselcad serve: cannot write the model's GLB: {e}");
                Vec::new()
            }))
        });
        Snapshot {
            revision: self.revision,
            ids: self.ids.clone(),
            glb: glb.clone(),
            outline: None,
            pushed: None,
        }
    }
}

/// One vessel's node tree at one revision, read under the session lock.
#[derive(Debug)]
pub struct VesselScene {
    revision: u64,
    vessel_revision: u64,
    scene: Scene,
}

impl VesselScene {
    /// Its GLB (write it without the session lock).
    pub fn glb(&self) -> VesselGlb {
        let glb = write_glb(&self.scene).unwrap_or_else(|e| {
            let tag = self.scene.vessels.first().map_or("", |v| v.tag.as_str());
            eprintln!("vesselcad serve: cannot write the GLB of {tag}: {e}");
            Vec::new()
        });
        VesselGlb {
            revision: self.revision,
            vessel_revision: self.vessel_revision,
            glb: Bytes::from(glb),
        }
    }
}

/// One design file being edited live.
pub struct Session {
    path: PathBuf,
    pub(super) model: Model,
    /// The current design as canonical JSON: the document patches apply to.
    pub(super) design: Value,
    pub(super) revision: u64,
    /// The revision the design file on disk holds.
    saved_revision: u64,
    /// The file's length unit: a save writes the design back in it.
    units: Units,
    /// Where accepted edits are made durable: the journal, or a store.
    pub(super) persistence: Box<dyn Persistence>,
    /// JSON Patches an undo applies (each takes back one edit of this
    /// server's), newest last (at most [`UNDO_DEPTH`]).
    pub(super) undo: Vec<json_patch::Patch>,
    /// JSON Patches a redo applies (each takes back one undo), newest last.
    pub(super) redo: Vec<json_patch::Patch>,
    /// The whole model at the current revision, its GLB written on first
    /// request (without the session lock).
    full: Option<Arc<FullModel>>,
    /// A fingerprint of each node's `extras` (kind, parameters, resolved
    /// figures) as last sent ([`extras_print`]), by vessel tag and stable id:
    /// a node whose metadata changed without its frame or geometry (a
    /// nozzle's service, a vessel's overall length) is sent again too.
    extras: BTreeMap<String, BTreeMap<String, u64>>,
    /// Each vessel's bounding box (glTF frame), by tag.
    bounds: BTreeMap<String, Bounds>,
    /// The last revision that changed each vessel, by tag (absent: none since
    /// the start).
    changed_at: BTreeMap<String, u64>,
    /// Meshing options of the model (and of the drawings' vessel models).
    options: TessellationOptions,
    /// The last drawings made, by tag and format, with the vessel revision they
    /// show (at most [`KEPT_SHEETS`]).
    sheets: BTreeMap<(String, SheetFormat), (u64, Bytes)>,
}

/// Drawings a session keeps (most viewers look at a few vessels' sheets).
const KEPT_SHEETS: usize = 16;

/// A drawing sheet's file format.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
pub enum SheetFormat {
    /// SVG text.
    Svg,
    /// DXF (R2000) bytes.
    Dxf,
}

/// How many edits back `POST /undo` reaches.
pub const UNDO_DEPTH: usize = 32;

impl Session {
    /// Applies a JSON Patch document (the request body) as one edit: all of it or
    /// nothing. On success the edit is durable in the journal.
    ///
    /// # Errors
    ///
    /// [`ApiError::Malformed`] for a body that is not a JSON Patch document,
    /// [`ApiError::Unappliable`] / [`ApiError::TestFailed`] for operations that do
    /// not apply, [`ApiError::Invalid`] / [`ApiError::Refused`] for a result that
    /// is not a valid design, [`ApiError::Storage`] if the journal cannot be
    /// written. In every case the session is unchanged.
    pub fn apply_patch(&mut self, body: &[u8]) -> Result<Accepted, ApiError> {
        let accepted = self.apply_unflushed(body)?;
        accepted.wait_durable()?;
        Ok(accepted)
    }

    /// [`Session::apply_patch`] that returns before the edit is flushed: the
    /// caller lets the session lock go, then calls [`Accepted::wait_durable`]
    /// before it acknowledges the edit or streams it (group commit).
    ///
    /// # Errors
    ///
    /// As [`Session::apply_patch`], but for the flush.
    pub fn apply_unflushed(&mut self, body: &[u8]) -> Result<Accepted, ApiError> {
        self.apply_as(body, "edit")
    }

    /// [`Session::apply_patch`] as a new edit of this server's: its inverse
    /// goes on the undo stack and the redo stack is emptied.
    pub(super) fn apply_as(&mut self, body: &[u8], message: &str) -> Result<Accepted, ApiError> {
        let (accepted, inverse) = self.apply_recorded(body, message)?;
        self.redo.clear();
        push_bounded(&mut self.undo, inverse);
        Ok(accepted)
    }

    /// [`Session::apply_patch`] with the message the revision is recorded
    /// with: the accepted edit and the JSON Patch that takes it back. The
    /// design is changed in place (only the vessels the edit changed are
    /// copied, into the inverse); neither stack is touched.
    pub(super) fn apply_recorded(
        &mut self,
        body: &[u8],
        message: &str,
    ) -> Result<(Accepted, json_patch::Patch), ApiError> {
        let value: Value = serde_json::from_slice(body)
            .map_err(|e| ApiError::Malformed(format!("the body is not JSON: {e}")))?;
        let mut normalized = value.clone();
        canonical_numbers(&mut normalized);
        let patch = parse_patch(normalized)?;
        let count = self.design["vessels"].as_array().map_or(0, Vec::len);
        let scoped = match scoped::vessel_scope(&patch, count) {
            Some(indices) => self.stage_vessels(&patch, &indices)?,
            None => None,
        };
        let (next, work) = match scoped {
            Some((vessels, work)) => (Next::Vessels(vessels), work),
            None => {
                let (next, work) = self.stage(&patch)?;
                (Next::Whole(next), work)
            }
        };
        let inverse = inverse::inverse(&self.design, &next);
        let (previous, touched) = self.swap_in(next);
        let record = Record {
            revision: self.revision + 1,
            patch: &value,
            design: &self.design,
            inverse: &inverse,
            message,
        };
        let durable = match self.persistence.record(&record) {
            Ok(pending) => pending,
            Err(e) => {
                // Not durable: put the design and the model back as they were.
                self.put_back(previous);
                return Err(match e {
                    PersistError::Conflict { current } => ApiError::Conflict {
                        current,
                        message: format!(
                            "{} was changed by another server first (it is at revision \
                         {current}); reload and edit again",
                            self.persistence.describe()
                        ),
                    },
                    PersistError::Failed(message) => ApiError::Storage(message),
                    PersistError::Unavailable(message) => ApiError::StoreUnavailable(message),
                });
            }
        };
        self.revision += 1;
        let mut accepted = self.accepted(work, touched);
        accepted.durable = durable;
        Ok((accepted, inverse))
    }

    /// The answer for the model's change since the last one, at the current
    /// revision; `touched` are the tags of the vessels whose design changed.
    pub(super) fn accepted(&mut self, work: WorkCounters, touched: Vec<String>) -> Accepted {
        self.full = None;
        let mut log = self.model.take_changes();
        // Only the vessels the edit touched are read back: their ids that
        // changed, and those whose metadata changed without their geometry.
        let mut tags: BTreeSet<String> = touched.into_iter().collect();
        for id in &log.changed {
            let known = tags.iter().any(|t| {
                id == t
                    || id
                        .strip_prefix(t.as_str())
                        .is_some_and(|r| r.starts_with('/'))
            });
            if !known {
                tags.insert(vessel_of(id).to_string());
            }
        }
        let tags: Vec<String> = tags.into_iter().collect();
        let scene = self.model.vessels_scene(&tags);
        let mut extras = node_extras(&scene);
        let mut bounds: BTreeMap<String, Bounds> = vessel_bounds(&scene).into_iter().collect();
        for tag in &tags {
            self.changed_at.insert(tag.clone(), self.revision);
            match bounds.remove(tag) {
                Some(b) => self.bounds.insert(tag.clone(), b),
                None => self.bounds.remove(tag),
            };
            let now = extras.remove(tag).unwrap_or_default();
            let before = self.extras.remove(tag).unwrap_or_default();
            for (id, value) in &now {
                if before.get(id) != Some(value) {
                    log.changed.insert(id.clone());
                }
            }
            if !now.is_empty() {
                self.extras.insert(tag.clone(), now);
            }
        }
        Accepted {
            revision: self.revision,
            durable: None,
            delta: delta_scene(&scene, &log.changed),
            changed: log.changed.into_iter().collect(),
            removed: log.removed.into_iter().collect(),
            work,
        }
    }

    /// Writes the design file and starts a fresh journal, if there are edits the
    /// file does not hold; returns the revision the file holds and whether it was
    /// written.
    ///
    /// The file keeps its length unit (an inch file is written in inches, each
    /// value with the decimals it was given), its previous content is kept as
    /// `<file>.bak`, and a design reached through a symbolic link is written to
    /// the link's target (the link stays). The write is atomic: temp file,
    /// `fsync`, rename, `fsync` of the folder.
    ///
    /// # Errors
    ///
    /// [`ApiError::SaveFailed`] when the file or the journal cannot be written:
    /// the file is as it was, no temp file is left, and the journal still holds
    /// every edit, so nothing is lost.
    pub fn save(&mut self) -> Result<Saved, ApiError> {
        if self.revision == self.saved_revision && self.path_holds_a_file() {
            return Ok(Saved {
                revision: self.revision,
                written: false,
                recreated: false,
            });
        }
        let mut design = self.model.design();
        if self.units == Units::In {
            to_inches(&mut design);
        }
        let text = to_canonical_json(&design);
        let print = fingerprint(text.as_bytes());
        let failed = |what: &Path, e: &dyn std::fmt::Display| {
            ApiError::SaveFailed(format!("cannot write {}: {e}", what.display()))
        };
        // Through a link to the file it names (a link left dangling by a
        // deleted target included).
        let target = link_target(&self.path);
        let mut backup = target.file_name().unwrap_or_default().to_os_string();
        backup.push(".bak");
        let backup = target.with_file_name(backup);
        // A file deleted while serving is written again (there is nothing to
        // back up), and the answer says so.
        let recreated = match std::fs::read(&target) {
            Ok(previous) => {
                write_atomically(&backup, &previous).map_err(|e| failed(&backup, &e))?;
                false
            }
            Err(e) if e.kind() == std::io::ErrorKind::NotFound => {
                eprintln!(
                    "vesselcad serve: {} was deleted while serving; the save writes it again",
                    target.display()
                );
                true
            }
            Err(e) => return Err(failed(&target, &e)),
        };
        let describe = self.persistence.describe();
        self.persistence
            .saving(&print, self.revision)
            .map_err(|e| ApiError::SaveFailed(format!("cannot write {describe}: {e}")))?;
        write_atomically(&target, text.as_bytes()).map_err(|e| failed(&target, &e))?;
        self.saved_revision = self.revision;
        self.persistence
            .saved(&print, self.revision)
            .map_err(|e| failed(&self.path, &e))?;
        Ok(Saved {
            revision: self.revision,
            written: true,
            recreated,
        })
    }

    /// Whether the design file (or the file its link names) still exists.
    fn path_holds_a_file(&self) -> bool {
        link_target(&self.path).exists()
    }

    /// Whether there are edits the design file does not hold yet.
    pub fn has_unsaved_edits(&self) -> bool {
        self.revision != self.saved_revision
    }

    /// The whole model at the current revision, to be written as GLB without
    /// the session lock ([`FullModel::snapshot`]; written once per revision).
    pub fn full_model(&mut self) -> Arc<FullModel> {
        if let Some(full) = &self.full {
            return full.clone();
        }
        let full = Arc::new(FullModel::new(self.revision, self.model.scene()));
        self.full = Some(full.clone());
        full
    }

    /// The full model at the current revision as GLB (written once per
    /// revision; under the lock: callers that hold it should prefer
    /// [`Session::full_model`]).
    pub fn snapshot(&mut self) -> Snapshot {
        self.full_model().snapshot()
    }

    /// A progressive viewer's snapshot: every stable id and each vessel's box,
    /// in design order, without meshes (cheap: nothing is read from the model).
    pub fn outline(&self) -> Snapshot {
        let mut ids = Vec::new();
        let mut boxes = Vec::new();
        for tag in self.design_tags() {
            if let Some(of_vessel) = self.extras.get(tag) {
                ids.push(tag.to_string());
                ids.extend(of_vessel.keys().filter(|id| *id != tag).cloned());
            }
            if let Some(b) = self.bounds.get(tag) {
                boxes.push((tag.to_string(), *b));
            }
        }
        Snapshot {
            revision: self.revision,
            ids,
            glb: Bytes::new(),
            outline: Some(bounds_json(&boxes)),
            pushed: None,
        }
    }

    /// Vessel `tag`'s node tree at the current revision, to be written as GLB
    /// without the session lock ([`VesselScene::glb`]); `None` for an unknown
    /// tag.
    pub fn vessel_scene(&self, tag: &str) -> Option<VesselScene> {
        let scene = self.model.vessels_scene(&[tag]);
        if scene.vessels.is_empty() {
            return None;
        }
        Some(VesselScene {
            revision: self.revision,
            vessel_revision: self.changed_at.get(tag).copied().unwrap_or(0),
            scene,
        })
    }

    /// Vessel `tag`'s GLB at the current revision; `None` for an unknown tag.
    pub fn vessel_glb(&self, tag: &str) -> Option<VesselGlb> {
        self.vessel_scene(tag).map(|v| v.glb())
    }

    /// Vessel `tag`'s drawing sheet (ANSI D) as SVG or DXF, from a model of the
    /// vessel alone with drawing views (the session's model keeps none); kept
    /// until the vessel changes.
    ///
    /// # Errors
    ///
    /// [`ApiError::NotFound`] for an unknown tag, [`ApiError::Drawing`] when the
    /// sheet cannot be made.
    pub fn drawing(&mut self, tag: &str, format: SheetFormat) -> Result<Bytes, ApiError> {
        let at = self.changed_at.get(tag).copied().unwrap_or(0);
        let key = (tag.to_string(), format);
        if let Some((made, bytes)) = self.sheets.get(&key)
            && *made == at
        {
            return Ok(bytes.clone());
        }
        let vessel = self
            .model
            .vessel_design(tag)
            .ok_or_else(|| ApiError::NotFound(format!("vessel {tag}")))?;
        let design = Design {
            format: design::FORMAT.to_string(),
            units: Units::Mm,
            vessels: vec![vessel],
        };
        let drawing_error = |e: &dyn std::fmt::Display| ApiError::Drawing(e.to_string());
        let (model, _) = sheet_model(&design, tag, self.options).map_err(|e| drawing_error(&e))?;
        let options = SheetOptions::default();
        let bytes = match format {
            SheetFormat::Svg => sheet_svg(&model, tag, &options).map(String::into_bytes),
            SheetFormat::Dxf => sheet_dxf(&model, tag, &options),
        }
        .map_err(|e| drawing_error(&e))?;
        let bytes = Bytes::from(bytes);
        if self.sheets.len() >= KEPT_SHEETS {
            self.sheets.pop_first();
        }
        self.sheets.insert(key, (at, bytes.clone()));
        Ok(bytes)
    }

    /// Vessel `tag`'s design and index: `{"revision", "index", "vessel"}`.
    pub fn vessel_entry(&self, tag: &str) -> Option<Value> {
        let vessels = self.design["vessels"].as_array()?;
        let index = vessels
            .iter()
            .position(|v| v.get("tag").and_then(Value::as_str) == Some(tag))?;
        Some(json!({ "revision": self.revision, "index": index, "vessel": vessels[index] }))
    }

    /// The vessel tags of the current design, in design order.
    fn design_tags(&self) -> impl Iterator<Item = &str> {
        self.design["vessels"]
            .as_array()
            .into_iter()
            .flatten()
            .filter_map(|v| v.get("tag")?.as_str())
    }

    /// The current revision.
    pub fn revision(&self) -> u64 {
        self.revision
    }

    /// The current design's canonical JSON text.
    pub fn design_text(&self) -> String {
        to_canonical_json(&self.model.design())
    }

    /// True if a vessel has this tag.
    pub fn has_vessel(&self, tag: &str) -> bool {
        self.design_tags().any(|t| t == tag)
    }

    /// Every vessel's tag, in design order.
    pub fn vessel_tags(&self) -> Vec<String> {
        self.design_tags().map(str::to_string).collect()
    }

    /// The model, for read-only outputs (e.g. drawings).
    pub fn model(&self) -> &Model {
        &self.model
    }

    /// The design file.
    pub fn path(&self) -> &Path {
        &self.path
    }
}

/// The outcome of [`Session::save`].
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Saved {
    /// The revision the design file holds.
    pub revision: u64,
    /// Whether the file was written (there were unsaved edits, or it was gone).
    pub written: bool,
    /// Whether the file had been deleted while serving and was written again.
    pub recreated: bool,
}

/// Pushes `patch` on an undo or redo stack, forgetting the oldest beyond
/// [`UNDO_DEPTH`].
pub(super) fn push_bounded(stack: &mut Vec<json_patch::Patch>, patch: json_patch::Patch) {
    stack.push(patch);
    if stack.len() > UNDO_DEPTH {
        stack.remove(0);
    }
}

/// The file `path` names: a symbolic link's target (resolved even when the
/// target no longer exists), else `path` itself.
fn link_target(path: &Path) -> PathBuf {
    if let Ok(resolved) = std::fs::canonicalize(path) {
        return resolved;
    }
    match std::fs::read_link(path) {
        Ok(to) => path.parent().unwrap_or(Path::new(".")).join(to),
        Err(_) => path.to_path_buf(),
    }
}

/// The vessel tag of a stable id (`tag` or `tag/id`).
fn vessel_of(id: &str) -> &str {
    id.split_once('/').map_or(id, |(tag, _)| tag)
}

/// Vessel `tag`'s entry in the viewers' index: the fingerprint of each of its
/// nodes' `extras` by stable id (empty for an unknown tag) and its box.
fn index_vessel(model: &Model, tag: &str) -> (BTreeMap<String, u64>, Option<Bounds>) {
    let scene = model.vessels_scene(&[tag]);
    let vessel_box = vessel_bounds(&scene).pop().map(|(_, b)| b);
    let prints = node_extras(&scene).remove(tag).unwrap_or_default();
    (prints, vessel_box)
}

/// The fingerprint of every node's `extras` by vessel tag, then by stable id.
fn node_extras(scene: &Scene) -> BTreeMap<String, BTreeMap<String, u64>> {
    let mut out = BTreeMap::new();
    for vessel in &scene.vessels {
        let mut of_vessel = BTreeMap::new();
        of_vessel.insert(vessel.tag.clone(), extras_print(&vessel.extras));
        for node in &vessel.nodes {
            of_vessel.insert(node_id(&vessel.tag, &node.id), extras_print(&node.extras));
        }
        out.insert(vessel.tag.clone(), of_vessel);
    }
    out
}

/// A 64-bit fingerprint of a node's `extras` (SipHash of its JSON text with
/// fixed keys): what the session keeps of them instead of the values, a
/// fraction of their memory (two different values share one with odds of
/// 2⁻⁶⁴, and then only a metadata-only change would not be resent).
fn extras_print(extras: &Value) -> u64 {
    use std::hash::Hasher;
    /// Feeds the JSON text to the hasher as it is written.
    struct Feed(std::hash::DefaultHasher);
    impl std::io::Write for Feed {
        fn write(&mut self, bytes: &[u8]) -> std::io::Result<usize> {
            self.0.write(bytes);
            Ok(bytes.len())
        }
        fn flush(&mut self) -> std::io::Result<()> {
            Ok(())
        }
    }
    let mut feed = Feed(std::hash::DefaultHasher::new());
    // Writing a `Value` into a sink that never fails cannot fail.
    let _ = serde_json::to_writer(&mut feed, extras);
    feed.0.finish()
}

/// A design as the JSON value patches apply to (its canonical form).
pub(super) fn design_value(design: &Design) -> Value {
    serde_json::to_value(design).unwrap_or(Value::Null)
}

/// Work counters as JSON.
fn work_json(w: &WorkCounters) -> Value {
    json!({
        "vessels_resolved": w.vessels_resolved,
        "resolutions_reused": w.resolutions_reused,
        "frames_updated": w.frames_updated,
        "shapes_rebuilt": w.shapes_rebuilt,
        "openings_cut": w.openings_cut,
        "openings_placed": w.openings_placed,
        "regions_laid_out": w.regions_laid_out,
        "regions_unchanged": w.regions_unchanged,
        "patches_rebuilt": w.patches_rebuilt,
        "meshes_rebuilt": w.meshes_rebuilt,
        "meshes_shared": w.meshes_shared,
        "triangles_meshed": w.triangles_meshed,
        "cavities_reused": w.cavities_reused,
        "failures": w.failures,
    })
}
