//! One scan point as the fit sees it: the parameters of its projection on the
//! design patch and its offset from there. `inspect` makes them from the
//! projected cloud; `cells` sorts them by knot cell and `fit` solves for the
//! displacement surface through them.

use glam::DVec3;

/// One point to fit: its projection's parameters and its offset from there.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Sample {
    /// u of the projection.
    pub u: f64,
    /// v of the projection.
    pub v: f64,
    /// Point − S(u, v), local frame, mm.
    pub offset: DVec3,
    /// Design unit normal at (u, v), local frame.
    pub normal: DVec3,
}
