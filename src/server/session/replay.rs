//! Opening a session: the design file read and checked, the journal's edits
//! replayed on the design alone (or an old journal migrated into a store, one
//! revision per edit), then the model built once, with progress on stderr.

use std::collections::BTreeMap;
use std::path::Path;
use std::time::Instant;

use super::stage::{canonical_numbers, parse_patch};
use rayon::prelude::*;

use super::{Session, design_value, index_vessel};
use crate::design::{self, Design, Units};
use crate::mesh::TessellationOptions;
use crate::model::{Model, ModelError, Views};
use crate::server::error::ServeError;
use crate::server::journal::{Journal, journal_path};
use crate::server::persist::Persistence;
use crate::server::store_link::StoreLink;

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
        let started = Instant::now();
        let progress = |what: &str| {
            let resident =
                resident_mb().map_or(String::new(), |mb| format!(", {mb:.0} MB resident"));
            eprintln!(
                "vesselcad serve: {} {what} ({:.1} s{resident})",
                path.display(),
                started.elapsed().as_secs_f64()
            );
        };
        let bytes = design::read_design_bytes(path).map_err(|e| design_error(e.into()))?;
        let text = design::decode_design(path, &bytes).map_err(|e| design_error(e.into()))?;
        let units = design::parse_unchecked(text)
            .map_err(|e| design_error(e.into()))?
            .units;
        let parsed = design::parse(text).map_err(|e| design_error(e.into()))?;
        progress(&format!(
            "read and checked: {} vessels; building and meshing",
            parsed.vessels.len()
        ));
        // A session whose edits go to the store: no drawing views (a sheet is
        // drawn from a model of its vessel alone).
        let on_store = |link: StoreLink, revision: u64, design: Design| {
            let model =
                Model::from_design_with(&design, options, Views::Off).map_err(design_error)?;
            let session = Session::assemble(
                path,
                options,
                Box::new(link),
                model,
                revision,
                revision,
                units,
            );
            progress("ready");
            Ok(session)
        };
        let old_journal = journal_path(path);
        let migrating = store.is_some() && old_journal.exists();
        if store.is_some() && !migrating {
            let file = parsed;
            let (link, revision, design) =
                StoreLink::open(store.unwrap_or_default(), path, &file, units, &[])?;
            return on_store(link, revision, design);
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
        // Migrating into a store: the design after each edit, one revision each.
        let mut steps = Vec::new();
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
                if migrating {
                    steps.push((revision, next));
                }
            }
            design = serde_json::from_value(value).map_err(|e| ServeError::Journal {
                path: journal_path.clone(),
                message: format!("the replayed design is not a design: {e}"),
            })?;
        }
        if let (Some(location), true) = (store, migrating) {
            let (link, revision, design) = StoreLink::open(location, path, &file, units, &steps)?;
            let mut migrated = old_journal.clone().into_os_string();
            migrated.push(".migrated");
            std::fs::rename(&old_journal, &migrated).map_err(|e| ServeError::Journal {
                path: journal_path.clone(),
                message: format!("migrated into the store, but cannot be renamed: {e}"),
            })?;
            return on_store(link, revision, design);
        }
        // No drawing views: a sheet is drawn from a model of its vessel alone
        // (`drawing`), so the plant is not projected at start nor on each edit.
        let model = Model::from_design_with(&design, options, Views::Off).map_err(|e| match e {
            e if replay.edits.is_empty() => design_error(e),
            e => ServeError::Journal {
                path: journal_path.clone(),
                message: format!("the design after replaying the journal is refused: {e}"),
            },
        })?;
        let memory = model.memory();
        let mb = |bytes: usize| bytes as f64 / 1e6;
        progress(&format!(
            "built: {:.1} MB of meshes, {:.1} MB of surfaces, regions, openings and cavities; \
             indexing {} vessels for viewers",
            mb(memory.meshes),
            mb(memory.surfaces + memory.regions + memory.openings + memory.cavities),
            design.vessels.len()
        ));
        let session = Session::assemble(
            path,
            options,
            Box::new(journal),
            model,
            revision,
            replay.base_revision,
            units,
        );
        progress("ready");
        Ok(session)
    }

    /// A session on `model` at `revision` whose edits go to `persistence`.
    pub(super) fn assemble(
        path: &Path,
        options: TessellationOptions,
        persistence: Box<dyn Persistence>,
        model: Model,
        revision: u64,
        saved_revision: u64,
        units: Units,
    ) -> Session {
        let design = design_value(&model.design());
        // Each vessel's node fingerprints and box, the vessels in parallel
        // (one vessel's scene at a time: the plant's is never held at once).
        let tags: Vec<&str> = design["vessels"]
            .as_array()
            .into_iter()
            .flatten()
            .filter_map(|v| v.get("tag")?.as_str())
            .collect();
        let indexed: Vec<_> = tags
            .par_iter()
            .map(|tag| (*tag, index_vessel(&model, tag)))
            .collect();
        let mut extras = BTreeMap::new();
        let mut bounds = BTreeMap::new();
        for (tag, (prints, vessel_box)) in indexed {
            if !prints.is_empty() {
                extras.insert(tag.to_string(), prints);
            }
            if let Some(b) = vessel_box {
                bounds.insert(tag.to_string(), b);
            }
        }
        let mut session = Session {
            path: path.to_path_buf(),
            design,
            extras,
            bounds,
            changed_at: BTreeMap::new(),
            options,
            sheets: BTreeMap::new(),
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
        session
    }
}

/// The process's resident set, MB (`/proc/self/statm`; `None` elsewhere):
/// printed with the start-up progress, so the model's memory and the
/// session's can be told apart.
fn resident_mb() -> Option<f64> {
    let statm = std::fs::read_to_string("/proc/self/statm").ok()?;
    let pages: f64 = statm.split_whitespace().nth(1)?.parse().ok()?;
    Some(pages * 4096.0 / 1e6)
}
