//! A live session: the model of one design file, its revision, its journal and the
//! current design as JSON — the state every request reads and every edit changes.
//!
//! Where it sits: the routes lock the session (one edit at a time), call
//! [`Session::apply_patch`], and hand the returned [`Accepted`] to the broadcast
//! hub while still holding the lock, so viewers get deltas in revision order.
//!
//! An edit is a JSON Patch (RFC 6902) against the design's canonical JSON (mm, as
//! `GET /design.json` serves it). It is applied to a copy; the result is parsed and
//! checked as a design file would be, then given to the model as one
//! [`Edit::ReplaceDesign`], which touches only the vessels that differ and, inside
//! them, rebuilds only the parts whose parameters changed (the model's change
//! detection). The edit is then appended to the journal and flushed; only then is
//! it given a revision and acknowledged. Any failure before that leaves the model,
//! the design and the journal as they were.

use axum::body::Bytes;
use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

use serde_json::{Value, json};

use super::error::{ApiError, ServeError};
use super::journal::{Journal, fingerprint, journal_path, write_atomically};
use super::persist::{PersistError, Persistence, Record};
use super::store_link::StoreLink;
use crate::design::units::to_inches;
use crate::design::{self, Design, DesignError, Units, to_canonical_json};
use crate::export::{Scene, node_id, scene_ids, write_delta_glb, write_glb};
use crate::mesh::TessellationOptions;
use crate::model::{Edit, Model, ModelError};
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
    /// GLB of the changed parts only (see [`crate::export::write_delta_glb`]).
    pub delta_glb: Bytes,
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
}

/// A full snapshot for a viewer: revision, every stable id, the whole GLB.
#[derive(Debug, Clone)]
pub struct Snapshot {
    /// The revision it shows.
    pub revision: u64,
    /// Every stable id in the model.
    pub ids: Vec<String>,
    /// The whole model as GLB.
    pub glb: Bytes,
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
    /// Designs an undo goes back to, newest last (at most [`UNDO_DEPTH`]).
    pub(super) undo: Vec<Design>,
    /// Designs a redo goes forward to, newest last.
    pub(super) redo: Vec<Design>,
    /// The full GLB of the current revision, built on first request.
    full: Option<Snapshot>,
    /// Each node's `extras` (kind, parameters, resolved figures) as last sent, by
    /// stable id: a node whose metadata changed without its frame or geometry
    /// (a nozzle's service, a vessel's overall length) is sent again too.
    extras: BTreeMap<String, Value>,
}

/// How many edits back `POST /undo` reaches.
pub const UNDO_DEPTH: usize = 32;

impl Session {
    /// Opens the design file at `path`, builds its model and replays its journal.
    ///
    /// # Errors
    ///
    /// [`ServeError::Design`] for a design that cannot be loaded or built,
    /// [`ServeError::Journal`] for a journal that cannot be read or replayed.
    pub fn open(path: &Path, options: TessellationOptions) -> Result<Session, ServeError> {
        Session::open_with(path, options, None)
    }

    /// Opens the design file at `path` with its edits in the store at `store`
    /// (see [`StoreLink`]), or in its journal without one.
    ///
    /// # Errors
    ///
    /// As [`Session::open`]; [`ServeError::Journal`] naming the store when it
    /// cannot be opened or reached.
    pub fn open_with(
        path: &Path,
        options: TessellationOptions,
        store: Option<&str>,
    ) -> Result<Session, ServeError> {
        let design_error = |source: ModelError| ServeError::Design {
            path: path.display().to_string(),
            source,
        };
        let bytes = design::read_design_bytes(path).map_err(|e| design_error(e.into()))?;
        let text = design::decode_design(path, &bytes).map_err(|e| design_error(e.into()))?;
        let units = design::parse_unchecked(text)
            .map_err(|e| design_error(e.into()))?
            .units;
        let parsed = design::parse(text).map_err(|e| design_error(e.into()))?;
        let old_journal = journal_path(path);
        let migrating = store.is_some() && old_journal.exists();
        if store.is_some() && !migrating {
            let file = parsed;
            let (link, revision, design) =
                StoreLink::open(store.unwrap_or_default(), path, &file, units, None)?;
            return Session::assemble(
                path,
                options,
                Box::new(link),
                design,
                revision,
                revision,
                units,
            )
            .map_err(design_error);
        }
        let file = parsed.clone();
        let (journal, replay) = Journal::open(path, &bytes)?;
        let journal_path = journal.path().display().to_string();
        for dropped in &replay.dropped {
            eprintln!("vesselcad serve: journal {journal_path}: dropped {dropped}");
        }
        // The journaled edits are replayed on the design alone, then the model is
        // built once: each edit was checked when it was accepted.
        let mut design = parsed;
        let mut revision = replay.base_revision;
        if !replay.edits.is_empty() {
            let mut value = design_value(&design);
            for entry in &replay.edits {
                let replay_error = |e: String| ServeError::Journal {
                    path: journal_path.clone(),
                    message: format!("revision {} cannot be replayed: {e}", entry.revision),
                };
                let mut patch = entry.patch.clone();
                canonical_numbers(&mut patch);
                let patch = parse_patch(patch).map_err(|e| replay_error(e.to_string()))?;
                canonical_numbers(&mut value);
                json_patch::patch(&mut value, &patch).map_err(|e| replay_error(e.to_string()))?;
                // As the model would give it back: defaults in their canonical form.
                let next: Design = serde_json::from_value(value)
                    .map_err(|e| replay_error(format!("not a design: {e}")))?;
                value = design_value(&next);
                revision = entry.revision;
            }
            design = serde_json::from_value(value).map_err(|e| ServeError::Journal {
                path: journal_path.clone(),
                message: format!("the replayed design is not a design: {e}"),
            })?;
        }
        if let (Some(location), true) = (store, migrating) {
            let replayed = (!replay.edits.is_empty()).then_some(&design);
            let (link, revision, design) = StoreLink::open(location, path, &file, units, replayed)?;
            let mut migrated = old_journal.clone().into_os_string();
            migrated.push(".migrated");
            std::fs::rename(&old_journal, &migrated).map_err(|e| ServeError::Journal {
                path: journal_path.clone(),
                message: format!("migrated into the store, but cannot be renamed: {e}"),
            })?;
            return Session::assemble(
                path,
                options,
                Box::new(link),
                design,
                revision,
                revision,
                units,
            )
            .map_err(design_error);
        }
        let model = Model::from_design(&design, options).map_err(|e| match e {
            e if replay.edits.is_empty() => design_error(e),
            e => ServeError::Journal {
                path: journal_path.clone(),
                message: format!("the design after replaying the journal is refused: {e}"),
            },
        })?;
        let mut session = Session {
            path: path.to_path_buf(),
            design: design_value(&model.design()),
            extras: node_extras(&model.scene()),
            model,
            revision,
            saved_revision: replay.base_revision,
            units,
            persistence: Box::new(journal),
            undo: Vec::new(),
            redo: Vec::new(),
            full: None,
        };
        session.model.take_changes();
        Ok(session)
    }

    /// A session on `design` at `revision` whose edits go to `persistence`.
    fn assemble(
        path: &Path,
        options: TessellationOptions,
        persistence: Box<dyn Persistence>,
        design: Design,
        revision: u64,
        saved_revision: u64,
        units: Units,
    ) -> Result<Session, ModelError> {
        let model = Model::from_design(&design, options)?;
        let mut session = Session {
            path: path.to_path_buf(),
            design: design_value(&model.design()),
            extras: node_extras(&model.scene()),
            model,
            revision,
            saved_revision,
            units,
            persistence,
            undo: Vec::new(),
            redo: Vec::new(),
            full: None,
        };
        session.model.take_changes();
        Ok(session)
    }

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
        self.apply_as(body, "edit")
    }

    /// [`Session::apply_patch`] with the message the revision is recorded with.
    pub(super) fn apply_as(&mut self, body: &[u8], message: &str) -> Result<Accepted, ApiError> {
        let value: Value = serde_json::from_slice(body)
            .map_err(|e| ApiError::Malformed(format!("the body is not JSON: {e}")))?;
        let mut normalized = value.clone();
        canonical_numbers(&mut normalized);
        let patch = parse_patch(normalized)?;
        let previous = self.design.clone();
        let before = self.model.design();
        let (next, work) = self.stage(&patch)?;
        let after = self.model.design();
        let record = Record {
            revision: self.revision + 1,
            patch: &value,
            before: &before,
            after: &after,
            message,
        };
        if let Err(e) = self.persistence.record(&record) {
            // Not durable: put the model back as it was before answering.
            self.restore(&previous);
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
            });
        }
        if message == "edit" {
            self.redo.clear();
        }
        if message != "undo" {
            self.undo.push(before);
            if self.undo.len() > UNDO_DEPTH {
                self.undo.remove(0);
            }
        }
        self.design = next;
        self.revision += 1;
        Ok(self.accepted(work))
    }

    /// The answer for the model's change since the last one, at the current
    /// revision.
    pub(super) fn accepted(&mut self, work: WorkCounters) -> Accepted {
        self.full = None;
        let mut log = self.model.take_changes();
        let scene = self.model.scene();
        let extras = node_extras(&scene);
        for (id, value) in &extras {
            if self.extras.get(id) != Some(value) {
                log.changed.insert(id.clone());
            }
        }
        self.extras = extras;
        let delta_glb = delta_or_empty(&scene, &log.changed);
        Accepted {
            revision: self.revision,
            changed: log.changed.into_iter().collect(),
            removed: log.removed.into_iter().collect(),
            work,
            delta_glb: Bytes::from(delta_glb),
        }
    }

    /// Applies a parsed patch to the model (not yet journaled): returns the new
    /// design JSON and the work done. On error the model is unchanged.
    fn stage(&mut self, patch: &json_patch::Patch) -> Result<(Value, WorkCounters), ApiError> {
        let mut doc = self.design.clone();
        canonical_numbers(&mut doc);
        json_patch::patch(&mut doc, patch).map_err(|e| match e.kind {
            json_patch::PatchErrorKind::TestFailed => ApiError::TestFailed(e.to_string()),
            _ => ApiError::Unappliable(e.to_string()),
        })?;
        // Parsed from text like a design file, for its exact error paths. The
        // rules are checked by the model's staging, on the vessels that differ
        // only (the others were valid already): the same checks as a design file,
        // without resolving the whole plant on every edit.
        let text =
            serde_json::to_string_pretty(&doc).map_err(|e| ApiError::Malformed(e.to_string()))?;
        let parsed =
            design::parse_unchecked(&text).map_err(|e| ApiError::Invalid(without_position(e)))?;
        let work = self
            .model
            .edit(Edit::ReplaceDesign(parsed))
            .map_err(|e| match e {
                ModelError::Design(e) => ApiError::Invalid(e),
                other => ApiError::Refused(other),
            })?;
        Ok((design_value(&self.model.design()), work))
    }

    /// Puts the model back to `design` (a design it held before).
    fn restore(&mut self, design: &Value) {
        if let Ok(d) = serde_json::from_value::<Design>(design.clone()) {
            // It was valid a moment ago, so this cannot be refused.
            if self.model.edit(Edit::ReplaceDesign(d)).is_ok() {
                self.model.take_changes();
            }
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

    /// The full model at the current revision (built once per revision).
    pub fn snapshot(&mut self) -> Snapshot {
        if let Some(s) = &self.full {
            return s.clone();
        }
        let scene = self.model.scene();
        let glb = write_glb(&scene).unwrap_or_else(|e| {
            eprintln!("vesselcad serve: cannot write the model's GLB: {e}");
            Vec::new()
        });
        let snapshot = Snapshot {
            revision: self.revision,
            ids: scene_ids(&scene),
            glb: Bytes::from(glb),
        };
        self.full = Some(snapshot.clone());
        snapshot
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
        self.model.design().vessels.iter().any(|v| v.tag == tag)
    }

    /// Every vessel's tag, in design order.
    pub fn vessel_tags(&self) -> Vec<String> {
        self.model
            .design()
            .vessels
            .into_iter()
            .map(|v| v.tag)
            .collect()
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

/// A JSON value as a JSON Patch document.
fn parse_patch(value: Value) -> Result<json_patch::Patch, ApiError> {
    if !value.is_array() {
        return Err(ApiError::Malformed(
            "a JSON Patch document (RFC 6902) is an array of operations such as \
             [{\"op\": \"replace\", \"path\": \"/vessels/0/parts/1/shell/length\", \"value\": 8000}]"
                .into(),
        ));
    }
    serde_json::from_value(value)
        .map_err(|e| ApiError::Malformed(format!("not a JSON Patch document (RFC 6902): {e}")))
}

/// A syntax error without its line and column: those are of the patched text,
/// which the editor never saw; the JSON path says where the problem is.
fn without_position(error: DesignError) -> DesignError {
    match error {
        DesignError::Syntax { path, message } => {
            let message = match message.rfind(" at line ") {
                Some(k) => message[..k].to_string(),
                None => message,
            };
            DesignError::Syntax { path, message }
        }
        other => other,
    }
}

/// Writes every whole number as an integer, so that a `test` of `7200` matches a
/// design value `7200.0`: RFC 6902 compares numbers by value, serde_json by
/// representation. Fractional and very large numbers are left as they are.
fn canonical_numbers(value: &mut Value) {
    /// Integers up to 2^53 are exact in f64.
    const EXACT: f64 = 9_007_199_254_740_992.0;
    match value {
        Value::Number(n) => {
            if let Some(f) = n.as_f64()
                && !n.is_i64()
                && !n.is_u64()
                && f.fract() == 0.0
                && f.abs() <= EXACT
            {
                *value = Value::from(f as i64);
            }
        }
        Value::Array(items) => items.iter_mut().for_each(canonical_numbers),
        Value::Object(map) => map.values_mut().for_each(canonical_numbers),
        _ => {}
    }
}

/// Every node's `extras` by stable id.
fn node_extras(scene: &Scene) -> BTreeMap<String, Value> {
    let mut out = BTreeMap::new();
    for vessel in &scene.vessels {
        out.insert(vessel.tag.clone(), vessel.extras.clone());
        for node in &vessel.nodes {
            out.insert(node_id(&vessel.tag, &node.id), node.extras.clone());
        }
    }
    out
}

/// A design as the JSON value patches apply to (its canonical form).
pub(super) fn design_value(design: &Design) -> Value {
    serde_json::to_value(design).unwrap_or(Value::Null)
}

/// The delta GLB, or an empty scene's GLB if the delta cannot be written (viewers
/// then see no geometry change; the error is printed).
fn delta_or_empty(scene: &Scene, changed: &BTreeSet<String>) -> Vec<u8> {
    write_delta_glb(scene, changed).unwrap_or_else(|e| {
        eprintln!("vesselcad serve: cannot write a delta GLB: {e}");
        write_glb(&Scene::default()).unwrap_or_default()
    })
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
