//! Automatic dimensions of the front elevation: overall tangent-to-tangent length,
//! overall length or height over heads and supports, head depths, the tangent
//! lines and the base marked, the OD of each course, skirt height, saddle
//! spacing and the centreline's height above the saddles' base, nozzle projections (where
//! the nozzle lies in the view plane, so the length is true) and nozzle elevations
//! or positions as ordinate callouts.
//!
//! Dimensions are chosen from the model (`plan`) in view coordinates, then placed
//! (`place`) in tracks outside the view's lines on the side nearest their features:
//! ordinates first, then linear dimensions packed first-fit into parallel tracks so
//! that no two dimension lines or texts in a track overlap. Tracks are spaced by
//! more than the lettering, so texts of different tracks do not overlap either, and
//! everything lies outside the view's box; the layout reserves the paper margins
//! this needs (`margins`).
//!
//! [`plan`] chooses the dimensions (`plan.rs`), [`place()`] lays them out in
//! tracks and [`margins`] reserves the paper they need (`place.rs`).

mod place;
mod plan;

pub use place::{margins, place};
pub use plan::{plan, plan_side};

use glam::DVec2;

/// Which side of the view a dimension goes.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum DimSide {
    /// Left of the view, measuring vertically.
    Left,
    /// Right of the view, measuring vertically.
    Right,
    /// Below the view, measuring horizontally.
    Below,
    /// Above the view, measuring horizontally.
    Above,
}

impl DimSide {
    const ALL: [DimSide; 4] = [
        DimSide::Left,
        DimSide::Right,
        DimSide::Below,
        DimSide::Above,
    ];

    fn vertical(self) -> bool {
        matches!(self, DimSide::Left | DimSide::Right)
    }

    /// Unit vector pointing away from the view.
    fn outward(self) -> DVec2 {
        match self {
            DimSide::Left => -DVec2::X,
            DimSide::Right => DVec2::X,
            DimSide::Below => -DVec2::Y,
            DimSide::Above => DVec2::Y,
        }
    }
}

/// A linear dimension between two feature points (view coordinates, model mm).
#[derive(Clone, Debug, PartialEq)]
pub struct LinearDim {
    /// Side it is placed on.
    pub side: DimSide,
    /// First feature point.
    pub a: DVec2,
    /// Second feature point.
    pub b: DVec2,
    /// Its text.
    pub text: String,
}

/// An ordinate callout: a feature point and its label.
#[derive(Clone, Debug, PartialEq)]
pub struct Ordinate {
    /// Side it is placed on.
    pub side: DimSide,
    /// Feature point (view coordinates, model mm).
    pub at: DVec2,
    /// Label, e.g. `"N1 EL 10000"`.
    pub text: String,
    /// The elevation or position it labels, mm from the datum.
    pub value: f64,
}

/// The dimensions of a front view.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Dimensions {
    /// Linear dimensions.
    pub linear: Vec<LinearDim>,
    /// Ordinate callouts.
    pub ordinates: Vec<Ordinate>,
}

/// A length for a dimension text: whole mm, or one decimal when not whole.
pub fn format_mm(v: f64) -> String {
    if (v - v.round()).abs() < 0.05 {
        format!("{:.0}", v.round())
    } else {
        format!("{v:.1}")
    }
}
