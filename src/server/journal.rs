//! The edit journal: every accepted edit, appended to a file beside the design and
//! flushed to disk before the edit is acknowledged, so nothing acknowledged is lost
//! if the server dies.
//!
//! Where it sits: [`super::session`] applies an edit to the model and appends it
//! here under the session lock; the edit route then flushes it (`fdatasync`,
//! one flush for every edit written meanwhile: [`super::flush`]) without the
//! lock, and only then answers the editor and streams the delta. On start the
//! session replays the journal over the design file; `POST /save` and a clean
//! shutdown write the design and start a fresh journal.
//!
//! The file is `<design>.journal`, JSON lines:
//!
//! ```text
//! {"journal":"vesselcad-journal/1","base":"<fingerprint>","revision":R}   header
//! {"revision":R+1,"patch":[...RFC 6902 operations...]}                     an edit
//! {"saved":"<fingerprint>","revision":R+n}                                 a save began
//! ```
//!
//! A fingerprint is the FNV-1a 64 hash and length of the design file's bytes. On
//! replay the design file is matched against the header and the save markers: the
//! edits after the last matching one are replayed. Saving is: append a save marker
//! (`fsync`), write the design (temp file, `fsync`, rename, `fsync` the folder),
//! then replace the journal by a fresh header (same way). A crash at any point
//! leaves a design file that matches either the header (replay everything) or the
//! marker (replay what followed it). A design that matches neither was changed
//! outside the server: the server refuses to start rather than guess. A last line
//! without its newline was never acknowledged (the `fsync` comes after the whole
//! line) and is dropped.

use std::fs::{File, OpenOptions};
use std::io::Write;
use std::path::{Path, PathBuf};
use std::sync::Arc;

use serde::{Deserialize, Serialize};
use serde_json::Value;

use super::error::ServeError;
use super::flush::{GroupFlush, Pending};

/// The journal format tag, in the header line.
pub const JOURNAL_FORMAT: &str = "vesselcad-journal/1";

/// One replayable edit.
#[derive(Clone, Debug, PartialEq)]
pub struct JournalEntry {
    /// Its revision.
    pub revision: u64,
    /// The JSON Patch document as accepted.
    pub patch: Value,
}

/// What the journal says must be replayed over the design file.
#[derive(Debug)]
pub struct Replay {
    /// The revision of the design file itself.
    pub base_revision: u64,
    /// The edits to apply over it, in order.
    pub edits: Vec<JournalEntry>,
    /// The lines not replayed, and why (the session logs them).
    pub dropped: Vec<Dropped>,
}

/// One line of the journal.
#[derive(Serialize, Deserialize)]
#[serde(untagged)]
enum Line {
    Header {
        journal: String,
        base: String,
        revision: u64,
    },
    Edit {
        revision: u64,
        patch: Value,
    },
    Saved {
        saved: String,
        revision: u64,
    },
}

/// The open journal, appending.
#[derive(Debug)]
pub struct Journal {
    path: PathBuf,
    file: File,
    /// Flushes edit lines after the session lock is let go ([`super::flush`]).
    flush: Arc<GroupFlush>,
}

/// The journal path of a design file: `<design>.journal`.
pub fn journal_path(design: &Path) -> PathBuf {
    let mut name = design.file_name().unwrap_or_default().to_os_string();
    name.push(".journal");
    design.with_file_name(name)
}

/// The fingerprint of a design file's bytes: FNV-1a 64 and length.
pub fn fingerprint(bytes: &[u8]) -> String {
    let mut hash: u64 = 0xcbf2_9ce4_8422_2325;
    for &b in bytes {
        hash ^= u64::from(b);
        hash = hash.wrapping_mul(0x0100_0000_01b3);
    }
    format!("{hash:016x}-{}", bytes.len())
}

impl Journal {
    /// Opens the journal of `design` whose file holds `design_bytes`: reads what must
    /// be replayed and opens the file for appending (a fresh journal is created
    /// when there is none, or when it is empty).
    ///
    /// # Errors
    ///
    /// [`ServeError::Journal`] when the file cannot be read or written, a line
    /// other than the last is not a journal line, or the design file matches
    /// neither the journal's base nor a save marker.
    pub fn open(design: &Path, design_bytes: &[u8]) -> Result<(Journal, Replay), ServeError> {
        let path = journal_path(design);
        let print = fingerprint(design_bytes);
        let bytes = match std::fs::read(&path) {
            Ok(bytes) => bytes,
            Err(e) if e.kind() == std::io::ErrorKind::NotFound => Vec::new(),
            Err(e) => return Err(journal_error(&path, e.to_string())),
        };
        if bytes.iter().all(u8::is_ascii_whitespace) {
            let journal = Journal::create(&path, &print, 0)?;
            return Ok((
                journal,
                Replay {
                    base_revision: 0,
                    edits: Vec::new(),
                    dropped: Vec::new(),
                },
            ));
        }
        let recovered = read_lines(&path, &bytes, &print)?;
        if recovered.keep < bytes.len() {
            // Keep what is dropped beside the journal, then cut the journal back to
            // its last intact line so new lines follow it.
            if recovered.replay.dropped.iter().any(|d| d.acknowledged) {
                let mut name = path.file_name().unwrap_or_default().to_os_string();
                name.push(".damaged");
                write_atomically(&path.with_file_name(name), &bytes)
                    .map_err(|e| journal_error(&path, e.to_string()))?;
            }
            let file = OpenOptions::new()
                .write(true)
                .open(&path)
                .map_err(|e| journal_error(&path, e.to_string()))?;
            file.set_len(recovered.keep as u64)
                .and_then(|()| file.sync_all())
                .map_err(|e| journal_error(&path, e.to_string()))?;
        }
        let file = OpenOptions::new()
            .append(true)
            .open(&path)
            .map_err(|e| journal_error(&path, e.to_string()))?;
        Ok((Journal::appending(path, file)?, recovered.replay))
    }

    /// Writes a fresh journal (header only) at `path`, atomically.
    fn create(path: &Path, base: &str, revision: u64) -> Result<Journal, ServeError> {
        let header = Line::Header {
            journal: JOURNAL_FORMAT.to_string(),
            base: base.to_string(),
            revision,
        };
        let mut text = serde_json::to_string(&header).unwrap_or_default();
        text.push('\n');
        write_atomically(path, text.as_bytes()).map_err(|e| journal_error(path, e.to_string()))?;
        let file = OpenOptions::new()
            .append(true)
            .open(path)
            .map_err(|e| journal_error(path, e.to_string()))?;
        Journal::appending(path.to_path_buf(), file)
    }

    /// The journal at `path` appending to `file`.
    fn appending(path: PathBuf, file: File) -> Result<Journal, ServeError> {
        let handle = file
            .try_clone()
            .map_err(|e| journal_error(&path, e.to_string()))?;
        Ok(Journal {
            path,
            file,
            flush: GroupFlush::new(handle),
        })
    }

    /// Appends an accepted edit; it is durable once the returned [`Pending`]
    /// is waited for (after the session lock is let go: group commit).
    ///
    /// # Errors
    ///
    /// The write's error, or the error of an earlier flush that failed (the
    /// journal is then stopped).
    pub fn append(&mut self, revision: u64, patch: &Value) -> std::io::Result<Pending> {
        if let Some(failed) = self.flush.failed() {
            return Err(std::io::Error::other(failed));
        }
        self.write(&Line::Edit {
            revision,
            patch: patch.clone(),
        })?;
        Ok(self.flush.written())
    }

    /// Records that a save of a design with fingerprint `print` at `revision` is
    /// about to be written.
    pub fn mark_saved(&mut self, print: &str, revision: u64) -> std::io::Result<()> {
        self.write_line(&Line::Saved {
            saved: print.to_string(),
            revision,
        })
    }

    /// Replaces the journal by a fresh one based on a design with fingerprint
    /// `print` at `revision` (after that design was written).
    pub fn reset(&mut self, print: &str, revision: u64) -> Result<(), ServeError> {
        *self = Journal::create(&self.path, print, revision)?;
        Ok(())
    }

    /// The journal file.
    pub fn path(&self) -> &Path {
        &self.path
    }

    /// Appends one line and flushes it (and every edit line before it).
    fn write_line(&mut self, line: &Line) -> std::io::Result<()> {
        self.write(line)?;
        self.file.sync_data()?;
        self.flush.all_durable();
        Ok(())
    }

    /// Appends one line, not flushed. On failure the file is cut back to where
    /// it was, so a half-written line never sits in front of the next one.
    fn write(&mut self, line: &Line) -> std::io::Result<()> {
        let mut bytes = serde_json::to_vec(line)?;
        bytes.push(b'\n');
        let before = self.file.metadata()?.len();
        let written = self.file.write_all(&bytes);
        if written.is_err() {
            // Best effort: if even this fails, replay drops a torn last line.
            let _ = self.file.set_len(before);
        }
        written
    }
}

/// What reading a journal's bytes gave: the replay and how many bytes of the
/// file are intact (the rest is cut off).
struct Recovered {
    replay: Replay,
    keep: usize,
}

/// A line of the journal that is not replayed, and why.
#[derive(Clone, Debug, PartialEq)]
pub struct Dropped {
    /// Its line number, from 1.
    pub line: usize,
    /// Why it is not replayed.
    pub reason: String,
    /// Whether it may have been acknowledged (a whole line; a last line without
    /// its newline never was). The journal is then kept as `<journal>.damaged`.
    pub acknowledged: bool,
}

impl std::fmt::Display for Dropped {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "line {}: {}", self.line, self.reason)
    }
}

/// Reads a journal: what to replay over a design file with fingerprint `print`.
///
/// Every intact line is recovered: blank lines are skipped; a last line without
/// its newline (never acknowledged) is dropped; the first line that is not a
/// journal line, is not UTF-8, or whose revision does not follow the one before
/// (backwards, repeated or jumping) ends the replay there, and it and every
/// line after it are dropped — each one listed in [`Replay::dropped`] with why.
fn read_lines(path: &Path, bytes: &[u8], print: &str) -> Result<Recovered, ServeError> {
    let mut parsed: Vec<(usize, Line)> = Vec::new();
    let mut dropped = Vec::new();
    let mut keep = 0;
    let mut start = 0;
    let mut number = 0;
    let mut damaged = false;
    while start < bytes.len() {
        number += 1;
        let (raw, end, whole) = match bytes[start..].iter().position(|&b| b == b'\n') {
            Some(k) => (&bytes[start..start + k], start + k + 1, true),
            None => (&bytes[start..], bytes.len(), false),
        };
        start = end;
        if damaged {
            dropped.push(Dropped {
                line: number,
                reason: "follows a damaged line".into(),
                acknowledged: whole,
            });
            continue;
        }
        if !whole {
            dropped.push(Dropped {
                line: number,
                reason: format!(
                    "the last line was cut off before its end ({} bytes, no newline): \
                     its edit was never acknowledged",
                    raw.len()
                ),
                acknowledged: false,
            });
            continue;
        }
        if raw.iter().all(u8::is_ascii_whitespace) {
            keep = end;
            continue;
        }
        let line = std::str::from_utf8(raw)
            .map_err(|e| format!("not UTF-8 text ({e})"))
            .and_then(|text| {
                serde_json::from_str::<Line>(text).map_err(|e| format!("not a journal line: {e}"))
            });
        let line = match (line, parsed.last()) {
            (Ok(line), Some((_, previous))) => {
                let expected = previous.revision();
                match line {
                    Line::Edit { revision, .. } if revision != expected + 1 => Err(format!(
                        "revision {revision} does not follow revision {expected} \
                         (expected {})",
                        expected + 1
                    )),
                    Line::Saved { revision, .. } if revision != expected => Err(format!(
                        "a save marker of revision {revision} after revision {expected}"
                    )),
                    Line::Header { .. } => Err("a header in the middle".into()),
                    line => Ok(line),
                }
            }
            (line, _) => line,
        };
        match line {
            Ok(line) => {
                parsed.push((number, line));
                keep = end;
            }
            Err(reason) if parsed.is_empty() => {
                return Err(journal_error(
                    path,
                    format!("line {number}: expected a {JOURNAL_FORMAT} header: {reason}"),
                ));
            }
            Err(reason) => {
                damaged = true;
                dropped.push(Dropped {
                    line: number,
                    reason,
                    acknowledged: true,
                });
            }
        }
    }
    let (base, base_revision) = match parsed.first() {
        Some((
            _,
            Line::Header {
                journal,
                base,
                revision,
            },
        )) if journal == JOURNAL_FORMAT => (base.clone(), *revision),
        _ => {
            return Err(journal_error(
                path,
                format!("line 1: expected a {JOURNAL_FORMAT} header"),
            ));
        }
    };
    // The last point (header or save marker) whose design is the file's.
    let mut from = None;
    if base == print {
        from = Some((0, base_revision));
    }
    for (k, (_, line)) in parsed.iter().enumerate().skip(1) {
        if let Line::Saved { saved, revision } = line
            && saved == print
        {
            from = Some((k, *revision));
        }
    }
    let Some((from, base_revision)) = from else {
        return Err(journal_error(
            path,
            "the design file was changed outside the server since this journal was \
             written (it matches neither the journal's base nor a save); move the \
             journal aside to start from the file as it is, or restore the file"
                .into(),
        ));
    };
    let edits = parsed
        .into_iter()
        .skip(from + 1)
        .filter_map(|(_, line)| match line {
            Line::Edit { revision, patch } => Some(JournalEntry { revision, patch }),
            _ => None,
        })
        .collect();
    Ok(Recovered {
        replay: Replay {
            base_revision,
            edits,
            dropped,
        },
        keep,
    })
}

impl Line {
    /// The revision the design has after this line.
    fn revision(&self) -> u64 {
        match self {
            Line::Header { revision, .. }
            | Line::Edit { revision, .. }
            | Line::Saved { revision, .. } => *revision,
        }
    }
}

/// Writes `bytes` to `path` so that a crash leaves either the old or the new file:
/// temp file beside it, `fsync`, rename, `fsync` of the folder.
pub fn write_atomically(path: &Path, bytes: &[u8]) -> std::io::Result<()> {
    let mut name = path.file_name().unwrap_or_default().to_os_string();
    name.push(".tmp");
    let tmp = path.with_file_name(name);
    let written = File::create(&tmp).and_then(|mut file| {
        // The new file keeps the old one's permissions.
        if let Ok(meta) = std::fs::metadata(path) {
            file.set_permissions(meta.permissions())?;
        }
        file.write_all(bytes)?;
        file.sync_all()?;
        drop(file);
        std::fs::rename(&tmp, path)
    });
    if let Err(e) = written {
        // No half-written temp file is left behind.
        let _ = std::fs::remove_file(&tmp);
        return Err(e);
    }
    let folder = match path.parent() {
        Some(p) if !p.as_os_str().is_empty() => p,
        _ => Path::new("."),
    };
    // Directories can be opened read-only and synced on Unix; elsewhere this is
    // best effort.
    if let Ok(dir) = File::open(folder) {
        let _ = dir.sync_all();
    }
    Ok(())
}

fn journal_error(path: &Path, message: String) -> ServeError {
    ServeError::Journal {
        path: path.display().to_string(),
        message,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use serde_json::json;

    /// A design file in a fresh folder, removed with the folder when the
    /// returned guard is dropped.
    fn temp_design(name: &str, text: &str) -> (tempfile::TempDir, PathBuf) {
        let dir = tempfile::Builder::new()
            .prefix(&format!("vesselcad-journal-{name}-"))
            .tempdir()
            .unwrap();
        let path = dir.path().join("d.json");
        std::fs::write(&path, text).unwrap();
        (dir, path)
    }

    #[test]
    fn replays_appended_edits_and_drops_a_torn_tail() {
        let (_dir, design) = temp_design("torn", "{}");
        let (mut j, replay) = Journal::open(&design, b"{}").unwrap();
        assert!(replay.edits.is_empty());
        j.append(1, &json!([{"op": "add", "path": "/a", "value": 1}]))
            .unwrap()
            .wait()
            .unwrap();
        j.append(2, &json!([])).unwrap().wait().unwrap();
        drop(j);
        let mut f = OpenOptions::new()
            .append(true)
            .open(journal_path(&design))
            .unwrap();
        f.write_all(b"{\"revision\":3,\"pat").unwrap();
        drop(f);
        let (mut j, replay) = Journal::open(&design, b"{}").unwrap();
        assert_eq!(
            replay.edits.iter().map(|e| e.revision).collect::<Vec<_>>(),
            [1, 2]
        );
        j.append(3, &json!([])).unwrap().wait().unwrap();
        drop(j);
        let (_, replay) = Journal::open(&design, b"{}").unwrap();
        assert_eq!(replay.edits.len(), 3);
    }

    #[test]
    fn a_save_marker_matching_the_file_skips_what_it_saved() {
        let (_dir, design) = temp_design("saved", "{}");
        let (mut j, _) = Journal::open(&design, b"{}").unwrap();
        j.append(1, &json!([])).unwrap().wait().unwrap();
        j.mark_saved(&fingerprint(b"{\"a\":1}"), 1).unwrap();
        j.append(2, &json!([])).unwrap().wait().unwrap();
        drop(j);
        // Crash after the marker, before the design was renamed: replay all.
        let (_, replay) = Journal::open(&design, b"{}").unwrap();
        assert_eq!((replay.base_revision, replay.edits.len()), (0, 2));
        // Crash after the rename, before the reset: replay what followed the marker.
        let (_, replay) = Journal::open(&design, b"{\"a\":1}").unwrap();
        assert_eq!((replay.base_revision, replay.edits.len()), (1, 1));
        // Changed by hand: refused.
        let err = Journal::open(&design, b"{\"b\":2}").unwrap_err();
        assert!(
            err.to_string().contains("changed outside the server"),
            "{err}"
        );
    }

    /// A journal of `design` (file `{}`) with these lines after its header.
    fn journal_with(name: &str, lines: &[u8]) -> (tempfile::TempDir, PathBuf) {
        let (dir, design) = temp_design(name, "{}");
        let (mut j, _) = Journal::open(&design, b"{}").unwrap();
        j.append(1, &json!([])).unwrap().wait().unwrap();
        drop(j);
        let mut f = OpenOptions::new()
            .append(true)
            .open(journal_path(&design))
            .unwrap();
        f.write_all(lines).unwrap();
        (dir, design)
    }

    fn revisions(replay: &Replay) -> Vec<u64> {
        replay.edits.iter().map(|e| e.revision).collect()
    }

    #[test]
    fn a_torn_multibyte_tail_and_a_blank_line_do_not_stop_the_start() {
        // "é" is C3 A9: cut after its first byte.
        let (_dir, design) = journal_with(
            "multibyte",
            b"{\"revision\":2,\"patch\":[]}\n\n{\"revision\":3,\"patch\":[{\"op\":\"add\",\"path\":\"/a\",\"value\":\"\xC3",
        );
        let (mut j, replay) = Journal::open(&design, b"{}").unwrap();
        assert_eq!(revisions(&replay), [1, 2]);
        assert_eq!(replay.dropped.len(), 1, "{:?}", replay.dropped);
        assert_eq!(replay.dropped[0].line, 5);
        assert!(!replay.dropped[0].acknowledged);
        assert!(
            replay.dropped[0].reason.contains("cut off"),
            "{:?}",
            replay.dropped
        );
        // The next edit starts a line of its own and is replayed.
        j.append(3, &json!([])).unwrap().wait().unwrap();
        drop(j);
        let (_, replay) = Journal::open(&design, b"{}").unwrap();
        assert_eq!(revisions(&replay), [1, 2, 3]);
        assert!(replay.dropped.is_empty(), "{:?}", replay.dropped);
    }

    #[test]
    fn revisions_out_of_sequence_end_the_replay_and_are_named() {
        for (name, lines, reason) in [
            (
                "backwards",
                &b"{\"revision\":2,\"patch\":[]}\n{\"revision\":1,\"patch\":[]}\n"[..],
                "revision 1 does not follow revision 2",
            ),
            (
                "repeated",
                b"{\"revision\":2,\"patch\":[]}\n{\"revision\":2,\"patch\":[]}\n",
                "revision 2 does not follow revision 2",
            ),
            (
                "jump",
                b"{\"revision\":2,\"patch\":[]}\n{\"revision\":5,\"patch\":[]}\n",
                "revision 5 does not follow revision 2",
            ),
            (
                "garbage",
                b"{\"revision\":2,\"patch\":[]}\n{\"revis\n",
                "not a journal line",
            ),
        ] {
            let (_dir, design) = journal_with(name, lines);
            let (_, replay) = Journal::open(&design, b"{}").unwrap();
            assert_eq!(revisions(&replay), [1, 2], "{name}");
            assert_eq!(replay.dropped.len(), 1, "{name}: {:?}", replay.dropped);
            let dropped = &replay.dropped[0];
            assert_eq!(dropped.line, 4, "{name}");
            assert!(dropped.acknowledged, "{name}");
            assert!(dropped.reason.contains(reason), "{name}: {dropped}");
            // The whole journal is kept aside; the journal itself is cut back to
            // its last intact line, so a restart drops nothing more.
            let mut aside = journal_path(&design).into_os_string();
            aside.push(".damaged");
            assert!(std::fs::read(&aside).unwrap().ends_with(lines), "{name}");
            let (_, replay) = Journal::open(&design, b"{}").unwrap();
            assert_eq!(
                (revisions(&replay), replay.dropped.len()),
                (vec![1, 2], 0),
                "{name}"
            );
        }
    }
}
