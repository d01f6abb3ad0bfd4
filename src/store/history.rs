//! Revisions: importing a design, committing a change on top of a known
//! revision (optimistic concurrency: the `(design, rev)` key lets one writer
//! win, the other gets [`StoreError::Conflict`]), reading the log, a design at
//! any revision, and named tags.
//!
//! A revision row keeps its parent, time, author, message, the exact JSON Patch
//! from its parent and the SHA-256 of the resulting canonical design. The full
//! design text is kept (once per distinct hash) at revision 0, every
//! [`CHECKPOINT`]th revision and every tagged revision; any other revision is
//! the nearest earlier snapshot plus the patches after it, checked against the
//! revision's hash.

use std::collections::BTreeMap;

use serde::Serialize;
use serde_json::Value;

use super::backend::{Backend, SqlValue, is_unique_violation, transaction};
use super::error::StoreError;
use super::features::Features;
use super::open::Store;
use super::snapshot::{apply, canonical_text, content_hash, parse_snapshot, patch_between};
use crate::design::{Design, Units};

/// A full snapshot is kept every this many revisions.
pub const CHECKPOINT: i64 = 32;

/// The `NOTIFY` channel of committed revisions; the payload is
/// `<revision> <design>`.
pub const CHANNEL: &str = "vesselcad_revisions";

/// Who made a change and why.
#[derive(Clone, Debug, Default)]
pub struct Change {
    /// The author (a user name).
    pub author: String,
    /// The message.
    pub message: String,
}

/// One revision of a design.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Revision {
    /// The revision number, from 0 (the import).
    pub rev: i64,
    /// The revision it changes (none for 0).
    pub parent: Option<i64>,
    /// When it was committed (RFC 3339, UTC).
    pub at: String,
    /// Who committed it.
    pub author: String,
    /// Why.
    pub message: String,
    /// The JSON Patch from the parent's design to this one.
    pub patch: Value,
    /// SHA-256 of the canonical design.
    pub hash: String,
    /// The tags naming it.
    pub tags: Vec<String>,
}

/// The rule a tag or design name follows.
const NAME_RULE: &str = "1 to 64 characters: letters, digits, `-`, `_`, `.`, not only digits for \
                         a design, not `head`";

fn check_name(what: &'static str, value: &str) -> Result<(), StoreError> {
    let ok = !value.is_empty()
        && value.len() <= 64
        && value != "head"
        && value
            .chars()
            .all(|c| c.is_ascii_alphanumeric() || matches!(c, '-' | '_' | '.'));
    if ok {
        Ok(())
    } else {
        Err(StoreError::BadName {
            what,
            value: value.to_string(),
            rule: NAME_RULE,
        })
    }
}

fn now() -> String {
    chrono::Utc::now().to_rfc3339_opts(chrono::SecondsFormat::Millis, true)
}

fn units_name(units: Units) -> &'static str {
    match units {
        Units::Mm => "mm",
        Units::In => "in",
    }
}

impl Store {
    /// Stores `design` (in mm) under `name`: a new design's revision 0, or for
    /// a stored design a new revision with the changes from its newest one
    /// (none if it is the same design). `units` is the unit the file was
    /// written in, which `store export` writes back.
    ///
    /// # Errors
    ///
    /// [`StoreError::BadName`], [`StoreError::Database`].
    pub fn import(
        &mut self,
        name: &str,
        design: &Design,
        units: Units,
        change: &Change,
    ) -> Result<Revision, StoreError> {
        check_name("design name", name)?;
        if name.chars().all(|c| c.is_ascii_digit()) {
            return Err(StoreError::BadName {
                what: "design name",
                value: name.to_string(),
                rule: NAME_RULE,
            });
        }
        if let Some(head) = self.head(name)? {
            let current = self.design_at(name, head)?;
            if canonical_text(&current) == canonical_text(design) {
                return self.revision(name, head);
            }
            return self.commit(name, head, &current, design, change);
        }
        let text = canonical_text(design);
        let hash = content_hash(&text);
        let at = now();
        let units = units_name(units);
        let features: Vec<Features> = design.vessels.iter().map(Features::of).collect();
        transaction(self.db.as_mut(), |db| {
            let created = db.execute(
                "INSERT INTO designs (name, units, created) VALUES ($1, $2, $3)
                 ON CONFLICT (name) DO NOTHING",
                &[name.into(), units.into(), at.as_str().into()],
            )?;
            if created == 0 {
                return Err(StoreError::Conflict {
                    design: name.to_string(),
                    parent: -1,
                    current: 0,
                });
            }
            put_snapshot(db, &hash, &text)?;
            db.execute(
                "INSERT INTO revisions (design, rev, parent, at, author, message, patch, hash)
                 VALUES ($1, 0, NULL, $2, $3, $4, '[]', $5)",
                &[
                    name.into(),
                    at.as_str().into(),
                    change.author.as_str().into(),
                    change.message.as_str().into(),
                    hash.as_str().into(),
                ],
            )?;
            for f in &features {
                put_features(db, name, 0, f)?;
            }
            db.notify(CHANNEL, &format!("0 {name}"))
        })?;
        self.revision(name, 0)
    }

    /// Commits the change from `before` (the design at revision `parent`) to
    /// `after` as revision `parent + 1`, and returns it. Durable when this
    /// returns (SQLite `synchronous=FULL`, PostgreSQL commit).
    ///
    /// # Errors
    ///
    /// [`StoreError::Conflict`] when `parent` is not the newest revision any
    /// more (nothing is written), [`StoreError::UnknownDesign`],
    /// [`StoreError::Database`].
    pub fn commit(
        &mut self,
        name: &str,
        parent: i64,
        before: &Design,
        after: &Design,
        change: &Change,
    ) -> Result<Revision, StoreError> {
        let rev = parent + 1;
        let patch = patch_between(before, after);
        let text = canonical_text(after);
        let hash = content_hash(&text);
        let at = now();
        let patch_text = serde_json::to_string(&patch).unwrap_or_else(|_| "[]".into());
        let features = changed_features(before, after);
        let outcome = transaction(self.db.as_mut(), |db| {
            let head = db
                .query(
                    "SELECT max(rev) FROM revisions WHERE design = $1",
                    &[name.into()],
                )?
                .first()
                .and_then(|r| r[0].int());
            match head {
                None => return Err(unknown(name)),
                Some(head) if head != parent => {
                    return Err(StoreError::Conflict {
                        design: name.to_string(),
                        parent,
                        current: head,
                    });
                }
                Some(_) => {}
            }
            if rev % CHECKPOINT == 0 {
                put_snapshot(db, &hash, &text)?;
            }
            db.execute(
                "INSERT INTO revisions (design, rev, parent, at, author, message, patch, hash)
                 VALUES ($1, $2, $3, $4, $5, $6, $7, $8)",
                &[
                    name.into(),
                    rev.into(),
                    parent.into(),
                    at.as_str().into(),
                    change.author.as_str().into(),
                    change.message.as_str().into(),
                    patch_text.as_str().into(),
                    hash.as_str().into(),
                ],
            )?;
            for (tag, f) in &features {
                match f {
                    Some(f) => put_features(db, name, rev, f)?,
                    None => {
                        db.execute(
                            "DELETE FROM vessels WHERE design = $1 AND tag = $2",
                            &[name.into(), tag.as_str().into()],
                        )?;
                    }
                }
            }
            db.notify(CHANNEL, &format!("{rev} {name}"))
        });
        match outcome {
            Ok(()) => {}
            // Another writer took revision `rev` between our check and insert.
            Err(e) if is_unique_violation(&e) => {
                let current = self.head(name)?.unwrap_or(parent);
                return Err(StoreError::Conflict {
                    design: name.to_string(),
                    parent,
                    current,
                });
            }
            Err(StoreError::UnknownDesign { name, .. }) => {
                return Err(StoreError::UnknownDesign {
                    name,
                    known: self.names()?,
                });
            }
            Err(e) => return Err(e),
        }
        Ok(Revision {
            rev,
            parent: Some(parent),
            at,
            author: change.author.clone(),
            message: change.message.clone(),
            patch,
            hash,
            tags: Vec::new(),
        })
    }

    /// Every revision of `design`, oldest first, with their tags.
    ///
    /// # Errors
    ///
    /// [`StoreError::UnknownDesign`], [`StoreError::Database`].
    pub fn log(&mut self, design: &str) -> Result<Vec<Revision>, StoreError> {
        self.revisions_after(design, -1)
    }

    /// The revisions of `design` after `rev`, oldest first.
    ///
    /// # Errors
    ///
    /// [`StoreError::UnknownDesign`], [`StoreError::Database`].
    pub fn revisions_after(&mut self, design: &str, rev: i64) -> Result<Vec<Revision>, StoreError> {
        self.require(design)?;
        let mut tags: BTreeMap<i64, Vec<String>> = BTreeMap::new();
        for row in self.db.query(
            "SELECT rev, name FROM tags WHERE design = $1 ORDER BY name",
            &[design.into()],
        )? {
            if let (Some(r), Some(n)) = (row[0].int(), row[1].text()) {
                tags.entry(r).or_default().push(n.to_string());
            }
        }
        let rows = self.db.query(
            "SELECT rev, parent, at, author, message, patch, hash FROM revisions
             WHERE design = $1 AND rev > $2 ORDER BY rev",
            &[design.into(), rev.into()],
        )?;
        rows.into_iter()
            .map(|row| {
                let rev = row[0].int().unwrap_or(0);
                let patch = serde_json::from_str(row[5].text().unwrap_or("[]")).map_err(|e| {
                    StoreError::Corrupt {
                        design: design.to_string(),
                        revision: rev,
                        message: format!("its patch is not JSON: {e}"),
                    }
                })?;
                Ok(Revision {
                    rev,
                    parent: row[1].int(),
                    at: row[2].text().unwrap_or_default().to_string(),
                    author: row[3].text().unwrap_or_default().to_string(),
                    message: row[4].text().unwrap_or_default().to_string(),
                    patch,
                    hash: row[6].text().unwrap_or_default().to_string(),
                    tags: tags.remove(&rev).unwrap_or_default(),
                })
            })
            .collect()
    }

    /// One revision.
    ///
    /// # Errors
    ///
    /// [`StoreError::UnknownRevision`] and as [`Store::log`].
    pub fn revision(&mut self, design: &str, rev: i64) -> Result<Revision, StoreError> {
        self.revisions_after(design, rev - 1)?
            .into_iter()
            .next()
            .filter(|r| r.rev == rev)
            .ok_or_else(|| unknown_revision(design, &rev.to_string()))
    }

    /// The design at revision `rev`: the nearest snapshot at or before it, then
    /// the patches after it, checked against the revision's hash.
    ///
    /// # Errors
    ///
    /// [`StoreError::UnknownRevision`], [`StoreError::Corrupt`] when the stored
    /// patches do not lead to the stored hash, [`StoreError::Database`].
    pub fn design_at(&mut self, design: &str, rev: i64) -> Result<Design, StoreError> {
        self.require(design)?;
        let base = self.db.query(
            "SELECT r.rev, s.body FROM revisions r JOIN snapshots s ON s.hash = r.hash
             WHERE r.design = $1 AND r.rev <= $2 ORDER BY r.rev DESC LIMIT 1",
            &[design.into(), rev.into()],
        )?;
        let Some(base) = base.first() else {
            return Err(unknown_revision(design, &rev.to_string()));
        };
        let from = base[0].int().unwrap_or(0);
        let corrupt = |revision: i64, message: String| StoreError::Corrupt {
            design: design.to_string(),
            revision,
            message,
        };
        let mut current = parse_snapshot(base[1].text().unwrap_or_default())
            .map_err(|e| corrupt(from, format!("its snapshot is not a design: {e}")))?;
        let steps = self.db.query(
            "SELECT rev, patch, hash FROM revisions
             WHERE design = $1 AND rev > $2 AND rev <= $3 ORDER BY rev",
            &[design.into(), from.into(), rev.into()],
        )?;
        let mut last = from;
        let mut hash = None;
        for step in &steps {
            last = step[0].int().unwrap_or(0);
            let patch: Value = serde_json::from_str(step[1].text().unwrap_or_default())
                .map_err(|e| corrupt(last, format!("its patch is not JSON: {e}")))?;
            current = apply(&current, &patch)
                .map_err(|e| corrupt(last, format!("its patch does not apply: {e}")))?;
            hash = step[2].text().map(str::to_string);
        }
        if last != rev {
            return Err(unknown_revision(design, &rev.to_string()));
        }
        if let Some(expected) = hash
            && content_hash(&canonical_text(&current)) != expected
        {
            return Err(corrupt(
                rev,
                "replaying the patches does not give the design its hash names".into(),
            ));
        }
        Ok(current)
    }

    /// The revision `given` names: a number, a tag, or `head`.
    ///
    /// # Errors
    ///
    /// [`StoreError::UnknownRevision`], [`StoreError::UnknownDesign`],
    /// [`StoreError::Database`].
    pub fn resolve(&mut self, design: &str, given: &str) -> Result<i64, StoreError> {
        self.require(design)?;
        let head = self.head(design)?.unwrap_or(0);
        if given == "head" {
            return Ok(head);
        }
        let tagged = self.db.query(
            "SELECT rev FROM tags WHERE design = $1 AND name = $2",
            &[design.into(), given.into()],
        )?;
        if let Some(rev) = tagged.first().and_then(|r| r[0].int()) {
            return Ok(rev);
        }
        match given.parse::<i64>() {
            Ok(rev) if (0..=head).contains(&rev) => Ok(rev),
            _ => Err(unknown_revision(design, given)),
        }
    }

    /// Names revision `rev` of `design` `tag` (moving the tag if it named
    /// another revision), and keeps that revision's full snapshot.
    ///
    /// # Errors
    ///
    /// [`StoreError::BadName`], [`StoreError::UnknownRevision`],
    /// [`StoreError::Database`].
    pub fn tag(&mut self, design: &str, tag: &str, rev: i64) -> Result<(), StoreError> {
        check_name("tag", tag)?;
        let snapshot = self.design_at(design, rev)?;
        let text = canonical_text(&snapshot);
        let hash = content_hash(&text);
        transaction(self.db.as_mut(), |db| {
            put_snapshot(db, &hash, &text)?;
            db.execute(
                "DELETE FROM tags WHERE design = $1 AND name = $2",
                &[design.into(), tag.into()],
            )?;
            db.execute(
                "INSERT INTO tags (design, name, rev) VALUES ($1, $2, $3)",
                &[design.into(), tag.into(), rev.into()],
            )?;
            Ok(())
        })
    }

    /// The unit `design` was imported in.
    ///
    /// # Errors
    ///
    /// [`StoreError::UnknownDesign`], [`StoreError::Database`].
    pub fn units(&mut self, design: &str) -> Result<Units, StoreError> {
        self.require(design)?;
        let rows = self.db.query(
            "SELECT units FROM designs WHERE name = $1",
            &[design.into()],
        )?;
        Ok(match rows.first().and_then(|r| r[0].text()) {
            Some("in") => Units::In,
            _ => Units::Mm,
        })
    }

    /// Refuses a design that is not stored.
    fn require(&mut self, design: &str) -> Result<(), StoreError> {
        let rows = self
            .db
            .query("SELECT 1 FROM designs WHERE name = $1", &[design.into()])?;
        if rows.is_empty() {
            return Err(StoreError::UnknownDesign {
                name: design.to_string(),
                known: self.names()?,
            });
        }
        Ok(())
    }
}

fn unknown(name: &str) -> StoreError {
    StoreError::UnknownDesign {
        name: name.to_string(),
        known: Vec::new(),
    }
}

fn unknown_revision(design: &str, given: &str) -> StoreError {
    StoreError::UnknownRevision {
        design: design.to_string(),
        given: given.to_string(),
        rule: "a revision is a number from 0 to the newest, a tag, or `head`".into(),
    }
}

/// Keeps a snapshot (once per hash).
fn put_snapshot(db: &mut dyn Backend, hash: &str, text: &str) -> Result<(), StoreError> {
    db.execute(
        "INSERT INTO snapshots (hash, body) VALUES ($1, $2) ON CONFLICT (hash) DO NOTHING",
        &[hash.into(), text.into()],
    )
    .map(|_| ())
}

/// Writes one vessel's feature row.
fn put_features(
    db: &mut dyn Backend,
    design: &str,
    rev: i64,
    f: &Features,
) -> Result<(), StoreError> {
    db.execute(
        "DELETE FROM vessels WHERE design = $1 AND tag = $2",
        &[design.into(), f.tag.as_str().into()],
    )?;
    let values: Vec<SqlValue> = vec![
        design.into(),
        f.tag.as_str().into(),
        rev.into(),
        f.kind.as_str().into(),
        f.head.as_str().into(),
        f.material.as_str().into(),
        f.od.into(),
        f.length.into(),
        f.pressure.into(),
        f.temperature.into(),
        f.nozzles.into(),
        f.max_nozzle.into(),
        f.nozzle_total.into(),
    ];
    db.execute(
        "INSERT INTO vessels (design, tag, rev, kind, head, material, od, length, pressure,
                              temperature, nozzles, max_nozzle, nozzle_total)
         VALUES ($1, $2, $3, $4, $5, $6, $7, $8, $9, $10, $11, $12, $13)",
        &values,
    )
    .map(|_| ())
}

/// The feature rows a change writes: each vessel whose features differ (or
/// that is new) by tag, and `None` for each vessel removed.
fn changed_features(before: &Design, after: &Design) -> Vec<(String, Option<Features>)> {
    let old: BTreeMap<&str, Features> = before
        .vessels
        .iter()
        .map(|v| (v.tag.as_str(), Features::of(v)))
        .collect();
    let mut out = Vec::new();
    let mut kept = std::collections::BTreeSet::new();
    for vessel in &after.vessels {
        kept.insert(vessel.tag.as_str());
        let f = Features::of(vessel);
        if old.get(vessel.tag.as_str()) != Some(&f) {
            out.push((vessel.tag.clone(), Some(f)));
        }
    }
    for tag in old.keys() {
        if !kept.contains(tag) {
            out.push((tag.to_string(), None));
        }
    }
    out
}
