//! Errors of the design store, one enum for the domain: what could not be opened,
//! read or written, and the refusals a caller acts on (a conflicting revision, an
//! unknown design, revision or tag, a malformed search).

use thiserror::Error;

/// Why a store operation failed. Nothing was committed.
#[derive(Debug, Error)]
pub enum StoreError {
    /// The database could not be opened, read or written (the backend's message,
    /// with the store's location).
    #[error("store {location}: {message}")]
    Database {
        /// The SQLite path or the PostgreSQL URL without its password.
        location: String,
        /// What the database said.
        message: String,
    },
    /// The connection to the database was lost (the server went away or ended
    /// the session); nothing was committed. Opening the store again reconnects.
    #[error("store {location}: the connection was lost: {message}")]
    Disconnected {
        /// The PostgreSQL URL without its password.
        location: String,
        /// What the client library said.
        message: String,
    },
    /// The database's schema is newer than this program knows.
    #[error(
        "store {location}: schema version {found} is newer than this vesselcad \
         (which knows up to {known}); upgrade vesselcad"
    )]
    NewerSchema {
        /// The store.
        location: String,
        /// The version the database has.
        found: i64,
        /// The newest version this program writes.
        known: i64,
    },
    /// Another writer committed a revision after `parent` first: nothing was
    /// written; the design is at `current`.
    #[error(
        "design {design:?}: revision {} was committed by someone else first (the design \
         is at revision {current}); reload and edit again", parent + 1
    )]
    Conflict {
        /// The design.
        design: String,
        /// The revision the edit was based on.
        parent: i64,
        /// The design's newest revision.
        current: i64,
    },
    /// No design of that name is stored.
    #[error("no design named {name:?} in the store; stored designs: {}", list(.known))]
    UnknownDesign {
        /// The name asked for.
        name: String,
        /// The stored names (the first 20).
        known: Vec<String>,
    },
    /// A revision given by number, tag or `head` that the design does not have.
    #[error("design {design:?} has no revision {given:?} ({rule})")]
    UnknownRevision {
        /// The design.
        design: String,
        /// The revision as given.
        given: String,
        /// What a revision may be.
        rule: String,
    },
    /// A tag or design name that breaks the naming rule.
    #[error("{what} {value:?} is refused: {rule}")]
    BadName {
        /// `tag` or `design name`.
        what: &'static str,
        /// The name given.
        value: String,
        /// The rule.
        rule: &'static str,
    },
    /// A stored revision that cannot be read back (damaged or edited by hand).
    #[error("design {design:?} revision {revision}: {message}")]
    Corrupt {
        /// The design.
        design: String,
        /// The revision.
        revision: i64,
        /// What is wrong.
        message: String,
    },
    /// A `--where` condition or `--like` request that cannot be read.
    #[error("search: {0}")]
    Search(String),
}

/// The first names of a list, then how many more.
fn list(names: &[String]) -> String {
    if names.is_empty() {
        return "none".into();
    }
    let shown: Vec<&str> = names.iter().take(20).map(String::as_str).collect();
    let mut text = shown.join(", ");
    if names.len() > 20 {
        text.push_str(&format!(" and {} more", names.len() - 20));
    }
    text
}
