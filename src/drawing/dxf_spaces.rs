//! Where a sheet's items go in the DXF: paper space (border and tables) or model
//! space at 1:1 (the views, and the enlarged plan beside them), each with the
//! map from sheet millimetres; and the line weight of each layer. Shared by the
//! writer ([`super::dxf`]) and its fix-up pass ([`super::dxf_fixup`]).

use dxf::Point;
use glam::DVec2;

use super::sheet::{Layer, Sheet};

/// Line weight of a layer, hundredths of a mm (the SVG's stroke widths rounded
/// to the standard DXF weights).
pub fn line_weight(layer: Layer) -> i16 {
    match layer {
        Layer::Border | Layer::Outline => 50,
        Layer::Hidden | Layer::Text => 25,
        Layer::Centre | Layer::Dimension => 18,
    }
}

/// Where an item goes and how its sheet coordinates map there.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Space {
    /// Paper space (border, tables) or model space.
    pub paper: bool,
    /// Model (or paper) mm per sheet mm.
    pub factor: f64,
    /// Model point of the sheet origin.
    pub offset: DVec2,
}

impl Space {
    pub(super) fn map(&self, q: DVec2) -> DVec2 {
        self.offset + q * self.factor
    }

    pub(super) fn point(&self, q: DVec2) -> Point {
        let p = self.map(q);
        Point::new(p.x, p.y, 0.0)
    }
}

/// The spaces of a sheet: paper, the main model area, the enlarged plan, then
/// one per detail view (each at 1:1 in model space, in a row beyond the plan).
pub fn spaces(sheet: &Sheet) -> Vec<Space> {
    let paper = Space {
        paper: true,
        factor: 1.0,
        offset: DVec2::ZERO,
    };
    let main = Space {
        paper: false,
        factor: sheet.scale,
        offset: DVec2::ZERO,
    };
    // The plan at 1:1 beside the sheet's model extent, its region's centre at
    // the same height.
    let f = sheet.scale / sheet.factors[1];
    let c = 0.5 * (sheet.plan_region.min + sheet.plan_region.max);
    let size = sheet.size.dimensions();
    let target = DVec2::new(
        (size.x + 0.5 * sheet.plan_region.size().x) * sheet.scale,
        c.y * sheet.scale,
    );
    let plan = Space {
        paper: false,
        factor: f,
        offset: target - c * f,
    };
    let mut out = vec![paper, main, plan];
    // Details: each region's lower-left corner at the next free x.
    let mut x = (2.0 * size.x + sheet.plan_region.size().x) * sheet.scale;
    for d in &sheet.details {
        let origin = DVec2::new(x, d.region.min.y * d.scale);
        out.push(Space {
            paper: false,
            factor: d.scale,
            offset: origin - d.region.min * d.scale,
        });
        x += 1.25 * d.region.size().x * d.scale;
    }
    out
}
