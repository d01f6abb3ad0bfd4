//! The label placer: every movable text of a sheet (dimension texts, ordinate
//! labels, notes, plan marks, view titles) is put where it touches no other text
//! and crosses no view outline, and [`collisions`] checks that this holds.
//!
//! Fixed texts (tables, the title block) and the visible lines of the views are
//! obstacles, indexed in a grid. Labels are then placed greedily in the order
//! given: first every label whose own position is free keeps it; then each
//! remaining one takes the nearest free position on rings of growing radius
//! about it (sixteen and more bearings per ring), staying on the drawing area and
//! out of the keep-out rectangles (the table column; the view boxes for dimension
//! texts). A label moved further than its own height gets a leader to where it
//! belonged; a note always has its leader, with an arrowhead, to its target.
//! A label that finds no free place anywhere on the area keeps its position and
//! [`collisions`] reports it.

use glam::DVec2;

use super::sheet::{Item, Layer, Rect};
use super::text::text_box;

/// A text item the placer may move.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Movable {
    /// Index of the [`Item::Text`] in the sheet's items.
    pub item: usize,
    /// Where its leader points: a note's target; `None` for the text's own
    /// position (dimension texts, ordinates, marks).
    pub target: Option<DVec2>,
    /// Whether it must stay out of the view boxes (dimension texts do).
    pub outside_views: bool,
}

/// Grid cell size of the obstacle index, mm.
const CELL: f64 = 4.0;

/// Clearance kept between a placed text and anything else, mm.
const CLEARANCE: f64 = 0.3;

/// A uniform grid over the sheet holding segments and boxes by the cells their
/// bounding boxes cover.
struct Grid {
    cols: usize,
    rows: usize,
    segments: Vec<(DVec2, DVec2)>,
    boxes: Vec<Rect>,
    cell_segments: Vec<Vec<u32>>,
    cell_boxes: Vec<Vec<u32>>,
}

impl Grid {
    fn new(paper: DVec2) -> Self {
        let cols = (paper.x / CELL).ceil().max(1.0) as usize;
        let rows = (paper.y / CELL).ceil().max(1.0) as usize;
        Self {
            cols,
            rows,
            segments: Vec::new(),
            boxes: Vec::new(),
            cell_segments: vec![Vec::new(); cols * rows],
            cell_boxes: vec![Vec::new(); cols * rows],
        }
    }

    fn cells(&self, r: &Rect) -> impl Iterator<Item = usize> + '_ {
        let clamp_x = |v: f64| ((v / CELL).floor().max(0.0) as usize).min(self.cols - 1);
        let clamp_y = |v: f64| ((v / CELL).floor().max(0.0) as usize).min(self.rows - 1);
        let (x0, x1) = (clamp_x(r.min.x), clamp_x(r.max.x));
        let (y0, y1) = (clamp_y(r.min.y), clamp_y(r.max.y));
        (y0..=y1).flat_map(move |y| (x0..=x1).map(move |x| y * self.cols + x))
    }

    fn add_segment(&mut self, a: DVec2, b: DVec2) {
        let id = self.segments.len() as u32;
        self.segments.push((a, b));
        let cells: Vec<usize> = self.cells(&Rect::new(a, b)).collect();
        for c in cells {
            self.cell_segments[c].push(id);
        }
    }

    fn add_box(&mut self, r: Rect) {
        let id = self.boxes.len() as u32;
        self.boxes.push(r);
        let cells: Vec<usize> = self.cells(&r).collect();
        for c in cells {
            self.cell_boxes[c].push(id);
        }
    }

    /// Whether `r` (grown by the clearance) touches a box or crosses a segment.
    fn blocked(&self, r: &Rect) -> bool {
        let grown = Rect::new(
            r.min - DVec2::splat(CLEARANCE),
            r.max + DVec2::splat(CLEARANCE),
        );
        self.cells(&grown).any(|c| {
            self.cell_boxes[c]
                .iter()
                .any(|&b| self.boxes[b as usize].overlaps(&grown, 0.0))
                || self.cell_segments[c].iter().any(|&s| {
                    let (a, b) = self.segments[s as usize];
                    segment_crosses(a, b, &grown)
                })
        })
    }
}

/// Whether segment `ab` has points in the interior of `r`.
pub fn segment_crosses(a: DVec2, b: DVec2, r: &Rect) -> bool {
    // Liang–Barsky clipping against the open rectangle.
    let d = b - a;
    let (mut t0, mut t1) = (0.0f64, 1.0f64);
    for (p, q) in [
        (-d.x, a.x - r.min.x),
        (d.x, r.max.x - a.x),
        (-d.y, a.y - r.min.y),
        (d.y, r.max.y - a.y),
    ] {
        if p.abs() < 1e-15 {
            if q <= 0.0 {
                return false;
            }
        } else {
            let t = q / p;
            if p < 0.0 {
                t0 = t0.max(t);
            } else {
                t1 = t1.min(t);
            }
        }
    }
    t0 < t1
}

/// The box of a text item, if it is one.
pub fn item_box(item: &Item) -> Option<Rect> {
    match item {
        Item::Text {
            at,
            height,
            align,
            rotation,
            text,
        } => Some(text_box(*at, *height, *align, *rotation, text)),
        _ => None,
    }
}

/// The segments of the views' visible outlines.
fn outline_segments(items: &[Item]) -> impl Iterator<Item = (DVec2, DVec2)> + '_ {
    items.iter().flat_map(|item| match item {
        Item::Line {
            layer: Layer::Outline,
            points,
            closed,
        } => {
            let mut s: Vec<(DVec2, DVec2)> = points.windows(2).map(|w| (w[0], w[1])).collect();
            if *closed && points.len() > 2 {
                s.push((points[points.len() - 1], points[0]));
            }
            s
        }
        _ => Vec::new(),
    })
}

/// Places the `movable` texts of `items` (see the module doc) on `area`, out of
/// `keep_out` and, for dimension texts, out of `views`; appends leaders. `h` is
/// the lettering height.
pub fn place_labels(
    items: &mut Vec<Item>,
    movable: &[Movable],
    paper: DVec2,
    area: Rect,
    keep_out: &[Rect],
    views: &[Rect],
    h: f64,
) {
    let mut grid = Grid::new(paper);
    for (a, b) in outline_segments(items) {
        grid.add_segment(a, b);
    }
    let is_movable: std::collections::HashSet<usize> = movable.iter().map(|m| m.item).collect();
    for (i, item) in items.iter().enumerate() {
        if !is_movable.contains(&i)
            && let Some(r) = item_box(item)
        {
            grid.add_box(r);
        }
    }
    let allowed = |m: &Movable, r: &Rect| {
        r.min.x >= area.min.x
            && r.min.y >= area.min.y
            && r.max.x <= area.max.x
            && r.max.y <= area.max.y
            && !keep_out.iter().any(|k| k.overlaps(r, 0.0))
            && !(m.outside_views && views.iter().any(|v| v.overlaps(r, 0.0)))
    };
    // Pass 1: labels free where they are keep their places.
    let mut done = vec![false; movable.len()];
    let mut shift = vec![DVec2::ZERO; movable.len()];
    for (k, m) in movable.iter().enumerate() {
        let Some(r) = items.get(m.item).and_then(item_box) else {
            done[k] = true;
            continue;
        };
        if allowed(m, &r) && !grid.blocked(&r) {
            grid.add_box(r);
            done[k] = true;
        }
    }
    // Pass 2: the others take the nearest free place.
    let step = 0.5 * h;
    let reach = area.size().length();
    for (k, m) in movable.iter().enumerate() {
        if done[k] {
            continue;
        }
        let Some(r) = items.get(m.item).and_then(item_box) else {
            continue;
        };
        let free = |d: DVec2| {
            let moved = Rect {
                min: r.min + d,
                max: r.max + d,
            };
            (allowed(m, &moved) && !grid.blocked(&moved)).then_some(moved)
        };
        let mut found = free(DVec2::ZERO).map(|b| (DVec2::ZERO, b));
        let mut ring = 1;
        while found.is_none() && f64::from(ring) * step <= reach {
            let radius = f64::from(ring) * step;
            let bearings = ((std::f64::consts::TAU * radius / step).ceil() as u32).max(16);
            let mut best: Option<(f64, DVec2, Rect)> = None;
            for j in 0..bearings {
                let a = std::f64::consts::TAU * f64::from(j) / f64::from(bearings);
                let d = DVec2::new(a.cos(), a.sin()) * radius;
                if let Some(b) = free(d) {
                    // Prefer the bearing nearest the target side.
                    let toward = m
                        .target
                        .map_or(0.0, |t| ((b.min + b.max) / 2.0 - t).length());
                    if best.is_none_or(|(s, ..)| toward < s) {
                        best = Some((toward, d, b));
                    }
                }
            }
            found = best.map(|(_, d, b)| (d, b));
            ring += 1;
        }
        if let Some((d, b)) = found {
            grid.add_box(b);
            shift[k] = d;
            if let Some(Item::Text { at, .. }) = items.get_mut(m.item) {
                *at += d;
            }
        }
        done[k] = true;
    }
    // Leaders.
    for (k, m) in movable.iter().enumerate() {
        let Some(r) = items.get(m.item).and_then(item_box) else {
            continue;
        };
        let (target, arrow) = match m.target {
            Some(t) => (t, true),
            None if shift[k].length() > 1.5 * h => ((r.min + r.max) / 2.0 - shift[k], false),
            None => continue,
        };
        let from = nearest_on_rect(&r, target);
        if (from - target).length() < 0.5 {
            continue;
        }
        items.push(Item::Line {
            layer: Layer::Dimension,
            points: vec![from, target],
            closed: false,
        });
        if arrow {
            let dir = (target - from).normalize();
            let len = 0.9 * h;
            let back = target - dir * len;
            let side = dir.perp() * len / 6.0;
            items.push(Item::Fill {
                layer: Layer::Dimension,
                points: vec![target, back + side, back - side],
            });
        }
    }
}

/// The point of `r`'s boundary nearest `p` (a point outside `r`), or the middle
/// of the nearer vertical side for a point inside.
fn nearest_on_rect(r: &Rect, p: DVec2) -> DVec2 {
    let c = p.clamp(r.min, r.max);
    if c != p {
        return c;
    }
    let mid_y = 0.5 * (r.min.y + r.max.y);
    if p.x - r.min.x < r.max.x - p.x {
        DVec2::new(r.min.x, mid_y)
    } else {
        DVec2::new(r.max.x, mid_y)
    }
}

/// Every collision on a sheet's items: two texts whose boxes overlap, or a text
/// crossed by a visible outline; each described for a failing test.
pub fn collisions(items: &[Item]) -> Vec<String> {
    let boxes: Vec<(Rect, &str)> = items
        .iter()
        .filter_map(|i| match i {
            Item::Text { text, .. } => item_box(i).map(|b| (b, text.as_str())),
            _ => None,
        })
        .collect();
    let paper = boxes
        .iter()
        .fold(DVec2::ONE, |m, (b, _)| m.max(b.max))
        .max(DVec2::ONE);
    let mut grid = Grid::new(paper + DVec2::ONE);
    for (a, b) in outline_segments(items) {
        grid.add_segment(a, b);
    }
    let mut out = Vec::new();
    // Boxes are checked strictly (touching is fine): shrink by a hair.
    let shrink = |r: &Rect| Rect {
        min: r.min + DVec2::splat(CLEARANCE * 0.5),
        max: r.max - DVec2::splat(CLEARANCE * 0.5),
    };
    let mut text_grid = Grid::new(paper + DVec2::ONE);
    for (i, (b, text)) in boxes.iter().enumerate() {
        let s = shrink(b);
        if grid.cells(&s).any(|c| {
            grid.cell_segments[c].iter().any(|&k| {
                let (p, q) = grid.segments[k as usize];
                segment_crosses(p, q, &s)
            })
        }) {
            out.push(format!("text {text:?} crosses a view outline at {b:?}"));
        }
        let mut hits = Vec::new();
        for c in text_grid.cells(&s) {
            for &j in &text_grid.cell_boxes[c] {
                if text_grid.boxes[j as usize].overlaps(&s, 0.0) && !hits.contains(&j) {
                    hits.push(j);
                }
            }
        }
        for j in hits {
            out.push(format!(
                "text {text:?} overlaps text {:?}",
                boxes[j as usize].1
            ));
        }
        debug_assert_eq!(text_grid.boxes.len(), i);
        text_grid.add_box(s);
    }
    out
}

/// Every layout problem of a sheet: the [`collisions`] of its items and every
/// text that runs off its paper; each described for a failing test or the
/// layout example.
pub fn layout_problems(sheet: &super::sheet::Sheet) -> Vec<String> {
    let paper = sheet.size.dimensions();
    let mut out = collisions(&sheet.items);
    for item in &sheet.items {
        if let (Item::Text { text, .. }, Some(b)) = (item, item_box(item))
            && (b.min.x < 0.0 || b.min.y < 0.0 || b.max.x > paper.x || b.max.y > paper.y)
        {
            out.push(format!("text {text:?} runs off the paper at {b:?}"));
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::drawing::Align;

    fn text(at: DVec2, s: &str) -> Item {
        Item::Text {
            at,
            height: 2.0,
            align: Align::Start,
            rotation: 0.0,
            text: s.to_string(),
        }
    }

    #[test]
    fn segments_cross_open_rectangles_only() {
        let r = Rect::new(DVec2::ZERO, DVec2::new(10.0, 5.0));
        assert!(segment_crosses(
            DVec2::new(-1.0, 2.0),
            DVec2::new(11.0, 2.0),
            &r
        ));
        assert!(!segment_crosses(
            DVec2::new(-1.0, 5.0),
            DVec2::new(11.0, 5.0),
            &r
        ));
        assert!(!segment_crosses(
            DVec2::new(-1.0, 6.0),
            DVec2::new(11.0, 9.0),
            &r
        ));
        assert!(segment_crosses(
            DVec2::new(5.0, 2.0),
            DVec2::new(5.0, 3.0),
            &r
        ));
    }

    /// Two labels on top of each other and one across an outline: the check
    /// finds both collisions; after placing, none is left and the moved labels
    /// have leaders.
    #[test]
    fn colliding_labels_are_moved_apart_and_off_outlines() {
        let mut items = vec![
            Item::Line {
                layer: Layer::Outline,
                points: vec![DVec2::new(50.0, 0.0), DVec2::new(50.0, 100.0)],
                closed: false,
            },
            text(DVec2::new(20.0, 50.0), "SADDLES 4380"),
            text(DVec2::new(22.0, 50.5), "N5 POS 4000"),
            text(DVec2::new(45.0, 20.0), "Davit for manway M1"),
        ];
        assert_eq!(collisions(&items).len(), 2, "{:?}", collisions(&items));
        let movable: Vec<Movable> = (1..4)
            .map(|item| Movable {
                item,
                target: None,
                outside_views: false,
            })
            .collect();
        let paper = DVec2::new(200.0, 100.0);
        let area = Rect::new(DVec2::ZERO, paper);
        place_labels(&mut items, &movable, paper, area, &[], &[], 2.0);
        assert!(collisions(&items).is_empty(), "{:?}", collisions(&items));
        let leaders = items
            .iter()
            .filter(|i| {
                matches!(
                    i,
                    Item::Line {
                        layer: Layer::Dimension,
                        ..
                    }
                )
            })
            .count();
        assert!(leaders <= 2);
    }
}
