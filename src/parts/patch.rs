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
    /// Which of several same-named patches this is: 0 for a patch whose name is unique
    /// in its part, else the 1-based number of the leg, lug… it belongs to.
    pub index: u32,
}

impl Patch {
    /// A named patch with index 0.
    pub fn new(name: &'static str, surface: NurbsSurface, analytic: Analytic) -> Self {
        Self {
            name,
            surface,
            analytic,
            index: 0,
        }
    }

    /// The same patch with `index` set (the 1-based number of its leg, lug…).
    pub fn with_index(mut self, index: u32) -> Self {
        self.index = index;
        self
    }
}
