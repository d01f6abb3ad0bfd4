//! The persistence seam of a live session: where an accepted edit is made
//! durable before it is acknowledged. [`Persistence`] has two implementations:
//! the journal beside the design file (the default, [`super::journal`]) and a
//! design store (`serve --store`, [`super::store_link`]), which also keeps the
//! history that `GET /revisions` and `GET /design.json?rev=` read, and with
//! PostgreSQL shares the design with other servers.

use serde_json::Value;

use super::flush::Pending;
use super::journal::Journal;
use crate::design::Design;
use crate::store::Revision;

/// Why an edit could not be made durable. The session is put back as it was.
#[derive(Debug)]
pub enum PersistError {
    /// Another server committed first; the design is at revision `current`.
    Conflict {
        /// The newest revision.
        current: u64,
    },
    /// The journal or database could not be written (its message).
    Failed(String),
    /// The database cannot be reached (its message); the next request tries
    /// to reconnect.
    Unavailable(String),
}

/// One accepted edit, as the session hands it to be made durable: the patch as
/// sent, and the design after it with the patch that takes it back, from which
/// [`Record::designs`] makes both designs for a persistence that needs them
/// (the store); the journal needs the patch alone, so an edit copies no design.
pub struct Record<'a> {
    /// The revision it becomes.
    pub revision: u64,
    /// The editor's JSON Patch as sent.
    pub patch: &'a Value,
    /// The design after, as the canonical JSON the session holds.
    pub design: &'a Value,
    /// The JSON Patch from `design` back to the design before (revision − 1).
    pub inverse: &'a json_patch::Patch,
    /// Why (`edit`, `undo`, `redo`).
    pub message: &'a str,
}

impl Record<'_> {
    /// The designs before and after the edit.
    ///
    /// # Errors
    ///
    /// The reason when the inverse does not apply or a design does not parse
    /// (a bug: both were designs the session held).
    pub fn designs(&self) -> Result<(Design, Design), String> {
        let mut before = self.design.clone();
        json_patch::patch(&mut before, self.inverse)
            .map_err(|e| format!("the edit's inverse does not apply: {e}"))?;
        let parse = |v: Value| {
            serde_json::from_value::<Design>(v).map_err(|e| format!("not a design: {e}"))
        };
        Ok((parse(before)?, parse(self.design.clone())?))
    }
}

/// Where a session's edits go.
pub trait Persistence: Send {
    /// Makes `record` durable: returns once it is, or with the flush still to
    /// wait for (after the session lock is let go: [`Pending::wait`]).
    fn record(&mut self, record: &Record<'_>) -> Result<Option<Pending>, PersistError>;

    /// A save of a design with fingerprint `print` at `revision` is about to
    /// write the design file.
    fn saving(&mut self, print: &str, revision: u64) -> std::io::Result<()>;

    /// The design file now holds revision `revision` (fingerprint `print`).
    fn saved(&mut self, print: &str, revision: u64) -> Result<(), String>;

    /// Where the edits go, for messages.
    fn describe(&self) -> String;

    /// The revisions kept (`None`: this persistence keeps no history).
    fn revisions(&mut self) -> Option<Result<Vec<Revision>, String>> {
        None
    }

    /// The design at `revision` (`None`: no history).
    fn design_at(&mut self, _revision: u64) -> Option<Result<Design, String>> {
        None
    }

    /// Revisions other writers committed after `revision`: the newest one and
    /// its design, if there is a newer one.
    fn newer_than(&mut self, _revision: u64) -> Result<Option<(u64, Design)>, String> {
        Ok(None)
    }
}

impl Persistence for Journal {
    fn record(&mut self, record: &Record<'_>) -> Result<Option<Pending>, PersistError> {
        self.append(record.revision, record.patch)
            .map(Some)
            .map_err(|e| {
                PersistError::Failed(format!(
                    "cannot write the journal {}: {e}",
                    self.path().display()
                ))
            })
    }

    fn saving(&mut self, print: &str, revision: u64) -> std::io::Result<()> {
        self.mark_saved(print, revision)
    }

    fn saved(&mut self, print: &str, revision: u64) -> Result<(), String> {
        self.reset(print, revision).map_err(|e| e.to_string())
    }

    fn describe(&self) -> String {
        format!("the journal {}", self.path().display())
    }
}
