//! The one seam between the store and a database: a [`Backend`] runs SQL text
//! with positional parameters (`$1`, `$2`, … in every statement, as PostgreSQL
//! writes them) and returns rows of plain [`SqlValue`]s. The store's queries are
//! written once, in the SQL both SQLite and PostgreSQL accept (`BIGINT`,
//! `DOUBLE PRECISION`, `TEXT`, `ON CONFLICT … DO NOTHING`); each backend only
//! maps values and placeholders ([`super::sqlite`], [`super::pg`]).

use super::error::StoreError;

/// A value going into or coming out of a statement.
#[derive(Clone, Debug, PartialEq)]
pub enum SqlValue {
    /// SQL `NULL`.
    Null,
    /// An integer (`BIGINT`).
    Int(i64),
    /// A float (`DOUBLE PRECISION`).
    Real(f64),
    /// Text.
    Text(String),
}

impl SqlValue {
    /// The integer, if it is one.
    pub fn int(&self) -> Option<i64> {
        match self {
            SqlValue::Int(i) => Some(*i),
            _ => None,
        }
    }

    /// The number, integer or float.
    pub fn real(&self) -> Option<f64> {
        match self {
            SqlValue::Real(f) => Some(*f),
            SqlValue::Int(i) => Some(*i as f64),
            _ => None,
        }
    }

    /// The text, if it is text.
    pub fn text(&self) -> Option<&str> {
        match self {
            SqlValue::Text(s) => Some(s),
            _ => None,
        }
    }
}

impl From<i64> for SqlValue {
    fn from(v: i64) -> SqlValue {
        SqlValue::Int(v)
    }
}

impl From<f64> for SqlValue {
    fn from(v: f64) -> SqlValue {
        SqlValue::Real(v)
    }
}

impl From<&str> for SqlValue {
    fn from(v: &str) -> SqlValue {
        SqlValue::Text(v.to_string())
    }
}

impl From<String> for SqlValue {
    fn from(v: String) -> SqlValue {
        SqlValue::Text(v)
    }
}

impl<T: Into<SqlValue>> From<Option<T>> for SqlValue {
    fn from(v: Option<T>) -> SqlValue {
        v.map_or(SqlValue::Null, Into::into)
    }
}

/// One row of a result.
pub type Row = Vec<SqlValue>;

/// Which database a backend speaks.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Dialect {
    /// SQLite (embedded, one file).
    Sqlite,
    /// PostgreSQL (a server).
    Postgres,
}

/// A connection to one database. Statements use `$1`, `$2`, … for parameters.
pub trait Backend: Send {
    /// Which database this is.
    fn dialect(&self) -> Dialect;

    /// Runs statements without parameters or results (schema changes,
    /// `BEGIN`/`COMMIT`), separated by `;`.
    fn batch(&mut self, sql: &str) -> Result<(), StoreError>;

    /// Runs one statement; returns how many rows it changed. A unique-key
    /// violation is a message starting with [`UNIQUE`] (see [`is_unique_violation`]).
    fn execute(&mut self, sql: &str, params: &[SqlValue]) -> Result<u64, StoreError>;

    /// Runs one query and returns its rows.
    fn query(&mut self, sql: &str, params: &[SqlValue]) -> Result<Vec<Row>, StoreError>;

    /// Starts a write transaction (SQLite takes the write lock at once).
    fn begin(&mut self) -> Result<(), StoreError>;

    /// Tells every listener on `channel` (PostgreSQL `NOTIFY`, sent at commit);
    /// nothing on SQLite, whose writers share one machine.
    fn notify(&mut self, channel: &str, payload: &str) -> Result<(), StoreError>;
}

/// The marker a backend puts in the message of a unique-key violation.
pub const UNIQUE: &str = "unique constraint violated";

/// Whether `error` is a unique-key violation (another writer took the key).
pub fn is_unique_violation(error: &StoreError) -> bool {
    matches!(error, StoreError::Database { message, .. } if message.starts_with(UNIQUE))
}

/// Runs `work` in a transaction on `db`: commits if it returns `Ok`, rolls back
/// otherwise.
pub fn transaction<T>(
    db: &mut dyn Backend,
    work: impl FnOnce(&mut dyn Backend) -> Result<T, StoreError>,
) -> Result<T, StoreError> {
    db.begin()?;
    match work(db) {
        Ok(value) => {
            db.batch("COMMIT")?;
            Ok(value)
        }
        Err(e) => {
            // The work's error is the one to report; a failed rollback leaves
            // the transaction to the connection's end.
            let _ = db.batch("ROLLBACK");
            Err(e)
        }
    }
}
