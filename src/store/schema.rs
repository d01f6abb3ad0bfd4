//! The store's tables and their versioned migrations. `schema_version` holds one
//! row, the number of migrations applied; opening a store applies the missing
//! ones in one transaction each, and refuses a database newer than this program.
//!
//! Version 1:
//!
//! ```text
//! designs    name PK, units, created                         one row per design
//! snapshots  hash PK, body                                   canonical design JSON (mm),
//!                                                            keyed by its SHA-256
//! revisions  (design, rev) PK, parent, at, author, message,  every accepted change; the
//!            patch, hash                                     PK serialises writers
//! tags       (design, name) PK, rev                          named revisions (A, B, 0)
//! vessels    (design, tag) PK, rev, kind, head, material,    the search features of each
//!            od, length, pressure, temperature, nozzles,     design's newest revision
//!            max_nozzle, nozzle_total                        (indexed on pressure, and on
//!                                                            od with every column: covering)
//! ```
//!
//! The SQL is the subset SQLite and PostgreSQL share.

use super::backend::{Backend, Dialect, transaction};
use super::error::StoreError;

/// The migrations, in order; the schema version is how many have run.
const MIGRATIONS: &[&str] = &[
    // 1: the first schema.
    "CREATE TABLE designs (
        name TEXT PRIMARY KEY,
        units TEXT NOT NULL,
        created TEXT NOT NULL
    );
    CREATE TABLE snapshots (
        hash TEXT PRIMARY KEY,
        body TEXT NOT NULL
    );
    CREATE TABLE revisions (
        design TEXT NOT NULL REFERENCES designs(name),
        rev BIGINT NOT NULL,
        parent BIGINT,
        at TEXT NOT NULL,
        author TEXT NOT NULL,
        message TEXT NOT NULL,
        patch TEXT NOT NULL,
        hash TEXT NOT NULL,
        PRIMARY KEY (design, rev)
    );
    CREATE INDEX revisions_hash ON revisions (hash);
    CREATE TABLE tags (
        design TEXT NOT NULL REFERENCES designs(name),
        name TEXT NOT NULL,
        rev BIGINT NOT NULL,
        PRIMARY KEY (design, name)
    );
    CREATE TABLE vessels (
        design TEXT NOT NULL REFERENCES designs(name),
        tag TEXT NOT NULL,
        rev BIGINT NOT NULL,
        kind TEXT NOT NULL,
        head TEXT NOT NULL,
        material TEXT NOT NULL,
        od DOUBLE PRECISION NOT NULL,
        length DOUBLE PRECISION NOT NULL,
        pressure DOUBLE PRECISION NOT NULL,
        temperature DOUBLE PRECISION NOT NULL,
        nozzles BIGINT NOT NULL,
        max_nozzle DOUBLE PRECISION NOT NULL,
        nozzle_total DOUBLE PRECISION NOT NULL,
        PRIMARY KEY (design, tag)
    );
    CREATE INDEX vessels_od ON vessels (od);
    CREATE INDEX vessels_pressure ON vessels (pressure);",
    // 2: a covering index for the search: every column a search reads, led by
    // `od` (which it replaces), so a search reads the index alone.
    "CREATE INDEX vessels_features ON vessels (od, length, pressure, temperature, kind, head,
        material, nozzles, max_nozzle, nozzle_total, rev, design, tag);
    DROP INDEX vessels_od;",
];

/// The schema version this program writes.
pub const SCHEMA_VERSION: i64 = MIGRATIONS.len() as i64;

/// Brings the database at `location` to [`SCHEMA_VERSION`].
///
/// # Errors
///
/// [`StoreError::NewerSchema`] for a database written by a newer vesselcad;
/// [`StoreError::Database`] when a migration fails (it is rolled back).
pub fn migrate(db: &mut dyn Backend, location: &str) -> Result<(), StoreError> {
    db.batch("CREATE TABLE IF NOT EXISTS schema_version (version BIGINT NOT NULL)")?;
    loop {
        let applied = transaction(db, |db| {
            if db.dialect() == Dialect::Postgres {
                // Two servers starting at once: one migrates, the other waits.
                db.batch("LOCK TABLE schema_version IN EXCLUSIVE MODE")?;
            }
            let rows = db.query("SELECT version FROM schema_version", &[])?;
            let version = match rows.first() {
                Some(row) => row[0].int().unwrap_or(0),
                None => {
                    db.execute("INSERT INTO schema_version (version) VALUES (0)", &[])?;
                    0
                }
            };
            if version > SCHEMA_VERSION {
                return Err(StoreError::NewerSchema {
                    location: location.to_string(),
                    found: version,
                    known: SCHEMA_VERSION,
                });
            }
            if version == SCHEMA_VERSION {
                return Ok(false);
            }
            db.batch(MIGRATIONS[version as usize])?;
            db.execute(
                "UPDATE schema_version SET version = $1",
                &[(version + 1).into()],
            )?;
            Ok(true)
        })?;
        if !applied {
            return Ok(());
        }
    }
}
