//! The stores every store suite runs against: a SQLite file in a temporary
//! folder always, and a fresh schema of the PostgreSQL database named by
//! `$VESSELCAD_TEST_PG` when it is set (`.ci/run` sets it).

use std::sync::atomic::{AtomicUsize, Ordering};

/// One store location for a test, and what keeps it alive.
pub struct TestStore {
    /// `sqlite` or `postgres`.
    pub label: &'static str,
    /// What `Store::open` and `--store` take.
    pub location: String,
    /// The SQLite file's folder (removed when dropped).
    pub dir: Option<tempfile::TempDir>,
}

/// The PostgreSQL URL of the test database, if the environment names one.
pub fn postgres_url() -> Option<String> {
    std::env::var("VESSELCAD_TEST_PG")
        .ok()
        .filter(|u| !u.is_empty())
}

/// A fresh SQLite store.
pub fn sqlite_store() -> TestStore {
    let dir = tempfile::tempdir().expect("temp dir");
    TestStore {
        label: "sqlite",
        location: dir.path().join("vesselcad.db").display().to_string(),
        dir: Some(dir),
    }
}

/// A fresh, empty schema in the test database, as a URL that selects it.
pub fn postgres_store(url: &str) -> TestStore {
    static NEXT: AtomicUsize = AtomicUsize::new(0);
    let nanos = std::time::SystemTime::now()
        .duration_since(std::time::UNIX_EPOCH)
        .map_or(0, |d| d.subsec_nanos());
    let schema = format!(
        "t_{}_{}_{nanos}",
        std::process::id(),
        NEXT.fetch_add(1, Ordering::Relaxed)
    );
    let mut client = postgres::Client::connect(url, postgres::NoTls)
        .unwrap_or_else(|e| panic!("VESSELCAD_TEST_PG={url}: {e}"));
    client
        .batch_execute(&format!("CREATE SCHEMA {schema}"))
        .expect("create schema");
    let sep = if url.contains('?') { '&' } else { '?' };
    TestStore {
        label: "postgres",
        location: format!("{url}{sep}options=-csearch_path%3D{schema}"),
        dir: None,
    }
}

/// A fresh SQLite store, and a fresh PostgreSQL one when the test database is set.
pub fn test_stores() -> Vec<TestStore> {
    let mut out = vec![sqlite_store()];
    if let Some(url) = postgres_url() {
        out.push(postgres_store(&url));
    } else {
        eprintln!("VESSELCAD_TEST_PG is not set: PostgreSQL not tested");
    }
    out
}
