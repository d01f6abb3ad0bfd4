//! Placing planned dimensions: ordinates first, then linear dimensions packed
//! first-fit into parallel tracks outside the view's box, and the paper margins
//! that needs (see the parent module).

use super::{DimSide, Dimensions, LinearDim};
use glam::DVec2;

use crate::drawing::layout::{Margins, Placement};
use crate::drawing::sheet::{Align, Item, Layer, Measure, PlacedDimension, Rect};
use crate::drawing::text::text_width;
use crate::project::ViewKind;

/// Spacing between linear tracks, mm, for lettering of height `h`.
fn track_spacing(h: f64) -> f64 {
    2.2 * h + 2.5
}

/// Distance from the view's box to the first track or ordinate line, mm.
fn first_offset(h: f64) -> f64 {
    2.0 * h + 3.0
}

/// Tracks per side after packing, and each linear dimension's track.
fn pack(dims: &Dimensions, h: f64, scale: f64) -> (Vec<usize>, [usize; 4]) {
    let mut tracks: Vec<Vec<Vec<(f64, f64)>>> = vec![Vec::new(); 4];
    let mut order: Vec<usize> = (0..dims.linear.len()).collect();
    let along = |d: &LinearDim, p: DVec2| if d.side.vertical() { p.y } else { p.x };
    let span = |d: &LinearDim| (along(d, d.b) - along(d, d.a)).abs();
    order.sort_by(|&i, &j| span(&dims.linear[i]).total_cmp(&span(&dims.linear[j])));
    let mut assigned = vec![0usize; dims.linear.len()];
    for i in order {
        let d = &dims.linear[i];
        let s = DimSide::ALL.iter().position(|&x| x == d.side).unwrap_or(0);
        let (a, b) = (along(d, d.a) / scale, along(d, d.b) / scale);
        let mid = 0.5 * (a + b);
        let half_text = 0.5 * text_width(&d.text, h) + 1.0;
        let interval = (
            a.min(b).min(mid - half_text) - 1.0,
            a.max(b).max(mid + half_text) + 1.0,
        );
        let t = tracks[s]
            .iter()
            .position(|used| {
                used.iter()
                    .all(|&(lo, hi)| interval.1 < lo || hi < interval.0)
            })
            .unwrap_or_else(|| {
                tracks[s].push(Vec::new());
                tracks[s].len() - 1
            });
        tracks[s][t].push(interval);
        assigned[i] = t;
    }
    let counts = std::array::from_fn(|s| tracks[s].len());
    (assigned, counts)
}

/// Width of the widest ordinate label on each side, mm.
fn ordinate_widths(dims: &Dimensions, h: f64) -> [f64; 4] {
    std::array::from_fn(|s| {
        dims.ordinates
            .iter()
            .filter(|o| o.side == DimSide::ALL[s])
            .map(|o| text_width(&o.text, h))
            .fold(0.0, f64::max)
    })
}

/// Depth of the ordinate band on each side (0 without ordinates), mm.
fn ordinate_depths(dims: &Dimensions, h: f64) -> [f64; 4] {
    let widths = ordinate_widths(dims, h);
    std::array::from_fn(|s| {
        if dims.ordinates.iter().any(|o| o.side == DimSide::ALL[s]) {
            first_offset(h) + widths[s] + 3.0
        } else {
            0.0
        }
    })
}

/// Paper margins the dimensions need round the view at `scale`.
pub fn margins(dims: &Dimensions, h: f64, scale: f64) -> Margins {
    let (_, counts) = pack(dims, h, scale);
    let ord = ordinate_depths(dims, h);
    let depth = |s: usize| {
        let tracks = if counts[s] > 0 {
            first_offset(h) + track_spacing(h) * (counts[s] as f64 - 1.0) + h + 2.0
        } else {
            0.0
        };
        ord[s] + tracks
    };
    Margins {
        left: depth(0),
        right: depth(1),
        bottom: depth(2),
        top: depth(3),
    }
}

/// An arrowhead at `tip` pointing along `dir` (unit), length `len`.
fn arrow(tip: DVec2, dir: DVec2, len: f64) -> Item {
    let back = tip - dir * len;
    let side = dir.perp() * (len / 3.0) * 0.5;
    Item::Fill {
        layer: Layer::Dimension,
        points: vec![tip, back + side, back - side],
    }
}

/// Places the dimensions of view `k` whose lines lie in `view_box`; appends the
/// items, the placed dimensions and, in the same order, the indices of their
/// text items (for the label placer).
#[expect(
    clippy::too_many_arguments,
    reason = "the view's dimensions are placed into the sheet's shared item, dimension and text lists"
)]
pub fn place(
    dims: &Dimensions,
    k: usize,
    view_box: Rect,
    placement: &Placement,
    h: f64,
    items: &mut Vec<Item>,
    placed: &mut Vec<PlacedDimension>,
    texts: &mut Vec<usize>,
) {
    let view = ViewKind::ALL[k];
    let to_sheet = |p: DVec2| placement.to_sheet(k, p);
    let ord = ordinate_depths(dims, h);
    // Where a side's band starts (the box edge) as a coordinate across the side.
    let edge = |side: DimSide| match side {
        DimSide::Left => view_box.min.x,
        DimSide::Right => view_box.max.x,
        DimSide::Below => view_box.min.y,
        DimSide::Above => view_box.max.y,
    };
    let with_across = |side: DimSide, along: f64, across: f64| {
        if side.vertical() {
            DVec2::new(across, along)
        } else {
            DVec2::new(along, across)
        }
    };
    // Ordinates.
    for side in DimSide::ALL {
        let mut list: Vec<(DVec2, &str, f64)> = dims
            .ordinates
            .iter()
            .filter(|o| o.side == side)
            .map(|o| (to_sheet(o.at), o.text.as_str(), o.value))
            .collect();
        if list.is_empty() {
            continue;
        }
        let out = side.outward();
        let base = edge(side) + out.dot(DVec2::ONE) * first_offset(h);
        let along = |p: DVec2| if side.vertical() { p.y } else { p.x };
        list.sort_by(|a, b| along(a.0).total_cmp(&along(b.0)));
        let mut last = f64::MIN;
        let lo = list.first().map_or(0.0, |l| along(l.0));
        let hi = list.last().map_or(0.0, |l| along(l.0));
        items.push(Item::Line {
            layer: Layer::Dimension,
            points: vec![with_across(side, lo, base), with_across(side, hi, base)],
            closed: false,
        });
        for (p, text, value) in list {
            let first = items.len();
            let level = along(p);
            let slot = level.max(last + 1.5 * h);
            last = slot;
            // Extension from the feature to the ordinate line, a tick, and a jog to
            // the label when it had to move.
            let start = p + out * 1.5;
            items.push(Item::Line {
                layer: Layer::Dimension,
                points: vec![start, with_across(side, level, base)],
                closed: false,
            });
            let label_at = base + out.dot(DVec2::ONE) * 2.5;
            items.push(Item::Line {
                layer: Layer::Dimension,
                points: vec![
                    with_across(side, level, base),
                    with_across(side, slot, label_at - out.dot(DVec2::ONE) * 0.8),
                ],
                closed: false,
            });
            let w = text_width(text, h);
            let (at, align, rotation, text_box) = match side {
                DimSide::Left => (
                    DVec2::new(label_at, slot - 0.5 * h),
                    Align::End,
                    0.0,
                    Rect::new(
                        DVec2::new(label_at - w, slot - 0.5 * h),
                        DVec2::new(label_at, slot + 0.5 * h),
                    ),
                ),
                DimSide::Right => (
                    DVec2::new(label_at, slot - 0.5 * h),
                    Align::Start,
                    0.0,
                    Rect::new(
                        DVec2::new(label_at, slot - 0.5 * h),
                        DVec2::new(label_at + w, slot + 0.5 * h),
                    ),
                ),
                DimSide::Below => (
                    DVec2::new(slot + 0.5 * h, label_at),
                    Align::End,
                    90.0,
                    Rect::new(
                        DVec2::new(slot - 0.5 * h, label_at - w),
                        DVec2::new(slot + 0.5 * h, label_at),
                    ),
                ),
                DimSide::Above => (
                    DVec2::new(slot + 0.5 * h, label_at),
                    Align::Start,
                    90.0,
                    Rect::new(
                        DVec2::new(slot - 0.5 * h, label_at),
                        DVec2::new(slot + 0.5 * h, label_at + w),
                    ),
                ),
            };
            texts.push(items.len());
            items.push(Item::Text {
                at,
                height: h,
                align,
                rotation,
                text: text.to_string(),
            });
            placed.push(PlacedDimension {
                view,
                text: text.to_string(),
                text_box,
                line_box: Rect::new(
                    with_across(side, level, base),
                    with_across(side, level, base),
                ),
                measure: Measure::Ordinate {
                    feature: p,
                    leader_end: with_across(side, slot, label_at),
                    vertical: side.vertical(),
                    value,
                },
                items: first..items.len(),
            });
        }
    }
    // Linear dimensions.
    let (assigned, _) = pack(dims, h, placement.scale);
    for (d, &t) in dims.linear.iter().zip(&assigned) {
        let first = items.len();
        let s = DimSide::ALL.iter().position(|&x| x == d.side).unwrap_or(0);
        let side = d.side;
        let out = side.outward();
        let sign = out.dot(DVec2::ONE);
        let across = edge(side) + sign * (ord[s] + first_offset(h) + track_spacing(h) * t as f64);
        let (a, b) = (to_sheet(d.a), to_sheet(d.b));
        let along = |p: DVec2| if side.vertical() { p.y } else { p.x };
        let (pa, pb) = (
            with_across(side, along(a), across),
            with_across(side, along(b), across),
        );
        for (f, q) in [(a, pa), (b, pb)] {
            items.push(Item::Line {
                layer: Layer::Dimension,
                points: vec![f + (q - f).normalize_or_zero() * 1.5, q + out * 1.5],
                closed: false,
            });
        }
        items.push(Item::Line {
            layer: Layer::Dimension,
            points: vec![pa, pb],
            closed: false,
        });
        let dir = (pb - pa).normalize_or_zero();
        let len = 0.9 * h;
        items.push(arrow(pa, -dir, len));
        items.push(arrow(pb, dir, len));
        let mid = 0.5 * (along(a) + along(b));
        let w = text_width(&d.text, h);
        let (at, rotation, text_box) = if side.vertical() {
            let x = across - 1.0;
            (
                DVec2::new(x, mid),
                90.0,
                Rect::new(
                    DVec2::new(x - h, mid - 0.5 * w),
                    DVec2::new(x, mid + 0.5 * w),
                ),
            )
        } else {
            let y = across + 1.0;
            (
                DVec2::new(mid, y),
                0.0,
                Rect::new(
                    DVec2::new(mid - 0.5 * w, y),
                    DVec2::new(mid + 0.5 * w, y + h),
                ),
            )
        };
        texts.push(items.len());
        items.push(Item::Text {
            at,
            height: h,
            align: Align::Middle,
            rotation,
            text: d.text.clone(),
        });
        placed.push(PlacedDimension {
            view,
            text: d.text.clone(),
            text_box,
            line_box: Rect::new(pa, pb),
            measure: Measure::Linear {
                a,
                b,
                line: pa,
                vertical: side.vertical(),
                value: (along(d.b) - along(d.a)).abs(),
            },
            items: first..items.len(),
        });
    }
}
