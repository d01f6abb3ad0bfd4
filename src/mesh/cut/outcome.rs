//! What cutting an opening gives: the [`Cut`] of the host (the loops and how each
//! host patch is trimmed) and the reinforcing pad's [`PadCut`]. A leaf of the
//! cut stage (beside `seams`' trims), so the marching (`opening`), the canonical
//! placements (`axial`) and the canonical neck (`reach`) share these types
//! without using each other.

use std::sync::Arc;

use super::seams::HostTrim;
use crate::nurbs::intersect::IntersectionLoop;
use crate::parts::Patch;

/// A nozzle's (or boot's) cut in its host, in the host part's frame.
#[derive(Clone, Debug, PartialEq)]
pub struct Cut {
    /// The host patches the opening cuts, by index, with how it trims each: one
    /// patch holding the whole loop ([`HostTrim::Hole`]), or the neighbouring
    /// patches whose seam the loop crosses ([`HostTrim::Notches`]).
    pub hosts: Vec<(usize, HostTrim)>,
    /// Where the neck meets the host. Its host (u, v) are those of the one host
    /// patch holding it; for an opening across a seam, those of the host patches
    /// joined in v (the notches carry each patch's own).
    pub neck: IntersectionLoop,
    /// Where the reinforcing pad's outside edge meets the host, if it has a pad.
    pub pad: Option<IntersectionLoop>,
}

/// A reinforcing pad's patch with the loops that trim it, in its own (u, v).
#[derive(Clone, Debug, PartialEq)]
pub struct PadCut {
    /// The pad's patch, in the nozzle's frame: a host surface (the host patch
    /// itself, or a straight course's canonical copy) moved there.
    pub patch: Patch,
    /// The pad's outer loop, host (u, v) on `patch`.
    pub outer: Arc<IntersectionLoop>,
    /// The neck's loop, host (u, v) on `patch`.
    pub inner: Arc<IntersectionLoop>,
}

/// Name of the reinforcing pad's patch.
pub const PAD_PATCH: &str = "reinforcing pad";
