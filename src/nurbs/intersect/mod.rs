//! Neck–host intersection: the closed curve where a nozzle neck meets its host
//! surface, the trim loop of every nozzle opening.
//!
//! Input: a neck-like surface (closed in u, straight generators along v: a nozzle
//! neck, or a reinforcing pad's outside cylinder) and a host patch, both in one
//! frame. Each generator at neck angle u crosses the host once; `generator` finds
//! that point by Newton's method on N(u, s) = H(a, b), `march` follows it once
//! around the neck and samples it to a chordal tolerance. Output: an
//! [`IntersectionLoop`] with the points and their parameters on both surfaces, for
//! trimming both.
//!
//! `crossing` finds where the loop crosses a host isoline (a seam), for the
//! samples an opening needs exactly there.
//!
//! `pair` holds what both share: the two surfaces with their domains (the neck's
//! generators extended beyond its ends, the host wrapped across its seam).

mod crossing;
mod generator;
mod march;
mod pair;

pub use crossing::{Crossing, HostIsoline, LoopSample, loop_crossing};
pub use generator::{GeneratorHit, intersect_generator};
pub use march::{IntersectionLoop, MAX_TURNING_ANGLE, neck_host_intersection};
