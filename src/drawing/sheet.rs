//! The sheet as a display list in paper millimetres (origin at the lower-left
//! corner, y up), with the options that choose its size and what it shows.
//!
//! Composition (`compose`) fills a [`Sheet`]; the writers (`svg`, `dxf`) only
//! translate its items, so both outputs always show the same drawing.

use glam::DVec2;

use crate::project::ViewKind;

/// Standard sheet sizes, landscape.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum SheetSize {
    /// ANSI B, 17 × 11 in.
    AnsiB,
    /// ANSI D, 34 × 22 in.
    AnsiD,
    /// ISO A3, 420 × 297 mm.
    IsoA3,
    /// ISO A1, 841 × 594 mm.
    IsoA1,
}

impl SheetSize {
    /// Every size.
    pub const ALL: [SheetSize; 4] = [
        SheetSize::AnsiB,
        SheetSize::AnsiD,
        SheetSize::IsoA3,
        SheetSize::IsoA1,
    ];

    /// Width and height, mm.
    pub fn dimensions(self) -> DVec2 {
        match self {
            SheetSize::AnsiB => DVec2::new(431.8, 279.4),
            SheetSize::AnsiD => DVec2::new(863.6, 558.8),
            SheetSize::IsoA3 => DVec2::new(420.0, 297.0),
            SheetSize::IsoA1 => DVec2::new(841.0, 594.0),
        }
    }

    /// The name written in the title block.
    pub fn name(self) -> &'static str {
        match self {
            SheetSize::AnsiB => "ANSI B",
            SheetSize::AnsiD => "ANSI D",
            SheetSize::IsoA3 => "ISO A3",
            SheetSize::IsoA1 => "ISO A1",
        }
    }

    /// Lettering height for this size, mm.
    pub fn text_height(self) -> f64 {
        match self {
            SheetSize::AnsiB | SheetSize::IsoA3 => 2.0,
            SheetSize::AnsiD | SheetSize::IsoA1 => 3.0,
        }
    }
}

/// Whether a view shows its hidden lines.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum HiddenLines {
    /// Drawn dashed (the default).
    #[default]
    Dashed,
    /// Left out.
    Omitted,
}

/// What to draw and on what.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct SheetOptions {
    /// Sheet size.
    pub size: SheetSize,
    /// Hidden lines per view, in [`ViewKind::ALL`](crate::project::ViewKind::ALL) order.
    pub hidden: [HiddenLines; 4],
}

impl Default for SheetOptions {
    fn default() -> Self {
        Self {
            size: SheetSize::AnsiD,
            hidden: [HiddenLines::Dashed; 4],
        }
    }
}

impl SheetOptions {
    /// The default options on sheet `size`.
    pub fn sized(size: SheetSize) -> Self {
        Self {
            size,
            ..Self::default()
        }
    }

    /// The same options with hidden lines of `view` set to `hidden`.
    pub fn with_hidden(mut self, view: ViewKind, hidden: HiddenLines) -> Self {
        if let Some(k) = ViewKind::ALL.iter().position(|&v| v == view) {
            self.hidden[k] = hidden;
        }
        self
    }
}

/// Which layer an item is on (DXF layer, SVG class).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Layer {
    /// Sheet border, title block and table rules.
    Border,
    /// Visible outlines.
    Outline,
    /// Hidden lines.
    Hidden,
    /// Centrelines.
    Centre,
    /// Dimension, extension and leader lines and arrowheads.
    Dimension,
    /// Lettering.
    Text,
}

impl Layer {
    /// Every layer, in drawing order.
    pub const ALL: [Layer; 6] = [
        Layer::Border,
        Layer::Hidden,
        Layer::Centre,
        Layer::Outline,
        Layer::Dimension,
        Layer::Text,
    ];

    /// The DXF layer name and SVG class.
    pub fn name(self) -> &'static str {
        match self {
            Layer::Border => "BORDER",
            Layer::Outline => "OUTLINE",
            Layer::Hidden => "HIDDEN",
            Layer::Centre => "CENTER",
            Layer::Dimension => "DIMENSIONS",
            Layer::Text => "TEXT",
        }
    }
}

/// Horizontal alignment of a text about its insertion point.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Align {
    /// The point is at the start of the text.
    Start,
    /// The point is at the middle.
    Middle,
    /// The point is at the end.
    End,
}

/// A rectangle on the sheet, mm.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Rect {
    /// Lower-left corner.
    pub min: DVec2,
    /// Upper-right corner.
    pub max: DVec2,
}

impl Rect {
    /// The rectangle spanned by two corners.
    pub fn new(a: DVec2, b: DVec2) -> Self {
        Self {
            min: a.min(b),
            max: a.max(b),
        }
    }

    /// Width and height.
    pub fn size(&self) -> DVec2 {
        self.max - self.min
    }

    /// Whether the two rectangles share interior points (more than `gap` apart
    /// counts as apart).
    pub fn overlaps(&self, other: &Rect, gap: f64) -> bool {
        self.min.x < other.max.x - gap
            && other.min.x < self.max.x - gap
            && self.min.y < other.max.y - gap
            && other.min.y < self.max.y - gap
    }

    /// Whether `p` lies inside (boundary included).
    pub fn contains(&self, p: DVec2) -> bool {
        p.x >= self.min.x && p.x <= self.max.x && p.y >= self.min.y && p.y <= self.max.y
    }

    /// The four corners, counter-clockwise from the lower left.
    pub fn corners(&self) -> Vec<DVec2> {
        vec![
            self.min,
            DVec2::new(self.max.x, self.min.y),
            self.max,
            DVec2::new(self.min.x, self.max.y),
        ]
    }
}

/// One thing drawn on the sheet.
#[derive(Clone, Debug, PartialEq)]
pub enum Item {
    /// An open or closed polyline.
    Line {
        /// Layer.
        layer: Layer,
        /// Vertices, mm.
        points: Vec<DVec2>,
        /// Whether the last vertex joins the first.
        closed: bool,
    },
    /// A filled polygon (arrowheads, the north arrow).
    Fill {
        /// Layer.
        layer: Layer,
        /// Vertices, mm.
        points: Vec<DVec2>,
    },
    /// A circle.
    Circle {
        /// Layer.
        layer: Layer,
        /// Centre, mm.
        centre: DVec2,
        /// Radius, mm.
        radius: f64,
    },
    /// One line of text.
    Text {
        /// Insertion point (on the baseline), mm.
        at: DVec2,
        /// Cap height, mm.
        height: f64,
        /// Alignment about `at`.
        align: Align,
        /// Rotation, degrees counter-clockwise.
        rotation: f64,
        /// The text.
        text: String,
    },
}

/// A dimension as placed, for checks: its text box and its dimension line.
#[derive(Clone, Debug, PartialEq)]
pub struct PlacedDimension {
    /// The view it belongs to.
    pub view: ViewKind,
    /// Its text.
    pub text: String,
    /// Box of the text, mm.
    pub text_box: Rect,
    /// Box of the dimension line (arrow to arrow), mm.
    pub line_box: Rect,
    /// What it measures, for writers that keep dimensions as entities (DXF).
    pub measure: Measure,
    /// The items that draw it (extension and dimension lines, arrowheads, text).
    pub items: std::ops::Range<usize>,
}

/// What a placed dimension measures, in sheet mm (model values in model mm).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Measure {
    /// A linear dimension between two feature points.
    Linear {
        /// First feature point.
        a: DVec2,
        /// Second feature point.
        b: DVec2,
        /// A point on the dimension line.
        line: DVec2,
        /// Whether it measures vertically (else horizontally).
        vertical: bool,
        /// The model distance, mm.
        value: f64,
    },
    /// An ordinate: a feature's elevation or position from the datum.
    Ordinate {
        /// The feature point.
        feature: DVec2,
        /// Where its leader ends at the label.
        leader_end: DVec2,
        /// Whether it measures vertically (an elevation).
        vertical: bool,
        /// The model coordinate from the datum, mm.
        value: f64,
    },
}

/// A row of the nozzle schedule.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct ScheduleRow {
    /// Cells, in [`SCHEDULE_COLUMNS`](super::SCHEDULE_COLUMNS) order: mark,
    /// quantity, size, rating, facing, flange type, schedule and wall, pad,
    /// service, orientation, elevation/position, projection.
    pub cells: [String; 12],
}

/// A drawing sheet: size, display list and where things went.
#[derive(Clone, Debug, PartialEq)]
pub struct Sheet {
    /// Sheet size.
    pub size: SheetSize,
    /// The drawing scale: paper mm per model mm is `1 / scale`.
    pub scale: f64,
    /// Everything drawn, in drawing order.
    pub items: Vec<Item>,
    /// Where each view's lines lie on the sheet, in [`ViewKind::ALL`](crate::project::ViewKind::ALL) order.
    pub view_boxes: [Rect; 4],
    /// The dimensions placed.
    pub dimensions: Vec<PlacedDimension>,
    /// The nozzle schedule's rows, in design order.
    pub schedule: Vec<ScheduleRow>,
    /// How much larger than the sheet's scale each view is drawn (1 but for an
    /// enlarged plan), in [`ViewKind::ALL`](crate::project::ViewKind::ALL) order.
    pub factors: [f64; 4],
    /// The region of the plan view with its orientation labels, mm.
    pub plan_region: Rect,
    /// The table column at the right (title block, design data, schedule,
    /// notes; the title block alone on sheets after the first), mm.
    pub tables: Rect,
    /// This sheet's number, from 1.
    pub number: usize,
    /// How many sheets the drawing has.
    pub of: usize,
    /// Which views this sheet shows, in [`ViewKind::ALL`](crate::project::ViewKind::ALL) order.
    pub shown: [bool; 4],
    /// The detail circles drawn on this sheet's elevation.
    pub detail_marks: Vec<DetailMark>,
    /// The enlarged detail views drawn on this sheet.
    pub details: Vec<DetailView>,
}

/// A detail's circle and label on its parent view (the front elevation).
#[derive(Clone, Debug, PartialEq)]
pub struct DetailMark {
    /// The detail's letter, e.g. `"A"`.
    pub label: String,
    /// Centre of the circle on the sheet, mm.
    pub centre: DVec2,
    /// Radius of the circle on the sheet, mm.
    pub radius: f64,
}

/// An enlarged detail view: a circle of the front elevation drawn at a larger
/// scale, titled `DETAIL A (SCALE 1:10)`.
#[derive(Clone, Debug, PartialEq)]
pub struct DetailView {
    /// The detail's letter.
    pub label: String,
    /// The scale it is drawn at (model mm per paper mm, the `n` of 1:n).
    pub scale: f64,
    /// Centre of the detail's circle in the front view's model coordinates, mm.
    pub model_centre: DVec2,
    /// Centre of the detail's circle on this sheet, mm.
    pub centre: DVec2,
    /// Radius of the detail's circle on this sheet, mm.
    pub radius: f64,
    /// The marks of the nozzles it shows.
    pub nozzles: Vec<String>,
    /// The detail's cell on the sheet (circle, dimensions and title), mm.
    pub region: Rect,
}
