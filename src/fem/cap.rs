//! A pole closed with quadrilaterals: an O-grid ("butterfly") cap. An inner
//! m × m grid, its outline rounded towards a circle, is joined to the rim ring
//! of 4m nodes by layers of quads blending the outline into the rim. The cap is
//! laid out in the plane across the axis and lifted onto the exact surface over
//! each point (the point of the piece at that radius), so every corner and
//! mid-side node lies on the surface; no triangle is needed at the pole.

use glam::DVec2;

use super::builder::Builder;

/// Share of the rim radius the inner grid's half-side takes.
const INNER: f64 = 0.45;
/// Blend of the inner grid towards the disk mapping (0: a square, 1: a disk).
const ROUND: f64 = 0.5;

/// The square [-1, 1]² onto the unit disk (the elliptical grid mapping).
fn disk(p: DVec2) -> DVec2 {
    DVec2::new(
        p.x * (1.0 - p.y * p.y / 2.0).sqrt(),
        p.y * (1.0 - p.x * p.x / 2.0).sqrt(),
    )
}

/// Builds the cap of rim radius `rim` whose rim nodes are `ring` (4m of them,
/// node k at angle 2πk/4m). `lift` maps a plane offset from the axis to a point
/// of the surface; `upward`: the outward normal points along +axis (else the
/// element order is reversed). Elements get part `part`.
pub fn cap(
    b: &mut Builder,
    ring: &[usize],
    rim: f64,
    part: usize,
    upward: bool,
    lift: &dyn Fn(DVec2) -> glam::DVec3,
) {
    let n = ring.len();
    let m = n / 4;
    debug_assert!(n.is_multiple_of(8));
    let a = INNER * rim;
    let inner = |i: usize, j: usize| -> DVec2 {
        let u = DVec2::new(
            2.0 * i as f64 / m as f64 - 1.0,
            2.0 * j as f64 / m as f64 - 1.0,
        );
        u * a * (1.0 - ROUND) + disk(u) * a * 1.2 * ROUND
    };
    // Inner grid nodes (the outline included).
    let mut grid = vec![vec![0usize; m + 1]; m + 1];
    for (i, row) in grid.iter_mut().enumerate() {
        for (j, id) in row.iter_mut().enumerate() {
            let p = inner(i, j);
            *id = b.node(lift(p), Some(p));
        }
    }
    // The outline, counter-clockwise from (+a, 0), 4m nodes.
    let mut outline = Vec::with_capacity(n);
    let (h, full) = (m / 2, m);
    for j in h..full {
        outline.push((full, j));
    }
    for i in (1..=full).rev() {
        outline.push((i, full));
    }
    for j in (1..=full).rev() {
        outline.push((0, j));
    }
    for i in 0..full {
        outline.push((i, 0));
    }
    for j in 0..h {
        outline.push((full, j));
    }
    debug_assert_eq!(outline.len(), n);
    let layers = ((1.0 - INNER) * rim / (1.2 * rim / m as f64))
        .round()
        .max(1.0) as usize;
    let mut rows: Vec<Vec<usize>> = vec![outline.iter().map(|&(i, j)| grid[i][j]).collect()];
    for l in 1..layers {
        let lambda = l as f64 / layers as f64;
        let row = outline
            .iter()
            .enumerate()
            .map(|(k, &(i, j))| {
                let theta = std::f64::consts::TAU * k as f64 / n as f64;
                let rimp = DVec2::new(theta.cos(), theta.sin()) * rim;
                let p = inner(i, j) * (1.0 - lambda) + rimp * lambda;
                b.node(lift(p), Some(p))
            })
            .collect();
        rows.push(row);
    }
    rows.push(ring.to_vec());
    let mid = |b: &mut Builder, x: usize, y: usize| {
        let p = 0.5 * (b.plane(x) + b.plane(y));
        b.mid(x, y, || lift(p))
    };
    let quad = |b: &mut Builder, c: [usize; 4]| {
        let c = if upward { c } else { [c[0], c[3], c[2], c[1]] };
        b.quad(part, c, &mut |b, x, y| mid(b, x, y));
    };
    for i in 0..m {
        for j in 0..m {
            quad(
                b,
                [
                    grid[i][j],
                    grid[i + 1][j],
                    grid[i + 1][j + 1],
                    grid[i][j + 1],
                ],
            );
        }
    }
    for l in 0..layers {
        for k in 0..n {
            let k1 = (k + 1) % n;
            quad(
                b,
                [rows[l][k], rows[l + 1][k], rows[l + 1][k1], rows[l][k1]],
            );
        }
    }
}
