//! The SQLite backend: one file, WAL journal, `synchronous=FULL` (a commit is on
//! disk before it returns, so an acknowledged revision survives a crash or power
//! loss), foreign keys on, and a busy timeout so two processes on one file wait
//! for each other rather than fail. `$N` placeholders become SQLite's `?N`.

use std::path::Path;
use std::time::Duration;

use rusqlite::types::{Value as Lite, ValueRef};
use rusqlite::{Connection, params_from_iter};

use super::backend::{Backend, Dialect, Row, SqlValue, UNIQUE};
use super::error::StoreError;

/// How long a writer waits for another process's transaction.
const BUSY_TIMEOUT: Duration = Duration::from_secs(10);

/// An open SQLite store.
pub struct Sqlite {
    connection: Connection,
    location: String,
}

impl Sqlite {
    /// Opens (creating if needed) the database file at `path`.
    ///
    /// # Errors
    ///
    /// [`StoreError::Database`] when the file cannot be opened or is not a
    /// SQLite database.
    pub fn open(path: &Path) -> Result<Sqlite, StoreError> {
        let location = path.display().to_string();
        let fail = |e: rusqlite::Error| StoreError::Database {
            location: location.clone(),
            message: e.to_string(),
        };
        let connection = Connection::open(path).map_err(fail)?;
        connection.busy_timeout(BUSY_TIMEOUT).map_err(fail)?;
        // `journal_mode` answers with a row; the others are plain settings.
        let mode: String = connection
            .query_row("PRAGMA journal_mode=WAL", [], |row| row.get(0))
            .map_err(fail)?;
        if !mode.eq_ignore_ascii_case("wal") {
            return Err(StoreError::Database {
                location,
                message: format!("cannot switch to WAL mode (the file stays in {mode} mode)"),
            });
        }
        connection
            .execute_batch("PRAGMA synchronous=FULL; PRAGMA foreign_keys=ON;")
            .map_err(fail)?;
        Ok(Sqlite {
            connection,
            location,
        })
    }

    fn error(&self, e: rusqlite::Error) -> StoreError {
        let unique = matches!(
            &e,
            rusqlite::Error::SqliteFailure(f, _)
                if f.extended_code == rusqlite::ffi::SQLITE_CONSTRAINT_PRIMARYKEY
                    || f.extended_code == rusqlite::ffi::SQLITE_CONSTRAINT_UNIQUE
        );
        StoreError::Database {
            location: self.location.clone(),
            message: if unique {
                format!("{UNIQUE}: {e}")
            } else {
                e.to_string()
            },
        }
    }
}

/// `$N` → `?N` (the store's SQL has no `$` elsewhere).
fn placeholders(sql: &str) -> String {
    sql.replace('$', "?")
}

fn to_lite(value: &SqlValue) -> Lite {
    match value {
        SqlValue::Null => Lite::Null,
        SqlValue::Int(i) => Lite::Integer(*i),
        SqlValue::Real(f) => Lite::Real(*f),
        SqlValue::Text(s) => Lite::Text(s.clone()),
    }
}

fn from_lite(value: ValueRef<'_>) -> SqlValue {
    match value {
        ValueRef::Null => SqlValue::Null,
        ValueRef::Integer(i) => SqlValue::Int(i),
        ValueRef::Real(f) => SqlValue::Real(f),
        ValueRef::Text(t) | ValueRef::Blob(t) => {
            SqlValue::Text(String::from_utf8_lossy(t).into_owned())
        }
    }
}

impl Backend for Sqlite {
    fn dialect(&self) -> Dialect {
        Dialect::Sqlite
    }

    fn batch(&mut self, sql: &str) -> Result<(), StoreError> {
        self.connection
            .execute_batch(sql)
            .map_err(|e| self.error(e))
    }

    fn execute(&mut self, sql: &str, params: &[SqlValue]) -> Result<u64, StoreError> {
        let sql = placeholders(sql);
        let result = self
            .connection
            .prepare_cached(&sql)
            .and_then(|mut s| s.execute(params_from_iter(params.iter().map(to_lite))));
        result.map(|n| n as u64).map_err(|e| self.error(e))
    }

    fn query(&mut self, sql: &str, params: &[SqlValue]) -> Result<Vec<Row>, StoreError> {
        let sql = placeholders(sql);
        let result = (|| {
            let mut statement = self.connection.prepare_cached(&sql)?;
            let width = statement.column_count();
            let mut rows = statement.query(params_from_iter(params.iter().map(to_lite)))?;
            let mut out = Vec::new();
            while let Some(row) = rows.next()? {
                let mut values = Vec::with_capacity(width);
                for k in 0..width {
                    values.push(from_lite(row.get_ref(k)?));
                }
                out.push(values);
            }
            Ok(out)
        })();
        result.map_err(|e| self.error(e))
    }

    fn begin(&mut self) -> Result<(), StoreError> {
        self.batch("BEGIN IMMEDIATE")
    }

    fn notify(&mut self, _channel: &str, _payload: &str) -> Result<(), StoreError> {
        Ok(())
    }
}
