//! Group commit for the journal: an edit's line is written under the session
//! lock, and flushed to disk (`fdatasync`) after the lock is let go, so the
//! next edit is staged while the disk works; one flush covers every line
//! written before it started, so editors waiting together share it.
//!
//! Where it sits: [`super::journal::Journal::append`] writes a line and hands
//! back a [`Pending`]; the edit route waits on it (without the lock) before it
//! answers the editor or streams the delta, so an edit is still acknowledged
//! and shown only once it is durable. A flush that fails stops the journal:
//! every edit waiting on it or on a later flush, and every later append, is
//! refused (the session must be restarted; its journal holds what reached the
//! disk, like after a crash).

use std::fs::File;
use std::sync::{Arc, Condvar, Mutex, MutexGuard};

/// The flushing state of one journal file.
#[derive(Debug)]
pub struct GroupFlush {
    file: File,
    state: Mutex<State>,
    flushed: Condvar,
}

#[derive(Debug, Default)]
struct State {
    /// Lines written so far.
    written: u64,
    /// Lines known to be on disk.
    durable: u64,
    /// A flush is under way.
    flushing: bool,
    /// Why a flush failed (the journal is stopped).
    failed: Option<String>,
}

/// A written line not yet known to be on disk.
#[derive(Clone, Debug)]
#[must_use = "an edit is durable only once its pending flush is waited for"]
pub struct Pending {
    flush: Arc<GroupFlush>,
    line: u64,
}

impl GroupFlush {
    /// The flushing state of `file` (a handle on the journal file).
    pub fn new(file: File) -> Arc<GroupFlush> {
        Arc::new(GroupFlush {
            file,
            state: Mutex::default(),
            flushed: Condvar::new(),
        })
    }

    fn lock(&self) -> MutexGuard<'_, State> {
        self.state.lock().unwrap_or_else(|p| p.into_inner())
    }

    /// Why the journal is stopped, if it is.
    pub fn failed(&self) -> Option<String> {
        self.lock().failed.clone()
    }

    /// Counts a line just written; it is durable once [`Pending::wait`] returns.
    pub fn written(self: &Arc<Self>) -> Pending {
        let mut state = self.lock();
        state.written += 1;
        Pending {
            flush: self.clone(),
            line: state.written,
        }
    }

    /// Every line written so far was flushed by the caller (a synchronous
    /// write): waiters return.
    pub fn all_durable(&self) {
        let mut state = self.lock();
        state.durable = state.written;
        self.flushed.notify_all();
    }
}

impl Pending {
    /// Returns once the line is on disk: flushes, or waits for the flush under
    /// way when it covers the line.
    ///
    /// # Errors
    ///
    /// The flush's error when it (or an earlier one) failed.
    pub fn wait(&self) -> Result<(), String> {
        let flush = &self.flush;
        let mut state = flush.lock();
        loop {
            if state.durable >= self.line {
                return Ok(());
            }
            if let Some(e) = &state.failed {
                return Err(e.clone());
            }
            if state.flushing {
                state = flush.flushed.wait(state).unwrap_or_else(|p| p.into_inner());
                continue;
            }
            state.flushing = true;
            let covers = state.written;
            drop(state);
            let result = flush.file.sync_data();
            state = flush.lock();
            state.flushing = false;
            match result {
                Ok(()) => state.durable = state.durable.max(covers),
                Err(e) => state.failed = Some(format!("flushing the journal failed: {e}")),
            }
            flush.flushed.notify_all();
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn flush() -> Arc<GroupFlush> {
        GroupFlush::new(tempfile::tempfile().unwrap())
    }

    #[test]
    fn one_flush_covers_every_line_written_before_it() {
        let flush = flush();
        let lines: Vec<Pending> = (0..5).map(|_| flush.written()).collect();
        lines[4].wait().unwrap();
        assert_eq!(flush.lock().durable, 5);
        // The others are durable without flushing again.
        for line in &lines {
            line.wait().unwrap();
        }
        let later = flush.written();
        assert_eq!(flush.lock().durable, 5);
        later.wait().unwrap();
        assert_eq!(flush.lock().durable, 6);
    }

    #[test]
    fn waiters_on_many_threads_all_return() {
        let flush = flush();
        let threads: Vec<_> = (0..16)
            .map(|_| {
                let line = flush.written();
                std::thread::spawn(move || line.wait())
            })
            .collect();
        for t in threads {
            t.join().unwrap().unwrap();
        }
        assert_eq!(flush.lock().durable, 16);
    }

    #[test]
    fn a_failed_flush_refuses_its_lines_and_the_later_ones() {
        let flush = flush();
        let durable = flush.written();
        durable.wait().unwrap();
        let line = flush.written();
        flush.lock().failed = Some("flushing the journal failed: disk gone".into());
        assert!(line.wait().unwrap_err().contains("disk gone"));
        assert!(flush.written().wait().is_err());
        // What was durable before stays durable.
        durable.wait().unwrap();
    }
}
