//! The PostgreSQL backend (the `postgres` crate, synchronous): the same SQL as
//! SQLite, with values converted to the types PostgreSQL infers for each
//! parameter and column. Synchronous because the store sits behind the session's
//! lock on a blocking thread, like the SQLite backend, so one code path serves
//! both; `NOTIFY` is sent inside the committing transaction, so listeners hear
//! of a revision exactly when it is visible.

use postgres::types::{ToSql, Type};
use postgres::{Client, NoTls};

use super::backend::{Backend, Dialect, Row, SqlValue, UNIQUE};
use super::error::StoreError;

/// An open PostgreSQL store.
pub struct Postgres {
    client: Client,
    location: String,
}

/// A URL with its password replaced by `***`, for messages.
pub fn redact(url: &str) -> String {
    let Some((scheme, rest)) = url.split_once("://") else {
        return url.to_string();
    };
    match rest.split_once('@') {
        Some((user, host)) => match user.split_once(':') {
            Some((name, _)) => format!("{scheme}://{name}:***@{host}"),
            None => url.to_string(),
        },
        None => url.to_string(),
    }
}

impl Postgres {
    /// Connects to the database at `url` (`postgres://user:password@host/db`).
    ///
    /// # Errors
    ///
    /// [`StoreError::Database`] when the server cannot be reached or refuses.
    pub fn connect(url: &str) -> Result<Postgres, StoreError> {
        let location = redact(url);
        let client = Client::connect(url, NoTls).map_err(|e| StoreError::Database {
            location: location.clone(),
            message: format!("cannot connect: {}", full_message(&e)),
        })?;
        Ok(Postgres { client, location })
    }

    fn error(&self, e: &postgres::Error) -> StoreError {
        if lost(e) || self.client.is_closed() {
            return StoreError::Disconnected {
                location: self.location.clone(),
                message: full_message(e),
            };
        }
        let unique = e.code() == Some(&postgres::error::SqlState::UNIQUE_VIOLATION);
        let message = full_message(e);
        StoreError::Database {
            location: self.location.clone(),
            message: if unique {
                format!("{UNIQUE}: {message}")
            } else {
                message
            },
        }
    }
}

/// Whether `e` means the connection is gone: closed by either side, or the
/// server ending the session (SQLSTATE class 08, or 57P01–57P03: shutdown,
/// `pg_terminate_backend`, cannot connect now).
fn lost(e: &postgres::Error) -> bool {
    e.is_closed()
        || e.code().is_some_and(|c| {
            let code = c.code();
            code.starts_with("08") || matches!(code, "57P01" | "57P02" | "57P03")
        })
}

/// The error with the database's own message (the `postgres` crate's display
/// alone says only "db error").
pub fn full_message(e: &postgres::Error) -> String {
    match e.as_db_error() {
        Some(db) => format!("{e}: {}", db.message()),
        None => match std::error::Error::source(e) {
            Some(source) => format!("{e}: {source}"),
            None => e.to_string(),
        },
    }
}

/// A parameter as the type PostgreSQL expects there.
fn parameter(value: &SqlValue, ty: &Type) -> Box<dyn ToSql + Sync> {
    match (value, ty) {
        (SqlValue::Null, t) if *t == Type::INT8 => Box::new(None::<i64>),
        (SqlValue::Null, t) if *t == Type::INT4 => Box::new(None::<i32>),
        (SqlValue::Null, t) if *t == Type::FLOAT8 => Box::new(None::<f64>),
        (SqlValue::Null, _) => Box::new(None::<String>),
        (SqlValue::Int(i), t) if *t == Type::INT4 => Box::new(*i as i32),
        (SqlValue::Int(i), t) if *t == Type::FLOAT8 => Box::new(*i as f64),
        (SqlValue::Int(i), _) => Box::new(*i),
        (SqlValue::Real(f), t) if *t == Type::INT8 => Box::new(*f as i64),
        (SqlValue::Real(f), _) => Box::new(*f),
        (SqlValue::Text(s), _) => Box::new(s.clone()),
    }
}

/// Column `k` of `row` as a plain value.
fn column(row: &postgres::Row, k: usize) -> Result<SqlValue, postgres::Error> {
    let ty = row.columns()[k].type_();
    Ok(if *ty == Type::INT8 {
        row.try_get::<_, Option<i64>>(k)?.into()
    } else if *ty == Type::INT4 {
        row.try_get::<_, Option<i32>>(k)?.map(i64::from).into()
    } else if *ty == Type::INT2 {
        row.try_get::<_, Option<i16>>(k)?.map(i64::from).into()
    } else if *ty == Type::FLOAT8 {
        row.try_get::<_, Option<f64>>(k)?.into()
    } else if *ty == Type::FLOAT4 {
        row.try_get::<_, Option<f32>>(k)?.map(f64::from).into()
    } else if *ty == Type::BOOL {
        row.try_get::<_, Option<bool>>(k)?.map(i64::from).into()
    } else {
        row.try_get::<_, Option<String>>(k)?.into()
    })
}

impl Postgres {
    fn run(
        &mut self,
        sql: &str,
        params: &[SqlValue],
    ) -> Result<Vec<postgres::Row>, postgres::Error> {
        let statement = self.client.prepare(sql)?;
        let typed: Vec<Box<dyn ToSql + Sync>> = params
            .iter()
            .zip(statement.params())
            .map(|(v, t)| parameter(v, t))
            .collect();
        let refs: Vec<&(dyn ToSql + Sync)> = typed.iter().map(AsRef::as_ref).collect();
        self.client.query(&statement, &refs)
    }
}

impl Backend for Postgres {
    fn dialect(&self) -> Dialect {
        Dialect::Postgres
    }

    fn batch(&mut self, sql: &str) -> Result<(), StoreError> {
        self.client.batch_execute(sql).map_err(|e| self.error(&e))
    }

    fn execute(&mut self, sql: &str, params: &[SqlValue]) -> Result<u64, StoreError> {
        let statement = self.client.prepare(sql).map_err(|e| self.error(&e))?;
        let typed: Vec<Box<dyn ToSql + Sync>> = params
            .iter()
            .zip(statement.params())
            .map(|(v, t)| parameter(v, t))
            .collect();
        let refs: Vec<&(dyn ToSql + Sync)> = typed.iter().map(AsRef::as_ref).collect();
        self.client
            .execute(&statement, &refs)
            .map_err(|e| self.error(&e))
    }

    fn query(&mut self, sql: &str, params: &[SqlValue]) -> Result<Vec<Row>, StoreError> {
        let rows = self.run(sql, params).map_err(|e| self.error(&e))?;
        let mut out = Vec::with_capacity(rows.len());
        for row in &rows {
            let mut values = Vec::with_capacity(row.len());
            for k in 0..row.len() {
                values.push(column(row, k).map_err(|e| self.error(&e))?);
            }
            out.push(values);
        }
        Ok(out)
    }

    fn begin(&mut self) -> Result<(), StoreError> {
        self.batch("BEGIN")
    }

    fn notify(&mut self, channel: &str, payload: &str) -> Result<(), StoreError> {
        self.execute(
            "SELECT pg_notify($1, $2)",
            &[channel.into(), payload.into()],
        )
        .map(|_| ())
    }
}
