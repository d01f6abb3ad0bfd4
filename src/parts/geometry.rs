//! The resolved parameters of any part, as the part builders take them: what the
//! rules ([`crate::constraints`]) produce and the operating figures, exports and
//! drawings read.

use super::heads::Head;
use super::{Boot, Legs, Lugs, PartError, Patch, Reducer, Saddle, Shell, Skirt};

/// Resolved parameters of one part (inherited diameters filled in).
#[derive(Clone, Debug, PartialEq)]
pub enum PartGeometry {
    /// Shell course.
    Shell(Shell),
    /// Head.
    Head(Head),
    /// Conical reducer.
    Reducer(Reducer),
    /// Skirt.
    Skirt(Skirt),
    /// Saddle.
    Saddle(Saddle),
    /// Pipe legs.
    Legs(Legs),
    /// Lugs.
    Lugs(Lugs),
    /// Boot.
    Boot(Boot),
}

impl PartGeometry {
    /// The exact patches of the part in its local frame.
    pub fn patches(&self) -> Result<Vec<Patch>, PartError> {
        match self {
            PartGeometry::Shell(p) => p.patches(),
            PartGeometry::Head(p) => p.patches(),
            PartGeometry::Reducer(p) => p.patches(),
            PartGeometry::Skirt(p) => p.patches(),
            PartGeometry::Saddle(p) => p.patches(),
            PartGeometry::Legs(p) => p.patches(),
            PartGeometry::Lugs(p) => p.patches(),
            PartGeometry::Boot(p) => p.patches(),
        }
    }

    /// The kind's name, as in design files.
    pub fn kind(&self) -> &'static str {
        match self {
            PartGeometry::Shell(_) => "shell",
            PartGeometry::Head(_) => "head",
            PartGeometry::Reducer(_) => "reducer",
            PartGeometry::Skirt(_) => "skirt",
            PartGeometry::Saddle(_) => "saddle",
            PartGeometry::Legs(_) => "legs",
            PartGeometry::Lugs(_) => "lugs",
            PartGeometry::Boot(_) => "boot",
        }
    }
}
