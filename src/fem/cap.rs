//! A pole closed with quadrilaterals: an O-grid ("butterfly") cap. An inner
//! m × m grid, its outline rounded towards a circle, is joined to the rim ring
//! of 4m nodes by layers of quads blending the outline into the rim, graded
//! ([`super::grading`]) from the outline's spacing to the rim's, then smoothed
//! (Laplacian, the rim fixed) in the plane. The cap is
//! laid out in the plane across the axis and lifted onto the exact surface over
//! each point (the point of the piece at that radius), so every corner and
//! mid-side node lies on the surface; no triangle is needed at the pole.

use std::f64::consts::TAU;

use glam::DVec2;

use super::builder::Builder;

/// Share of the rim radius the inner grid's half-side takes.
const INNER: f64 = 0.45;
/// Blend of the inner grid towards the disk mapping (0: a square, 1: a disk).
const ROUND: f64 = 0.5;
/// Laplacian smoothing sweeps over the cap's nodes.
const SMOOTHING: usize = 30;

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
    // The cap's nodes in the plane: local ids, the rim's last.
    let mut plane: Vec<DVec2> = Vec::new();
    let mut grid = vec![vec![0usize; m + 1]; m + 1];
    for (i, row) in grid.iter_mut().enumerate() {
        for (j, id) in row.iter_mut().enumerate() {
            *id = plane.len();
            plane.push(inner(i, j));
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
    // Layers graded from the outline's spacing to the rim's (the spacing of
    // the ring beyond the rim, which the meridian grades to match).
    let mean = outline
        .iter()
        .map(|&(i, j)| inner(i, j).length())
        .sum::<f64>()
        / n as f64;
    let (first, last) = (TAU * mean / n as f64, TAU * rim / n as f64);
    let lambdas = super::grading::layers(rim - mean, first, last, last);
    let layers = lambdas.len() - 1;
    let rim_at = |k: usize| {
        let theta = TAU * k as f64 / n as f64;
        DVec2::new(theta.cos(), theta.sin()) * rim
    };
    let mut rows: Vec<Vec<usize>> = vec![outline.iter().map(|&(i, j)| grid[i][j]).collect()];
    for &lambda in &lambdas[1..] {
        let row = outline
            .iter()
            .enumerate()
            .map(|(k, &(i, j))| {
                plane.push(inner(i, j) * (1.0 - lambda) + rim_at(k) * lambda);
                plane.len() - 1
            })
            .collect();
        rows.push(row);
    }
    let mut quads: Vec<[usize; 4]> = Vec::new();
    for i in 0..m {
        for j in 0..m {
            quads.push([
                grid[i][j],
                grid[i + 1][j],
                grid[i + 1][j + 1],
                grid[i][j + 1],
            ]);
        }
    }
    for l in 0..layers {
        for k in 0..n {
            let k1 = (k + 1) % n;
            quads.push([rows[l][k], rows[l + 1][k], rows[l + 1][k1], rows[l][k1]]);
        }
    }
    let rim_start = rows[layers][0];
    smooth(&mut plane, &quads, rim_start);
    // Into the builder: the rim is `ring`, the rest lifted onto the surface.
    let ids: Vec<usize> = (0..plane.len())
        .map(|v| {
            if v >= rim_start {
                ring[v - rim_start]
            } else {
                b.node(lift(plane[v]), Some(plane[v]))
            }
        })
        .collect();
    let mid = |b: &mut Builder, x: usize, y: usize| {
        let p = 0.5 * (b.plane(x) + b.plane(y));
        b.mid(x, y, || lift(p))
    };
    for q in quads {
        let c = q.map(|v| ids[v]);
        let c = if upward { c } else { [c[0], c[3], c[2], c[1]] };
        b.quad(part, c, &mut |b, x, y| mid(b, x, y));
    }
}

/// Laplacian smoothing of the plane positions of the nodes below `fixed`
/// (the rim's nodes, from `fixed` on, stay): [`SMOOTHING`] sweeps moving each
/// node to the mean of its edge neighbours, which evens the sizes of the
/// O-grid's corner cells and its layers.
fn smooth(plane: &mut [DVec2], quads: &[[usize; 4]], fixed: usize) {
    let mut neighbours: Vec<Vec<usize>> = vec![Vec::new(); plane.len()];
    for q in quads {
        for k in 0..4 {
            let (x, y) = (q[k], q[(k + 1) % 4]);
            if !neighbours[x].contains(&y) {
                neighbours[x].push(y);
                neighbours[y].push(x);
            }
        }
    }
    for _ in 0..SMOOTHING {
        for v in 0..fixed {
            let around = &neighbours[v];
            if !around.is_empty() {
                plane[v] = around.iter().map(|&w| plane[w]).sum::<DVec2>() / around.len() as f64;
            }
        }
    }
}
