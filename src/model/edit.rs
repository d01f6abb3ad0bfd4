//! Edits: the changes a user (file, API call, live session) can make to a model.
//! Each is checked as one transaction; a [`Edit::Batch`] is all or nothing.

use crate::design::{
    Design, NoteDesign, NozzleDesign, OperatingDesign, PartDesign, Placement, VesselDesign,
};

/// One change to the model.
#[derive(Clone, Debug, PartialEq)]
pub enum Edit {
    /// Replace the whole design; only vessels that differ are touched.
    ReplaceDesign(Design),
    /// Add a vessel, or replace the one with the same tag.
    SetVessel(VesselDesign),
    /// Remove a vessel.
    RemoveVessel {
        /// Its tag.
        tag: String,
    },
    /// Move a vessel (a frame change: no patch is rebuilt).
    MoveVessel {
        /// Its tag.
        tag: String,
        /// The new placement.
        placement: Placement,
    },
    /// Replace the part with the same id.
    SetPart {
        /// Vessel tag.
        vessel: String,
        /// The part's new parameters.
        part: PartDesign,
    },
    /// Insert a new part at `index` in the vessel's part list.
    InsertPart {
        /// Vessel tag.
        vessel: String,
        /// Position in the part list (clamped to its length).
        index: usize,
        /// The part.
        part: PartDesign,
    },
    /// Remove a part (and with it the nozzles it hosts must go too, or the edit
    /// is refused).
    RemovePart {
        /// Vessel tag.
        vessel: String,
        /// Part id.
        id: String,
    },
    /// Add a nozzle, or replace the one with the same mark.
    SetNozzle {
        /// Vessel tag.
        vessel: String,
        /// The nozzle.
        nozzle: NozzleDesign,
    },
    /// Remove a nozzle.
    RemoveNozzle {
        /// Vessel tag.
        vessel: String,
        /// Its mark.
        mark: String,
    },
    /// Add a note, or replace the one with the same id.
    SetNote {
        /// Vessel tag.
        vessel: String,
        /// The note.
        note: NoteDesign,
    },
    /// Remove a note.
    RemoveNote {
        /// Vessel tag.
        vessel: String,
        /// Its id.
        id: String,
    },
    /// Set a vessel's operating state (liquid level and density; `None`: empty).
    /// Only its operating figures are recomputed.
    SetOperating {
        /// Vessel tag.
        vessel: String,
        /// The new operating state.
        operating: Option<OperatingDesign>,
    },
    /// Several edits applied together: all or none.
    Batch(Vec<Edit>),
}

impl Edit {
    /// The tag of the one existing vessel the edit changes, for the edits that
    /// name one (a move, a part, nozzle, note or operating edit); `None` for a
    /// whole design, a vessel set or removed, and a batch.
    pub fn vessel_tag(&self) -> Option<&str> {
        match self {
            Edit::MoveVessel { tag: vessel, .. }
            | Edit::SetPart { vessel, .. }
            | Edit::InsertPart { vessel, .. }
            | Edit::RemovePart { vessel, .. }
            | Edit::SetNozzle { vessel, .. }
            | Edit::RemoveNozzle { vessel, .. }
            | Edit::SetNote { vessel, .. }
            | Edit::RemoveNote { vessel, .. }
            | Edit::SetOperating { vessel, .. } => Some(vessel),
            Edit::ReplaceDesign(_)
            | Edit::SetVessel(_)
            | Edit::RemoveVessel { .. }
            | Edit::Batch(_) => None,
        }
    }
}
