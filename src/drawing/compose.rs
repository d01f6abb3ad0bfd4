//! Composes a vessel's sheet: border, the four views at one scale with their
//! titles, dimensions on the front elevation, notes with leaders to their targets,
//! north arrow beside the plan, tables in the right-hand column and the revision
//! triangle — all as a [`Sheet`] display list in paper mm. One sheet of several
//! ([`Content`], chosen by `sheets`) shows some of the views, the detail circles
//! on its elevation or detail views in a grid, and the title block alone after
//! the first sheet.

use glam::DVec2;

use super::data::VesselData;
use super::detail;
use super::dimensions::{self, format_mm};
use super::labels::{self, Movable};
use super::layout::{Margins, Placement, enlarged_scale, lay_out};
use super::legibility::{DetailSpec, detail_radius};
use super::orientation;
use super::sheet::{
    Align, HiddenLines, Item, Layer, PlacedDimension, Rect, Sheet, SheetOptions, SheetSize,
};
use super::tables;
use super::text::text_width;
use crate::project::{LineKind, plan_north};

/// Titles written under the views.
const VIEW_TITLES: [&str; 4] = ["ELEVATION", "PLAN", "SIDE ELEVATION", "ISOMETRIC"];

/// Border margin and table column width, mm.
fn frame_sizes(size: SheetSize) -> (f64, f64) {
    match size {
        SheetSize::AnsiB | SheetSize::IsoA3 => (8.0, 150.0),
        SheetSize::AnsiD | SheetSize::IsoA1 => (12.0, 230.0),
    }
}

/// What one sheet of a drawing shows.
#[derive(Clone, Debug, PartialEq)]
pub struct Content {
    /// The views drawn, in `ViewKind::ALL` order.
    pub shown: [bool; 4],
    /// Whether the table column has the design data, schedule and notes (the
    /// first sheet) or the title block alone.
    pub full_tables: bool,
    /// The sheet's number, from 1, and how many there are.
    pub number: (usize, usize),
    /// Details whose circles are drawn on this sheet's elevation.
    pub marks: Vec<DetailSpec>,
    /// Details drawn on this sheet.
    pub details: Vec<DetailSpec>,
}

impl Content {
    /// Everything on one sheet.
    pub fn single() -> Self {
        Self {
            shown: [true; 4],
            full_tables: true,
            number: (1, 1),
            marks: Vec::new(),
            details: Vec::new(),
        }
    }
}

/// The drawing area of a sheet of `size`: inside the border, left of the table
/// column.
pub fn drawing_area(size: SheetSize) -> Rect {
    let paper = size.dimensions();
    let (margin, column) = frame_sizes(size);
    let inner = Rect::new(DVec2::splat(margin), paper - DVec2::splat(margin));
    Rect::new(
        inner.min + DVec2::splat(4.0),
        DVec2::new(inner.max.x - column - 6.0, inner.max.y - 4.0),
    )
}

/// Composes the sheet of one vessel with every view.
pub fn compose(data: &VesselData, options: &SheetOptions) -> Sheet {
    compose_content(data, options, &Content::single())
}

/// Composes one sheet of a vessel's drawing showing `content`.
pub fn compose_content(data: &VesselData, options: &SheetOptions, content: &Content) -> Sheet {
    let size = options.size;
    let shown = content.shown;
    let h = size.text_height();
    let paper = size.dimensions();
    let (margin, column) = frame_sizes(size);
    let mut items = Vec::new();
    items.push(Item::Line {
        layer: Layer::Border,
        points: Rect::new(DVec2::ZERO, paper).corners(),
        closed: true,
    });
    let inner = Rect::new(DVec2::splat(margin), paper - DVec2::splat(margin));
    items.push(Item::Line {
        layer: Layer::Border,
        points: inner.corners(),
        closed: true,
    });
    let column_left = inner.max.x - column;
    let area = drawing_area(size);
    // Layout: margins depend on the scale (dimension packing is in paper mm), so
    // lay out twice.
    let bounds: [(DVec2, DVec2); 4] =
        std::array::from_fn(|k| data.views[k].bounds().unwrap_or((DVec2::ZERO, DVec2::ONE)));
    let dims = dimensions::plan(data);
    let side_dims = dimensions::plan_side(data);
    let title_room = 2.8 * h + 2.0;
    let margins_at = |scale: f64| -> [Margins; 4] {
        let mut m = [Margins {
            left: 2.0,
            right: 2.0,
            bottom: title_room,
            top: 2.0,
        }; 4];
        let d = dimensions::margins(&dims, h, scale);
        m[0] = Margins {
            left: d.left.max(2.0),
            right: d.right.max(2.0),
            bottom: d.bottom + title_room,
            top: d.top.max(2.0),
        };
        let d = dimensions::margins(&side_dims, h, scale);
        m[2] = Margins {
            left: d.left.max(2.0),
            right: d.right.max(2.0),
            bottom: d.bottom + title_room,
            top: d.top.max(2.0),
        };
        m[1].right += 16.0;
        m
    };
    // The plan (the angle view of a horizontal vessel) needs room for the
    // orientation circle's labels; a plan smaller than `min_plan` at the sheet's
    // scale is drawn at a larger standard scale of its own.
    let ov = orientation::angle_view(data);
    let min_plan = match size {
        SheetSize::AnsiB | SheetSize::IsoA3 => 60.0,
        SheetSize::AnsiD | SheetSize::IsoA1 => 100.0,
    };
    let margins_with = |scale: f64| {
        let mut m = margins_at(scale);
        let extra = orientation::label_margin(h);
        m[ov].left += extra;
        m[ov].right += extra;
        m[ov].top += extra;
        m[ov].bottom += extra;
        m
    };
    let plan_extent = {
        let (lo, hi) = bounds[1];
        (hi - lo).max_element()
    };
    let settle = |factors: [f64; 4]| {
        let first = lay_out(&bounds, &margins_with(1.0), area, factors, shown);
        let mut p = lay_out(&bounds, &margins_with(first.scale), area, factors, shown);
        if p.scale < first.scale {
            p = lay_out(&bounds, &margins_with(p.scale), area, factors, shown);
        }
        p
    };
    let mut factors = [1.0; 4];
    let mut placement = settle(factors);
    if !shown.contains(&true) {
        // A sheet of details: its scale is its elevation's (the details say theirs).
        placement.scale = content.details.first().map_or(1.0, |d| d.scale);
    }
    for _ in 0..4 {
        if !shown[1] {
            break;
        }
        let want = if plan_extent / placement.scale < min_plan {
            (placement.scale / enlarged_scale(plan_extent, min_plan)).max(1.0)
        } else {
            1.0
        };
        if (want - factors[1]).abs() < 1e-9 {
            break;
        }
        factors[1] = want;
        placement = settle(factors);
    }
    let view_boxes: [Rect; 4] = std::array::from_fn(|k| {
        if shown[k] {
            Rect::new(
                placement.to_sheet(k, bounds[k].0),
                placement.to_sheet(k, bounds[k].1),
            )
        } else {
            Rect::new(DVec2::ZERO, DVec2::ZERO)
        }
    });
    // Views.
    let mut titles = Vec::new();
    for (k, view) in data.views.iter().enumerate() {
        if !shown[k] {
            continue;
        }
        for line in view.entities.iter().flat_map(|e| &e.lines) {
            let layer = match line.kind {
                LineKind::Visible => Layer::Outline,
                LineKind::Hidden if options.hidden[k] == HiddenLines::Omitted => continue,
                LineKind::Hidden => Layer::Hidden,
                LineKind::Centre => Layer::Centre,
            };
            items.push(Item::Line {
                layer,
                points: line
                    .points
                    .iter()
                    .map(|&p| placement.to_sheet(k, p))
                    .collect(),
                closed: false,
            });
        }
        let b = view_boxes[k];
        let title = format!(
            "{} ({} {})",
            VIEW_TITLES[k],
            data.design.tag,
            scale_text(placement.view_scale(k))
        );
        titles.push(items.len());
        items.push(Item::Text {
            at: DVec2::new(
                0.5 * (b.min.x + b.max.x),
                b.min.y - 2.2 * h - dims_bottom(k, [&dims, &side_dims], h, placement.scale),
            ),
            height: h,
            align: Align::Middle,
            rotation: 0.0,
            text: title,
        });
    }
    let mut placed = Vec::new();
    let mut dim_texts = Vec::new();
    for (k, d) in [(0, &dims), (2, &side_dims)] {
        if shown[k] {
            dimensions::place(
                d,
                k,
                view_boxes[k],
                &placement,
                h,
                &mut items,
                &mut placed,
                &mut dim_texts,
            );
        }
    }
    let mut movable: Vec<Movable> = dim_texts
        .iter()
        .map(|&item| Movable {
            item,
            target: None,
            outside_views: true,
        })
        .collect();
    if shown[ov] {
        movable.extend(orientation::draw(data, &placement, h, shown, &mut items));
    }
    if shown[0] {
        movable.extend(notes(data, &placement, area, &placed, h, &mut items));
    }
    movable.extend(titles.iter().map(|&item| Movable {
        item,
        target: None,
        outside_views: false,
    }));
    if shown[1] {
        north_arrow(data, view_boxes[1], h, &mut items);
    }
    // Detail circles on the elevation, detail views in a grid.
    let mut detail_marks = Vec::new();
    if shown[0] {
        for spec in &content.marks {
            let (m, label) = detail::mark(spec, &placement, h, &mut items);
            detail_marks.push(m);
            movable.push(label);
        }
    }
    let mut details = Vec::new();
    let mut keep_views: Vec<Rect> = view_boxes.to_vec();
    let radius = detail_radius(size);
    for (spec, cell) in
        content
            .details
            .iter()
            .zip(detail_cells(data, &content.details, area, h, radius))
    {
        let (view, dims, labels) =
            detail::draw(data, spec, cell, radius, options.hidden[0], h, &mut items);
        keep_views.push(Rect::new(
            view.centre - DVec2::splat(radius),
            view.centre + DVec2::splat(radius),
        ));
        details.push(view);
        placed.extend(dims);
        movable.extend(labels);
    }
    let schedule = tables::schedule(data);
    let scale_cell = if shown.contains(&true) {
        scale_text(placement.scale)
    } else {
        "AS SHOWN".to_string()
    };
    let (_, revision_at) = tables::draw(
        data,
        &schedule,
        &tables::Frame {
            size,
            scale: &scale_cell,
            number: content.number,
            full: content.full_tables,
        },
        DVec2::new(column_left, inner.min.y),
        inner.max.x,
        &mut items,
    );
    let revision = tables::title_fields(data).revision;
    revision_triangle(revision_at, &revision, h, &mut items);
    // Every movable text where it touches no other text and no outline.
    labels::place_labels(&mut items, &movable, paper, area, &[], &keep_views, h);
    for d in placed.iter_mut() {
        if let Some(b) = d
            .items
            .clone()
            .filter_map(|i| items.get(i))
            .find_map(labels::item_box)
        {
            d.text_box = b;
        }
    }
    Sheet {
        size,
        scale: placement.scale,
        items,
        view_boxes,
        dimensions: placed,
        schedule,
        factors: placement.factors,
        plan_region: {
            let m = if ov == 1 {
                orientation::label_margin(h)
            } else {
                2.0 * h
            };
            Rect::new(
                view_boxes[1].min - DVec2::splat(m),
                view_boxes[1].max + DVec2::splat(m),
            )
        },
        tables: Rect::new(
            DVec2::new(column_left, inner.min.y),
            DVec2::new(inner.max.x, inner.max.y),
        ),
        number: content.number.0,
        of: content.number.1,
        shown,
        detail_marks,
        details,
    }
}

/// Cells for `specs` on `area`: a grid of equal cells (the largest detail's),
/// filled row by row from the top left, the spare room shared out.
fn detail_cells(
    data: &VesselData,
    specs: &[DetailSpec],
    area: Rect,
    h: f64,
    radius: f64,
) -> Vec<Rect> {
    let cell = specs
        .iter()
        .map(|s| detail::cell_size(data, s, radius, h))
        .fold(DVec2::ZERO, DVec2::max);
    let (cols, _) = detail_grid(area, cell);
    let rows = specs.len().div_ceil(cols.max(1)).max(1);
    let spare = (area.size() - cell * DVec2::new(cols as f64, rows as f64)).max(DVec2::ZERO);
    let gap = spare / DVec2::new(cols as f64 + 1.0, rows as f64 + 1.0);
    (0..specs.len())
        .map(|i| {
            let (c, r) = ((i % cols) as f64, (i / cols) as f64);
            let min = DVec2::new(
                area.min.x + gap.x + c * (cell.x + gap.x),
                area.max.y - (r + 1.0) * (cell.y + gap.y),
            );
            Rect::new(min, min + cell)
        })
        .collect()
}

/// Columns and rows of cells of `cell` size that fit on `area` (at least one).
pub fn detail_grid(area: Rect, cell: DVec2) -> (usize, usize) {
    let fit = |avail: f64, c: f64| ((avail / c.max(1.0)).floor() as usize).max(1);
    (fit(area.size().x, cell.x), fit(area.size().y, cell.y))
}

/// How many details of `specs` a detail sheet of `size` holds.
pub fn details_per_sheet(data: &VesselData, specs: &[DetailSpec], size: SheetSize) -> usize {
    let h = size.text_height();
    let cell = specs
        .iter()
        .map(|s| detail::cell_size(data, s, detail_radius(size), h))
        .fold(DVec2::ZERO, DVec2::max);
    let (cols, rows) = detail_grid(drawing_area(size), cell);
    cols * rows
}

/// `1:n` for a scale.
fn scale_text(scale: f64) -> String {
    format!("1:{}", format_mm(scale))
}

/// How far below view `k`'s box its dimensions reach (the front and side
/// elevations carry dimensions; 0 for the other views).
fn dims_bottom(k: usize, [front, side]: [&dimensions::Dimensions; 2], h: f64, scale: f64) -> f64 {
    match k {
        0 => dimensions::margins(front, h, scale).bottom,
        2 => dimensions::margins(side, h, scale).bottom,
        _ => 0.0,
    }
}

/// Notes in the front elevation: text at the note's position, handed to the
/// label placer with its target's anchor, where its leader points (both follow
/// the target: they are resolved from it on every update). A text that would cover a dimension is moved out
/// past the dimensions on its side; every text stays on the drawing area.
fn notes(
    data: &VesselData,
    placement: &Placement,
    area: Rect,
    dims: &[PlacedDimension],
    h: f64,
    items: &mut Vec<Item>,
) -> Vec<Movable> {
    let mut movable = Vec::new();
    let front = data.views[0].projection;
    for n in &data.notes {
        let anchor = placement.to_sheet(0, front.project(n.anchor));
        let at = placement.to_sheet(0, front.project(n.position));
        let w = text_width(&n.text, h);
        let mut right = at.x >= anchor.x;
        let mut x = if right { at.x + 1.0 } else { at.x - 1.0 };
        let y = (at.y - 0.4 * h).clamp(area.min.y, area.max.y - h);
        let text_box = |x: f64, right: bool| {
            let x0 = if right { x } else { x - w };
            Rect::new(DVec2::new(x0, y - 0.3 * h), DVec2::new(x0 + w, y + 1.3 * h))
        };
        let blocked = |b: &Rect| {
            dims.iter()
                .any(|d| d.text_box.overlaps(b, 0.0) || d.line_box.overlaps(b, 0.0))
        };
        if blocked(&text_box(x, right)) {
            // Past the farthest dimension box in the text's band on its side.
            let band = |d: &&PlacedDimension| {
                let r = [d.text_box, d.line_box];
                r.iter()
                    .any(|r| r.min.y <= y + 1.3 * h && r.max.y >= y - 0.3 * h)
            };
            x = if right {
                dims.iter()
                    .filter(band)
                    .map(|d| d.text_box.max.x.max(d.line_box.max.x))
                    .fold(x, f64::max)
                    + 2.0
            } else {
                dims.iter()
                    .filter(band)
                    .map(|d| d.text_box.min.x.min(d.line_box.min.x))
                    .fold(x, f64::min)
                    - 2.0
            };
        }
        // Keep the text on the drawing area: flip it to the other side, then
        // slide it in, when it would run off.
        if right && x + w > area.max.x {
            right = false;
        } else if !right && x - w < area.min.x {
            right = true;
        }
        x = if right {
            x.clamp(area.min.x, (area.max.x - w).max(area.min.x))
        } else {
            x.clamp((area.min.x + w).min(area.max.x), area.max.x)
        };
        movable.push(Movable {
            item: items.len(),
            target: Some(anchor),
            outside_views: false,
        });
        items.push(Item::Text {
            at: DVec2::new(x, y),
            height: h,
            align: if right { Align::Start } else { Align::End },
            rotation: 0.0,
            text: n.text.clone(),
        });
    }
    movable
}

/// The north arrow beside the plan view's upper right corner.
fn north_arrow(data: &VesselData, plan_box: Rect, h: f64, items: &mut Vec<Item>) {
    let north = plan_north(&data.views[1].projection, &data.frame);
    let r = 5.0;
    let c = DVec2::new(plan_box.max.x + 9.0, plan_box.max.y - r - 2.0 * h);
    items.push(Item::Circle {
        layer: Layer::Dimension,
        centre: c,
        radius: r,
    });
    let tip = c + north * r;
    let tail = c - north * r;
    let side = north.perp() * r * 0.35;
    items.push(Item::Fill {
        layer: Layer::Dimension,
        points: vec![tip, c + side - north * r * 0.3, c - side - north * r * 0.3],
    });
    items.push(Item::Line {
        layer: Layer::Dimension,
        points: vec![tail, tip],
        closed: false,
    });
    items.push(Item::Text {
        at: c + north * (r + 1.0 + 0.5 * h) - DVec2::Y * 0.5 * h,
        height: h,
        align: Align::Middle,
        rotation: 0.0,
        text: "N".to_string(),
    });
}

/// The revision triangle with the revision inside, centred at `at`.
fn revision_triangle(at: DVec2, revision: &str, h: f64, items: &mut Vec<Item>) {
    let side = (text_width(revision, h) + 1.6 * h).max(2.2 * h);
    let height = side * 3f64.sqrt() / 2.0;
    let base = at.y - height / 3.0;
    items.push(Item::Line {
        layer: Layer::Border,
        points: vec![
            DVec2::new(at.x - side / 2.0, base),
            DVec2::new(at.x + side / 2.0, base),
            DVec2::new(at.x, base + height),
        ],
        closed: true,
    });
    items.push(Item::Text {
        at: DVec2::new(at.x, base + 0.25 * h),
        height: 0.8 * h,
        align: Align::Middle,
        rotation: 0.0,
        text: revision.to_string(),
    });
}
