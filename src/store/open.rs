//! Opening a store: a `postgres://` or `postgresql://` URL is a PostgreSQL
//! database, anything else the path of a SQLite file (created on first use).
//! Either way the schema is brought up to date ([`super::schema`]) and the
//! [`Store`] holds one connection.

use std::path::Path;

use super::backend::{Backend, Dialect};
use super::error::StoreError;
use super::pg::{Postgres, redact};
use super::schema::migrate;
use super::sqlite::Sqlite;

/// An open design store.
pub struct Store {
    pub(super) db: Box<dyn Backend>,
    pub(super) location: String,
}

/// Whether `location` names a PostgreSQL database rather than a SQLite file.
pub fn is_postgres_url(location: &str) -> bool {
    location.starts_with("postgres://") || location.starts_with("postgresql://")
}

/// A stored design: its name, its newest revision and when that was made.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct DesignEntry {
    /// The design's name.
    pub name: String,
    /// Its newest revision.
    pub head: i64,
    /// When the newest revision was committed (RFC 3339, UTC).
    pub at: String,
    /// Who committed it.
    pub author: String,
    /// The file's length unit (`mm` or `in`), used by `store export`.
    pub units: String,
    /// How many vessels the newest revision has.
    pub vessels: i64,
}

/// How much a store holds.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize)]
pub struct Stats {
    /// Designs.
    pub designs: i64,
    /// Revisions of all designs.
    pub revisions: i64,
    /// Distinct design snapshots kept (content-addressed, so shared).
    pub snapshots: i64,
    /// Vessels in the search index (each design's newest revision).
    pub vessels: i64,
}

impl Store {
    /// Opens the store at `location` (a SQLite path or a PostgreSQL URL).
    ///
    /// # Errors
    ///
    /// [`StoreError::Database`] when it cannot be opened or reached,
    /// [`StoreError::NewerSchema`] for a database of a newer vesselcad.
    pub fn open(location: &str) -> Result<Store, StoreError> {
        let (mut db, shown): (Box<dyn Backend>, String) = if is_postgres_url(location) {
            (Box::new(Postgres::connect(location)?), redact(location))
        } else {
            (
                Box::new(Sqlite::open(Path::new(location))?),
                location.to_string(),
            )
        };
        migrate(db.as_mut(), &shown)?;
        Ok(Store {
            db,
            location: shown,
        })
    }

    /// Where the store is (a PostgreSQL URL without its password).
    pub fn location(&self) -> &str {
        &self.location
    }

    /// Which database it is.
    pub fn dialect(&self) -> Dialect {
        self.db.dialect()
    }

    /// Every stored design, by name.
    ///
    /// # Errors
    ///
    /// [`StoreError::Database`].
    pub fn designs(&mut self) -> Result<Vec<DesignEntry>, StoreError> {
        let rows = self.db.query(
            "SELECT d.name, r.rev, r.at, r.author, d.units,
                    (SELECT count(*) FROM vessels v WHERE v.design = d.name)
             FROM designs d JOIN revisions r ON r.design = d.name
             WHERE r.rev = (SELECT max(rev) FROM revisions WHERE design = d.name)
             ORDER BY d.name",
            &[],
        )?;
        Ok(rows
            .into_iter()
            .map(|row| DesignEntry {
                name: row[0].text().unwrap_or_default().to_string(),
                head: row[1].int().unwrap_or(0),
                at: row[2].text().unwrap_or_default().to_string(),
                author: row[3].text().unwrap_or_default().to_string(),
                units: row[4].text().unwrap_or_default().to_string(),
                vessels: row[5].int().unwrap_or(0),
            })
            .collect())
    }

    /// How many designs, revisions, snapshots and indexed vessels it holds.
    ///
    /// # Errors
    ///
    /// [`StoreError::Database`].
    pub fn stats(&mut self) -> Result<Stats, StoreError> {
        let rows = self.db.query(
            "SELECT (SELECT count(*) FROM designs), (SELECT count(*) FROM revisions),
                    (SELECT count(*) FROM snapshots), (SELECT count(*) FROM vessels)",
            &[],
        )?;
        let count = |k: usize| rows.first().and_then(|r| r[k].int()).unwrap_or(0);
        Ok(Stats {
            designs: count(0),
            revisions: count(1),
            snapshots: count(2),
            vessels: count(3),
        })
    }

    /// The names of every stored design.
    pub(super) fn names(&mut self) -> Result<Vec<String>, StoreError> {
        let rows = self
            .db
            .query("SELECT name FROM designs ORDER BY name", &[])?;
        Ok(rows
            .into_iter()
            .filter_map(|r| r[0].text().map(str::to_string))
            .collect())
    }

    /// The newest revision of `design`, or `None` if it is not stored.
    ///
    /// # Errors
    ///
    /// [`StoreError::Database`].
    pub fn head(&mut self, design: &str) -> Result<Option<i64>, StoreError> {
        let rows = self.db.query(
            "SELECT max(rev) FROM revisions WHERE design = $1",
            &[design.into()],
        )?;
        Ok(rows.first().and_then(|r| r[0].int()))
    }
}
