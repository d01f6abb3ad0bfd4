//! `serve --store`: a session's edits committed as revisions of a design in a
//! [`Store`] — the design named by the file's name (`plant.json` → `plant`).
//! Each edit is committed on top of the revision the session holds; another
//! server having committed first is a [`PersistError::Conflict`] (the session
//! then catches up and the editor gets 409 with the current revision).
//!
//! On first start the design file is imported as revision 0, and edits still
//! in an old `<design>.journal` follow, one revision each; the journal is then kept
//! as `<design>.journal.migrated`. Later starts take the store's newest
//! revision (the file is written only by `POST /save` or `store export`).
//!
//! A lost database connection refuses the edit at hand
//! ([`PersistError::Unavailable`], nothing acknowledged) and the next request
//! opens the store again: the session goes on once the database is back. An edit
//! whose commit reached the database just before the connection dropped comes
//! back as a conflict on the next edit, and the session then catches up.

use std::path::Path;

use super::error::ServeError;
use super::flush::Pending;
use super::persist::{PersistError, Persistence, Record};
use crate::design::{Design, Units};
use crate::store::pg::redact;
use crate::store::{Change, Revision, Store, StoreError};

/// A session's link to its design in a store.
pub struct StoreLink {
    store: Store,
    /// What `--store` named (with its password), to reconnect.
    location: String,
    /// The connection was lost: open the store again before the next use.
    lost: bool,
    name: String,
    author: String,
}

/// The store's name of a design file.
pub fn design_name(path: &Path) -> String {
    let file = path.file_name().unwrap_or_default().to_string_lossy();
    file.strip_suffix(".json").unwrap_or(&file).to_string()
}

fn error(location: &str, e: &StoreError) -> ServeError {
    ServeError::Journal {
        path: redact(location),
        message: e.to_string(),
    }
}

impl StoreLink {
    /// Opens the store at `location` for the design file at `path` whose
    /// content (in mm) is `file` in unit `units`. On first start the file
    /// becomes revision 0 and `migrated` — the design after each edit of an old
    /// journal, with that edit's journal revision — follow, one revision each.
    /// Returns the link, the revision and the design to serve.
    ///
    /// # Errors
    ///
    /// [`ServeError::Journal`] naming the store when it cannot be opened,
    /// reached or written.
    pub fn open(
        location: &str,
        path: &Path,
        file: &Design,
        units: Units,
        migrated: &[(u64, Design)],
    ) -> Result<(StoreLink, u64, Design), ServeError> {
        let mut store = Store::open(location).map_err(|e| error(location, &e))?;
        let shown = store.location().to_string();
        let name = design_name(path);
        let author = std::env::var("VESSELCAD_AUTHOR")
            .or_else(|_| std::env::var("USER"))
            .unwrap_or_else(|_| "serve".into());
        let fail = |e: StoreError| error(&shown, &e);
        if store.head(&name).map_err(fail)?.is_none() {
            let change = Change {
                author: author.clone(),
                message: format!("import {}", path.display()),
            };
            store.import(&name, file, units, &change).map_err(fail)?;
            let mut before = file;
            for (parent, (revision, after)) in migrated.iter().enumerate() {
                let change = Change {
                    author: author.clone(),
                    message: format!("edit migrated from the journal (its revision {revision})"),
                };
                store
                    .commit(&name, parent as i64, before, after, &change)
                    .map_err(fail)?;
                before = after;
            }
        }
        let head = store.head(&name).map_err(fail)?.unwrap_or(0);
        let design = store.design_at(&name, head).map_err(fail)?;
        Ok((
            StoreLink {
                store,
                location: location.to_string(),
                lost: false,
                name,
                author,
            },
            head as u64,
            design,
        ))
    }
}

impl StoreLink {
    /// Runs `f` on the store, reconnecting first if the connection was lost,
    /// and noting a connection lost on the way. The error's flag is whether
    /// the store cannot be reached.
    fn with_store<T>(
        &mut self,
        f: impl FnOnce(&mut Store, &str) -> Result<T, StoreError>,
    ) -> Result<T, (bool, StoreError)> {
        if self.lost {
            self.store = Store::open(&self.location).map_err(|e| (true, e))?;
            self.lost = false;
        }
        f(&mut self.store, &self.name).map_err(|e| {
            let lost = matches!(e, StoreError::Disconnected { .. });
            self.lost |= lost;
            (lost, e)
        })
    }

    /// [`StoreLink::with_store`] with the error as text.
    fn read<T>(
        &mut self,
        f: impl FnOnce(&mut Store, &str) -> Result<T, StoreError>,
    ) -> Result<T, String> {
        self.with_store(f).map_err(|(_, e)| e.to_string())
    }
}

impl Persistence for StoreLink {
    fn record(&mut self, record: &Record<'_>) -> Result<Option<Pending>, PersistError> {
        let change = Change {
            author: self.author.clone(),
            message: record.message.to_string(),
        };
        let parent = record.revision as i64 - 1;
        let (before, after) = record.designs().map_err(PersistError::Failed)?;
        let commit =
            |store: &mut Store, name: &str| store.commit(name, parent, &before, &after, &change);
        // Committed (synchronously) before this returns.
        match self.with_store(commit) {
            Ok(_) => Ok(None),
            Err((_, StoreError::Conflict { current, .. })) => Err(PersistError::Conflict {
                current: current as u64,
            }),
            Err((true, e)) => Err(PersistError::Unavailable(e.to_string())),
            Err((false, e)) => Err(PersistError::Failed(e.to_string())),
        }
    }

    fn saving(&mut self, _print: &str, _revision: u64) -> std::io::Result<()> {
        Ok(())
    }

    fn saved(&mut self, _print: &str, _revision: u64) -> Result<(), String> {
        Ok(())
    }

    fn describe(&self) -> String {
        format!(
            "design {:?} in the store {}",
            self.name,
            self.store.location()
        )
    }

    fn revisions(&mut self) -> Option<Result<Vec<Revision>, String>> {
        Some(self.read(|store, name| store.log(name)))
    }

    fn design_at(&mut self, revision: u64) -> Option<Result<Design, String>> {
        Some(self.read(|store, name| store.design_at(name, revision as i64)))
    }

    fn newer_than(&mut self, revision: u64) -> Result<Option<(u64, Design)>, String> {
        self.read(|store, name| {
            let head = store.head(name)?.unwrap_or(0) as u64;
            if head <= revision {
                return Ok(None);
            }
            Ok(Some((head, store.design_at(name, head as i64)?)))
        })
    }
}
