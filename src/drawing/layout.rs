//! Where the four views go on the sheet and at what scale.
//!
//! Each view has its bounds (model mm) and the paper margins its dimensions need
//! round it. The views are tried in two arrangements — third-angle (plan above the
//! elevation, side view right of it, isometric top right) and all four in a row
//! (for tall columns) — and the arrangement that allows the largest standard scale
//! wins. Views are centred in their cells; the leftover space is shared out. A
//! view may be drawn larger than the sheet's scale (a column's plan, which at the
//! elevation's scale would be a few centimetres across): it is laid out at its
//! enlarged size and titled with its own scale.

use glam::DVec2;

use super::sheet::Rect;

/// Paper space a view needs beyond its lines on each side, mm.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Margins {
    /// Left.
    pub left: f64,
    /// Right.
    pub right: f64,
    /// Below.
    pub bottom: f64,
    /// Above.
    pub top: f64,
}

/// The chosen scale and where each view's model origin lands on the sheet.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Placement {
    /// Model mm per paper mm (the `n` of 1:n) of the sheet.
    pub scale: f64,
    /// How much larger than the sheet's scale each view is drawn (1 but for a
    /// plan enlarged to stay legible).
    pub factors: [f64; 4],
    /// Sheet position of each view's model origin:
    /// `paper = offset + model · factor / scale`.
    pub offsets: [DVec2; 4],
}

impl Placement {
    /// Sheet position of view `k`'s model point `p`.
    pub fn to_sheet(self, k: usize, p: DVec2) -> DVec2 {
        self.offsets[k] + p * self.factors[k] / self.scale
    }

    /// The scale (model mm per paper mm) view `k` is drawn at.
    pub fn view_scale(self, k: usize) -> f64 {
        self.scale / self.factors[k]
    }
}

/// The largest standard scale at which `extent` (model mm) spans at least
/// `paper` mm, or 1:1.
pub fn enlarged_scale(extent: f64, paper: f64) -> f64 {
    SCALES
        .iter()
        .rev()
        .copied()
        .find(|&n| extent / n >= paper)
        .unwrap_or(1.0)
}

/// Standard drawing scales 1:n.
const SCALES: [f64; 24] = [
    1.0, 2.0, 2.5, 5.0, 10.0, 15.0, 20.0, 25.0, 30.0, 40.0, 50.0, 60.0, 75.0, 100.0, 125.0, 150.0,
    200.0, 250.0, 300.0, 400.0, 500.0, 750.0, 1000.0, 2000.0,
];

/// Gap between view cells, mm.
const GAP: f64 = 6.0;

/// Arrangements tried, as rows (top first) of view indices in `ViewKind::ALL`
/// order (0 front, 1 top, 2 side, 3 iso).
const ARRANGEMENTS: [&[&[usize]]; 2] = [&[&[1, 3], &[0, 2]], &[&[0, 2, 1, 3]]];

/// Lays out the views `shown` with model `bounds` and paper `margins` in
/// `area`, view `k` drawn `factors[k]` times larger than the sheet's scale (a
/// view not shown takes no room; its offset is meaningless).
pub fn lay_out(
    bounds: &[(DVec2, DVec2); 4],
    margins: &[Margins; 4],
    area: Rect,
    factors: [f64; 4],
    shown: [bool; 4],
) -> Placement {
    let bounds: [(DVec2, DVec2); 4] =
        std::array::from_fn(|k| (bounds[k].0 * factors[k], bounds[k].1 * factors[k]));
    let size = |k: usize| (bounds[k].1 - bounds[k].0).max(DVec2::splat(1.0));
    let arrangements: Vec<Vec<Vec<usize>>> = ARRANGEMENTS
        .iter()
        .map(|rows| {
            rows.iter()
                .map(|r| r.iter().copied().filter(|&k| shown[k]).collect::<Vec<_>>())
                .filter(|r| !r.is_empty())
                .collect()
        })
        .filter(|rows: &Vec<Vec<usize>>| !rows.is_empty())
        .collect();
    let mut best: Option<(f64, &[Vec<usize>])> = None;
    for rows in &arrangements {
        let cols = rows.iter().map(|r| r.len()).max().unwrap_or(1);
        let (mut widths, mut col_margins) = (vec![0.0f64; cols], vec![0.0f64; cols]);
        let (mut heights, mut row_margins) = (vec![0.0f64; rows.len()], vec![0.0f64; rows.len()]);
        for (r, row) in rows.iter().enumerate() {
            for (c, &k) in row.iter().enumerate() {
                widths[c] = widths[c].max(size(k).x);
                col_margins[c] = col_margins[c].max(margins[k].left + margins[k].right);
                heights[r] = heights[r].max(size(k).y);
                row_margins[r] = row_margins[r].max(margins[k].bottom + margins[k].top);
            }
        }
        let fit = |avail: f64, model: &[f64], paper: &[f64]| {
            let free = avail - paper.iter().sum::<f64>() - GAP * (paper.len() as f64 - 1.0);
            free.max(1e-3) / model.iter().sum::<f64>()
        };
        let s = fit(area.size().x, &widths, &col_margins).min(fit(
            area.size().y,
            &heights,
            &row_margins,
        ));
        if best.is_none_or(|(b, _)| s > b) {
            best = Some((s, rows));
        }
    }
    let Some((fit, rows)) = best else {
        return Placement {
            scale: 1.0,
            factors,
            offsets: [DVec2::ZERO; 4],
        };
    };
    let scale = SCALES
        .iter()
        .copied()
        .find(|&n| 1.0 / n <= fit)
        .unwrap_or(1.0 / fit);
    // Cell sizes at the chosen scale, then the grid centred in the area.
    let cols = rows.iter().map(|r| r.len()).max().unwrap_or(1);
    let mut col_w = vec![0.0f64; cols];
    let mut row_h = vec![0.0f64; rows.len()];
    let mut col_left = vec![0.0f64; cols];
    let mut row_bottom = vec![0.0f64; rows.len()];
    for (r, row) in rows.iter().enumerate() {
        for (c, &k) in row.iter().enumerate() {
            let m = margins[k];
            col_w[c] = col_w[c].max(size(k).x / scale + m.left + m.right);
            row_h[r] = row_h[r].max(size(k).y / scale + m.bottom + m.top);
            col_left[c] = col_left[c].max(m.left);
            row_bottom[r] = row_bottom[r].max(m.bottom);
        }
    }
    let total_w: f64 = col_w.iter().sum::<f64>() + GAP * (cols as f64 - 1.0);
    let total_h: f64 = row_h.iter().sum::<f64>() + GAP * (rows.len() as f64 - 1.0);
    let spare = (area.size() - DVec2::new(total_w, total_h)).max(DVec2::ZERO);
    let gap_x = GAP + spare.x / cols as f64;
    let gap_y = GAP + spare.y / rows.len() as f64;
    let mut offsets = [DVec2::ZERO; 4];
    let mut top = area.max.y - 0.5 * (gap_y - GAP);
    for (r, row) in rows.iter().enumerate() {
        let mut left = area.min.x + 0.5 * (gap_x - GAP);
        let cell_bottom = top - row_h[r];
        for (c, &k) in row.iter().enumerate() {
            let m = margins[k];
            let cell = Rect::new(
                DVec2::new(left, cell_bottom),
                DVec2::new(left + col_w[c], top),
            );
            // Centre the view's lines in the cell's inner part.
            let inner_min = cell.min + DVec2::new(m.left, m.bottom);
            let inner_max = cell.max - DVec2::new(m.right, m.top);
            let centre = 0.5 * (inner_min + inner_max);
            let model_centre = 0.5 * (bounds[k].0 + bounds[k].1);
            offsets[k] = centre - model_centre / scale;
            left += col_w[c] + gap_x;
        }
        top = cell_bottom - gap_y;
    }
    Placement {
        scale,
        factors,
        offsets,
    }
}
