//! Detail views: a circle of the front elevation drawn enlarged in a cell of its
//! own sheet, with the elevation's lines clipped to the circle, the linear
//! dimensions that lie wholly inside it and the title `DETAIL A (SCALE 1:10)`;
//! and, on the elevation, the detail's circle and letter.
//!
//! A detail is the elevation's geometry scaled: a model point `p` of the front
//! view lands at `centre + (p − model_centre) / scale` on the detail's sheet.

use glam::DVec2;

use super::data::VesselData;
use super::dimensions::{self, Dimensions, format_mm};
use super::labels::Movable;
use super::layout::Placement;
use super::legibility::DetailSpec;
use super::sheet::{
    Align, DetailMark, DetailView, HiddenLines, Item, Layer, PlacedDimension, Rect,
};
use crate::project::LineKind;

/// The front view's linear dimensions lying wholly inside `spec`'s circle.
fn inside(data: &VesselData, spec: &DetailSpec) -> Dimensions {
    let within = |p: DVec2| (p - spec.centre).length() <= spec.radius * (1.0 - 1e-9);
    Dimensions {
        linear: dimensions::plan(data)
            .linear
            .into_iter()
            .filter(|d| within(d.a) && within(d.b))
            .collect(),
        ordinates: Vec::new(),
    }
}

/// Room for the title under a detail, mm.
fn title_room(h: f64) -> f64 {
    2.8 * h + 2.0
}

/// The size of `spec`'s cell: its circle of paper radius `radius`, the
/// dimensions round it and its title.
pub fn cell_size(data: &VesselData, spec: &DetailSpec, radius: f64, h: f64) -> DVec2 {
    let m = dimensions::margins(&inside(data, spec), h, spec.scale);
    DVec2::new(
        2.0 * radius + m.left + m.right + 4.0,
        2.0 * radius + m.bottom + m.top + title_room(h) + 4.0,
    )
}

/// Draws `spec`'s circle and letter on the elevation placed by `placement`;
/// returns the mark and the letter for the label placer.
pub fn mark(
    spec: &DetailSpec,
    placement: &Placement,
    h: f64,
    items: &mut Vec<Item>,
) -> (DetailMark, Movable) {
    let centre = placement.to_sheet(0, spec.centre);
    let radius = spec.radius / placement.view_scale(0);
    items.push(Item::Circle {
        layer: Layer::Dimension,
        centre,
        radius,
    });
    let movable = Movable {
        item: items.len(),
        target: None,
        outside_views: false,
    };
    items.push(Item::Text {
        at: centre + DVec2::splat(radius * std::f64::consts::FRAC_1_SQRT_2 + 0.8),
        height: h,
        align: Align::Start,
        rotation: 0.0,
        text: spec.label.clone(),
    });
    (
        DetailMark {
            label: spec.label.clone(),
            centre,
            radius,
        },
        movable,
    )
}

/// The parts of polyline `points` inside the circle about `c` of radius `r`.
pub fn clip_to_circle(points: &[DVec2], c: DVec2, r: f64) -> Vec<Vec<DVec2>> {
    let mut out: Vec<Vec<DVec2>> = Vec::new();
    let mut current: Vec<DVec2> = Vec::new();
    for w in points.windows(2) {
        let (a, b) = (w[0], w[1]);
        let d = b - a;
        let f = a - c;
        // |f + t d|² = r²: the parameter interval inside the circle.
        let (qa, qb, qc) = (
            d.length_squared(),
            2.0 * f.dot(d),
            f.length_squared() - r * r,
        );
        let span = if qa < 1e-18 {
            (qc <= 0.0).then_some((0.0, 1.0))
        } else {
            let disc = qb * qb - 4.0 * qa * qc;
            if disc < 0.0 {
                None
            } else {
                let s = disc.sqrt();
                let t0 = ((-qb - s) / (2.0 * qa)).max(0.0);
                let t1 = ((-qb + s) / (2.0 * qa)).min(1.0);
                (t0 < t1).then_some((t0, t1))
            }
        };
        let Some((t0, t1)) = span else {
            if current.len() >= 2 {
                out.push(std::mem::take(&mut current));
            }
            current.clear();
            continue;
        };
        let (p0, p1) = (a + d * t0, a + d * t1);
        if current.last().is_none_or(|&l| (l - p0).length() > 1e-9) {
            if current.len() >= 2 {
                out.push(std::mem::take(&mut current));
            }
            current = vec![p0];
        }
        current.push(p1);
        if t1 < 1.0 {
            out.push(std::mem::take(&mut current));
        }
    }
    if current.len() >= 2 {
        out.push(current);
    }
    out
}

/// Draws `spec` in `cell`: the elevation's lines clipped to its circle (hidden
/// ones unless `hidden` omits them), the circle, its dimensions and title.
/// Returns the view, the dimensions placed and the texts for the label placer.
pub fn draw(
    data: &VesselData,
    spec: &DetailSpec,
    cell: Rect,
    radius: f64,
    hidden: HiddenLines,
    h: f64,
    items: &mut Vec<Item>,
) -> (DetailView, Vec<PlacedDimension>, Vec<Movable>) {
    let dims = inside(data, spec);
    let m = dimensions::margins(&dims, h, spec.scale);
    // The circle centred in the cell's part left by the margins and title.
    let lo = cell.min + DVec2::new(m.left + 2.0, m.bottom + title_room(h) + 2.0);
    let hi = cell.max - DVec2::new(m.right + 2.0, m.top + 2.0);
    let centre = 0.5 * (lo + hi);
    let placement = Placement {
        scale: spec.scale,
        factors: [1.0; 4],
        offsets: [centre - spec.centre / spec.scale; 4],
    };
    for line in data.views[0].entities.iter().flat_map(|e| &e.lines) {
        let layer = match line.kind {
            LineKind::Visible => Layer::Outline,
            LineKind::Hidden if hidden == HiddenLines::Omitted => continue,
            LineKind::Hidden => Layer::Hidden,
            LineKind::Centre => Layer::Centre,
        };
        let on_sheet: Vec<DVec2> = line
            .points
            .iter()
            .map(|&p| placement.to_sheet(0, p))
            .collect();
        for points in clip_to_circle(&on_sheet, centre, radius) {
            items.push(Item::Line {
                layer,
                points,
                closed: false,
            });
        }
    }
    items.push(Item::Circle {
        layer: Layer::Dimension,
        centre,
        radius,
    });
    let view_box = Rect::new(centre - DVec2::splat(radius), centre + DVec2::splat(radius));
    let (mut placed, mut texts) = (Vec::new(), Vec::new());
    dimensions::place(
        &dims,
        0,
        view_box,
        &placement,
        h,
        items,
        &mut placed,
        &mut texts,
    );
    let mut movable: Vec<Movable> = texts
        .iter()
        .map(|&item| Movable {
            item,
            target: None,
            outside_views: true,
        })
        .collect();
    movable.push(Movable {
        item: items.len(),
        target: None,
        outside_views: false,
    });
    items.push(Item::Text {
        at: DVec2::new(centre.x, view_box.min.y - m.bottom - 2.2 * h),
        height: h,
        align: Align::Middle,
        rotation: 0.0,
        text: format!("DETAIL {} (SCALE 1:{})", spec.label, format_mm(spec.scale)),
    });
    (
        DetailView {
            label: spec.label.clone(),
            scale: spec.scale,
            model_centre: spec.centre,
            centre,
            radius,
            nozzles: spec.nozzles.clone(),
            region: cell,
        },
        placed,
        movable,
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn polylines_are_clipped_to_the_circle() {
        let c = DVec2::ZERO;
        // A line through the centre: one piece, from -1 to 1.
        let parts = clip_to_circle(&[DVec2::new(-3.0, 0.0), DVec2::new(3.0, 0.0)], c, 1.0);
        assert_eq!(parts.len(), 1);
        assert!((parts[0][0] - DVec2::new(-1.0, 0.0)).length() < 1e-12);
        assert!((parts[0][1] - DVec2::new(1.0, 0.0)).length() < 1e-12);
        // In, out and in again: two pieces; wholly outside: none.
        let zig = [
            DVec2::new(0.0, 0.0),
            DVec2::new(5.0, 0.0),
            DVec2::new(0.0, 0.5),
        ];
        assert_eq!(clip_to_circle(&zig, c, 1.0).len(), 2);
        assert!(clip_to_circle(&[DVec2::new(2.0, 2.0), DVec2::new(3.0, 2.0)], c, 1.0).is_empty());
        // Wholly inside: kept as it is.
        let inner = [
            DVec2::new(0.1, 0.0),
            DVec2::new(0.2, 0.1),
            DVec2::new(0.3, 0.0),
        ];
        assert_eq!(clip_to_circle(&inner, c, 1.0), vec![inner.to_vec()]);
    }
}
