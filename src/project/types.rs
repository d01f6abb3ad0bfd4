//! The shared vocabulary of views: which view, how the vessel frame maps onto it,
//! and the classified polylines each entity contributes. Built by the Project stage,
//! read by the drawing sheet and its writers (SVG, DXF).

use std::sync::Arc;

use glam::{DVec2, DVec3};

/// Which view of a vessel.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum ViewKind {
    /// Front elevation: vertical vessels seen from the south (east to the right);
    /// horizontal ones across the axis, the axis left to right.
    Front,
    /// Plan, looking down, the front side at the bottom (third-angle). For a
    /// vertical vessel north is up on the sheet; the sheet's north arrow shows it.
    Top,
    /// Side (end) elevation seen from the front view's right (third-angle).
    Side,
    /// Isometric, from front-right-above.
    Iso,
}

impl ViewKind {
    /// Every view, in sheet order.
    pub const ALL: [ViewKind; 4] = [
        ViewKind::Front,
        ViewKind::Top,
        ViewKind::Side,
        ViewKind::Iso,
    ];
}

/// How a line is drawn.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum LineKind {
    /// Visible outline, silhouette, boundary or seam edge: continuous, thick.
    Visible,
    /// Hidden edge: dashed, thin.
    Hidden,
    /// Centreline: chain (long dash, short dash), thin.
    Centre,
}

/// An orthographic projection of the vessel frame (mm) onto a view plane (mm,
/// model scale; the sheet applies the drawing scale): `right` and `up` are unit
/// vectors in the vessel frame, `toward_viewer` = `right × up`. A point's view
/// coordinates are `(p·right, p·up)`; larger `p·toward_viewer` is nearer the viewer.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Projection {
    /// The view's kind.
    pub kind: ViewKind,
    /// Unit vector (vessel frame) drawn to the right on the sheet.
    pub right: DVec3,
    /// Unit vector (vessel frame) drawn upward on the sheet.
    pub up: DVec3,
    /// Unit vector (vessel frame) pointing from the vessel toward the viewer.
    pub toward_viewer: DVec3,
}

impl Projection {
    /// View coordinates of a vessel-frame point, mm.
    pub fn project(&self, p: DVec3) -> DVec2 {
        DVec2::new(p.dot(self.right), p.dot(self.up))
    }

    /// Depth of a vessel-frame point: larger is nearer the viewer.
    pub fn depth(&self, p: DVec3) -> f64 {
        p.dot(self.toward_viewer)
    }
}

/// A polyline of one line kind, in view coordinates (mm, model scale).
#[derive(Clone, Debug, PartialEq)]
pub struct ViewLine {
    /// Visible, hidden or centre.
    pub kind: LineKind,
    /// The vertices, at least two.
    pub points: Vec<DVec2>,
}

/// What one entity (part or nozzle, by stable id `tag/id`) contributes to one view.
#[derive(Clone, Debug, PartialEq)]
pub struct EntityView {
    /// Stable id, `tag/id`.
    pub id: String,
    /// Its lines.
    pub lines: Vec<ViewLine>,
}

/// One view of one vessel: its projection and every entity's lines.
#[derive(Clone, Debug)]
pub struct View {
    /// How the vessel frame maps onto this view.
    pub projection: Projection,
    /// Per-entity lines, parts then nozzles in design order (shared with the cache).
    pub entities: Vec<Arc<EntityView>>,
}

impl View {
    /// Bounding box of every line in view coordinates, `None` when empty.
    pub fn bounds(&self) -> Option<(DVec2, DVec2)> {
        let mut it = self
            .entities
            .iter()
            .flat_map(|e| e.lines.iter())
            .flat_map(|l| l.points.iter().copied());
        let first = it.next()?;
        Some(it.fold((first, first), |(lo, hi), p| (lo.min(p), hi.max(p))))
    }
}
