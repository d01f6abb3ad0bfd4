//! The edit journal: every accepted edit, appended to a file beside the design and
//! flushed to disk before the edit is acknowledged, so nothing acknowledged is lost
//! if the server dies.
//!
//! Where it sits: [`super::session`] applies an edit to the model, appends it here
//! (`fsync`), and only then answers the editor and streams the delta. On start the
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

use serde::{Deserialize, Serialize};
use serde_json::Value;

use super::error::ServeError;

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
        let text = match std::fs::read(&path) {
            Ok(bytes) => String::from_utf8(bytes)
                .map_err(|_| journal_error(&path, "not UTF-8 text".into()))?,
            Err(e) if e.kind() == std::io::ErrorKind::NotFound => String::new(),
            Err(e) => return Err(journal_error(&path, e.to_string())),
        };
        // Complete lines only: the tail after the last newline was never acknowledged.
        let complete = text.rfind('\n').map_or(0, |k| k + 1);
        let lines: Vec<&str> = text[..complete].lines().collect();
        if lines.is_empty() {
            let journal = Journal::create(&path, &print, 0)?;
            return Ok((
                journal,
                Replay {
                    base_revision: 0,
                    edits: Vec::new(),
                },
            ));
        }
        let replay = read_lines(&path, &lines, &print)?;
        if complete < text.len() {
            // Drop the torn tail so new lines start on a line of their own.
            let file = OpenOptions::new()
                .write(true)
                .open(&path)
                .map_err(|e| journal_error(&path, e.to_string()))?;
            file.set_len(complete as u64)
                .and_then(|()| file.sync_all())
                .map_err(|e| journal_error(&path, e.to_string()))?;
        }
        let file = OpenOptions::new()
            .append(true)
            .open(&path)
            .map_err(|e| journal_error(&path, e.to_string()))?;
        Ok((Journal { path, file }, replay))
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
        Ok(Journal {
            path: path.to_path_buf(),
            file,
        })
    }

    /// Appends an accepted edit and flushes it to disk. Returns only once the
    /// edit is durable.
    pub fn append(&mut self, revision: u64, patch: &Value) -> std::io::Result<()> {
        self.write_line(&Line::Edit {
            revision,
            patch: patch.clone(),
        })
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

    /// Appends one line and flushes it. On failure the file is cut back to where
    /// it was, so a half-written line never sits in front of the next one.
    fn write_line(&mut self, line: &Line) -> std::io::Result<()> {
        let mut bytes = serde_json::to_vec(line)?;
        bytes.push(b'\n');
        let before = self.file.metadata()?.len();
        let written = self
            .file
            .write_all(&bytes)
            .and_then(|()| self.file.sync_data());
        if written.is_err() {
            // Best effort: if even this fails, replay drops a torn last line.
            let _ = self.file.set_len(before);
        }
        written
    }
}

/// Reads the complete lines of a journal: what to replay over a design file with
/// fingerprint `print`.
fn read_lines(path: &Path, lines: &[&str], print: &str) -> Result<Replay, ServeError> {
    let mut parsed = Vec::with_capacity(lines.len());
    for (k, line) in lines.iter().enumerate() {
        let line: Line = serde_json::from_str(line)
            .map_err(|e| journal_error(path, format!("line {}: not a journal line: {e}", k + 1)))?;
        parsed.push(line);
    }
    let (base, base_revision) = match parsed.first() {
        Some(Line::Header {
            journal,
            base,
            revision,
        }) if journal == JOURNAL_FORMAT => (base.clone(), *revision),
        _ => {
            return Err(journal_error(
                path,
                format!("line 1: expected a {JOURNAL_FORMAT} header"),
            ));
        }
    };
    // The last point (header or save marker) whose design is the file's.
    let mut start = None;
    if base == print {
        start = Some((0, base_revision));
    }
    for (k, line) in parsed.iter().enumerate().skip(1) {
        if let Line::Saved { saved, revision } = line
            && saved == print
        {
            start = Some((k, *revision));
        }
    }
    let Some((start, base_revision)) = start else {
        return Err(journal_error(
            path,
            "the design file was changed outside the server since this journal was \
             written (it matches neither the journal's base nor a save); move the \
             journal aside to start from the file as it is, or restore the file"
                .into(),
        ));
    };
    let mut edits = Vec::new();
    for (k, line) in parsed.into_iter().enumerate().skip(start + 1) {
        match line {
            Line::Edit { revision, patch } => edits.push(JournalEntry { revision, patch }),
            Line::Saved { .. } => {}
            Line::Header { .. } => {
                return Err(journal_error(
                    path,
                    format!("line {}: a header in the middle", k + 1),
                ));
            }
        }
    }
    Ok(Replay {
        base_revision,
        edits,
    })
}

/// Writes `bytes` to `path` so that a crash leaves either the old or the new file:
/// temp file beside it, `fsync`, rename, `fsync` of the folder.
pub fn write_atomically(path: &Path, bytes: &[u8]) -> std::io::Result<()> {
    let mut name = path.file_name().unwrap_or_default().to_os_string();
    name.push(".tmp");
    let tmp = path.with_file_name(name);
    let mut file = File::create(&tmp)?;
    file.write_all(bytes)?;
    file.sync_all()?;
    drop(file);
    std::fs::rename(&tmp, path)?;
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
            .unwrap();
        j.append(2, &json!([])).unwrap();
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
        j.append(3, &json!([])).unwrap();
        drop(j);
        let (_, replay) = Journal::open(&design, b"{}").unwrap();
        assert_eq!(replay.edits.len(), 3);
    }

    #[test]
    fn a_save_marker_matching_the_file_skips_what_it_saved() {
        let (_dir, design) = temp_design("saved", "{}");
        let (mut j, _) = Journal::open(&design, b"{}").unwrap();
        j.append(1, &json!([])).unwrap();
        j.mark_saved(&fingerprint(b"{\"a\":1}"), 1).unwrap();
        j.append(2, &json!([])).unwrap();
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
}
