//! A patch: one exact NURBS surface of a part, with its name and analytic form.

use crate::nurbs::NurbsSurface;

use super::Analytic;

/// One surface patch of a part in the part's local frame.
#[derive(Clone, Debug, PartialEq)]
pub struct Patch {
    /// Stable name within the part, e.g. `"crown"`, `"knuckle"`, `"straight flange"`.
    pub name: &'static str,
    /// The exact surface; its outward normal is `S_u × S_v`.
    pub surface: NurbsSurface,
    /// The analytic surface the patch lies on.
    pub analytic: Analytic,
}

impl Patch {
    /// A named patch.
    pub fn new(name: &'static str, surface: NurbsSurface, analytic: Analytic) -> Self {
        Self {
            name,
            surface,
            analytic,
        }
    }
}
