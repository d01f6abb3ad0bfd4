//! The design store: every design and every accepted edit as a revision (parent,
//! time, author, message, JSON Patch, SHA-256 of the canonical design), named
//! revisions (tags `A`, `B`, `0` that match a drawing's revision block),
//! content-addressed snapshots, and a feature row per vessel for similar-design
//! search — in SQLite (one file, the default) or PostgreSQL (a team), with the
//! same schema and the same SQL.
//!
//! Where it sits: `vesselcad store …` reads and writes it ([`Store`]);
//! `vesselcad serve --store` commits each edit here before acknowledging it, and
//! with PostgreSQL several servers share a design, serialised by the revision
//! key and told of each other's revisions by `NOTIFY` on [`CHANNEL`]. The only
//! database-specific code is behind [`backend::Backend`].

pub mod backend;
pub mod diff;
pub mod error;
pub mod features;
pub mod history;
pub mod open;
pub mod pg;
pub mod schema;
pub mod search;
pub mod snapshot;
pub mod sqlite;

pub use diff::{Changed, diff};
pub use error::StoreError;
pub use features::Features;
pub use history::{CHANNEL, CHECKPOINT, Change, Revision};
pub use open::{DesignEntry, Stats, Store, is_postgres_url};
pub use schema::SCHEMA_VERSION;
pub use search::Hit;
