//! `serve --store`: a session's edits committed as revisions of a design in a
//! [`Store`] — the design named by the file's name (`plant.json` → `plant`).
//! Each edit is committed on top of the revision the session holds; another
//! server having committed first is a [`PersistError::Conflict`] (the session
//! then catches up and the editor gets 409 with the current revision).
//!
//! On first start the design file is imported as revision 0, and edits still
//! in an old `<design>.journal` follow as one revision; the journal is then kept
//! as `<design>.journal.migrated`. Later starts take the store's newest
//! revision (the file is written only by `POST /save` or `store export`).

use std::path::Path;

use super::error::ServeError;
use super::persist::{PersistError, Persistence, Record};
use crate::design::{Design, Units};
use crate::store::pg::redact;
use crate::store::{Change, Revision, Store, StoreError};

/// A session's link to its design in a store.
pub struct StoreLink {
    store: Store,
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
    /// content (in mm) is `file` in unit `units`, and `replayed` that design
    /// with its old journal's edits (if any). Returns the link, the revision
    /// and the design to serve.
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
        replayed: Option<&Design>,
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
            if let Some(replayed) = replayed {
                let change = Change {
                    author: author.clone(),
                    message: "edits migrated from the journal".into(),
                };
                store
                    .commit(&name, 0, file, replayed, &change)
                    .map_err(fail)?;
            }
        }
        let head = store.head(&name).map_err(fail)?.unwrap_or(0);
        let design = store.design_at(&name, head).map_err(fail)?;
        Ok((
            StoreLink {
                store,
                name,
                author,
            },
            head as u64,
            design,
        ))
    }
}

impl Persistence for StoreLink {
    fn record(&mut self, record: &Record<'_>) -> Result<(), PersistError> {
        let change = Change {
            author: self.author.clone(),
            message: record.message.to_string(),
        };
        let parent = record.revision as i64 - 1;
        match self
            .store
            .commit(&self.name, parent, record.before, record.after, &change)
        {
            Ok(_) => Ok(()),
            Err(StoreError::Conflict { current, .. }) => Err(PersistError::Conflict {
                current: current as u64,
            }),
            Err(e) => Err(PersistError::Failed(e.to_string())),
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
        Some(self.store.log(&self.name).map_err(|e| e.to_string()))
    }

    fn design_at(&mut self, revision: u64) -> Option<Result<Design, String>> {
        Some(
            self.store
                .design_at(&self.name, revision as i64)
                .map_err(|e| e.to_string()),
        )
    }

    fn newer_than(&mut self, revision: u64) -> Result<Option<(u64, Design)>, String> {
        let head = self
            .store
            .head(&self.name)
            .map_err(|e| e.to_string())?
            .unwrap_or(0) as u64;
        if head <= revision {
            return Ok(None);
        }
        let design = self
            .store
            .design_at(&self.name, head as i64)
            .map_err(|e| e.to_string())?;
        Ok(Some((head, design)))
    }
}
