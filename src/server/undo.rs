//! Undo, redo, history and catching up, on top of [`Session`]: an undo or a redo
//! is a new revision whose design is an earlier one (history is never
//! rewritten), made durable like any edit. The undo and redo stacks hold, for
//! this server's last [`UNDO_DEPTH`](super::session::UNDO_DEPTH) edits, the
//! JSON Patch that takes each back (in memory: a restart
//! starts them empty; the store's history stays, and `store checkout` reaches
//! any revision). Catching up adopts the newest revision another server
//! committed to the same store.

use super::error::ApiError;
use super::session::{Accepted, Session, design_value, push_bounded};
use crate::design::to_canonical_json;
use crate::model::Edit;
use crate::store::Revision;

impl Session {
    /// Goes back to the design before this server's last edit not yet undone,
    /// as a new revision, durable once [`Accepted::wait_durable`] returns (as
    /// [`Session::apply_unflushed`]).
    ///
    /// # Errors
    ///
    /// [`ApiError::NothingTo`] with nothing to undo, and as
    /// [`Session::apply_patch`].
    pub fn undo(&mut self) -> Result<Accepted, ApiError> {
        let Some(patch) = self.undo.last() else {
            return Err(ApiError::NothingTo("undo"));
        };
        let body = serde_json::to_vec(patch).map_err(|e| ApiError::Malformed(e.to_string()))?;
        let (accepted, inverse) = self.apply_recorded(&body, "undo")?;
        self.undo.pop();
        push_bounded(&mut self.redo, inverse);
        Ok(accepted)
    }

    /// Redoes the last undo, as a new revision (durable once
    /// [`Accepted::wait_durable`] returns).
    ///
    /// # Errors
    ///
    /// [`ApiError::NothingTo`] with nothing to redo, and as
    /// [`Session::apply_patch`].
    pub fn redo(&mut self) -> Result<Accepted, ApiError> {
        let Some(patch) = self.redo.last() else {
            return Err(ApiError::NothingTo("redo"));
        };
        let body = serde_json::to_vec(patch).map_err(|e| ApiError::Malformed(e.to_string()))?;
        let (accepted, inverse) = self.apply_recorded(&body, "redo")?;
        self.redo.pop();
        push_bounded(&mut self.undo, inverse);
        Ok(accepted)
    }

    /// The revisions kept, oldest first.
    ///
    /// # Errors
    ///
    /// [`ApiError::NoHistory`] without a store, [`ApiError::Storage`] when it
    /// cannot be read.
    pub fn revisions(&mut self) -> Result<Vec<Revision>, ApiError> {
        match self.persistence.revisions() {
            None => Err(ApiError::NoHistory),
            Some(r) => r.map_err(ApiError::Storage),
        }
    }

    /// The canonical JSON of the design at `revision`.
    ///
    /// # Errors
    ///
    /// [`ApiError::NoHistory`] without a store (for another revision than the
    /// current), [`ApiError::BadQuery`] for a revision not kept.
    pub fn design_text_at(&mut self, revision: u64) -> Result<String, ApiError> {
        if revision == self.revision {
            return Ok(self.design_text());
        }
        match self.persistence.design_at(revision) {
            None => Err(ApiError::NoHistory),
            Some(Ok(d)) => Ok(to_canonical_json(&d)),
            Some(Err(e)) => Err(ApiError::BadQuery(e)),
        }
    }

    /// Adopts the newest revision another server committed, if there is one:
    /// the model takes its design (only what differs is rebuilt) and the
    /// answer is what viewers are sent.
    ///
    /// # Errors
    ///
    /// [`ApiError::Storage`] when the store cannot be read,
    /// [`ApiError::Refused`] if the model cannot build it.
    pub fn catch_up(&mut self) -> Result<Option<Accepted>, ApiError> {
        let Some((revision, design)) = self
            .persistence
            .newer_than(self.revision)
            .map_err(ApiError::Storage)?
        else {
            return Ok(None);
        };
        let work = self
            .model
            .edit(Edit::ReplaceDesign(design))
            .map_err(ApiError::Refused)?;
        let next = design_value(&self.model.design());
        let touched = super::scoped::differing_vessels(&self.design, &next);
        self.design = next;
        self.revision = revision;
        // Another server's edits are not this server's to undo.
        self.undo.clear();
        self.redo.clear();
        Ok(Some(self.accepted(work, touched)))
    }
}
