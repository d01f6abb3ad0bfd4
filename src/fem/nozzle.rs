//! A nozzle on a cylindrical course (radial, hillside, tangential or inclined)
//! or off the centre of a head, meshed conforming with its host: the window of [`super::window`] is filled
//! by a ring of quadrilaterals from the window's boundary (the course's own
//! nodes) to the exact intersection curve of the neck's and the course's
//! mid-surfaces, and the neck is swept from that curve to its end (the flange's
//! back, a plane across the nozzle axis) in rings sharing the curve's nodes.
//!
//! The ring is laid out on the course unrolled, `(u, z) = (R·Δθ, Δz)` about the
//! point where the nozzle axis meets the course, which maps exactly onto the
//! cylinder (on a head, the chart `(ρ·Δθ, Δσ)` of [`super::head_window`]); the curve's nodes are at neck angles φ whose unrolled polar
//! angles spread evenly over each side of the window, between the polar angles
//! of its corners. The ring's layers blend the curve into the window
//! boundary, graded ([`super::grading`]) from the curve's edge length to the
//! window's cells. Every corner and mid-side node is an exact point of its surface:
//! ring nodes of the cylinder, curve nodes (and the mid-side nodes between
//! them) of the intersection, neck nodes of the neck cylinder.
//!
//! Pads are a thicker shell region: the course's elements whose centroid is
//! within the pad's radius of the nozzle axis become the part `TAG/MARK/pad`
//! with the course's plus the pad's thickness (the mid-surface is not shifted
//! for the pad). The neck is the part `TAG/MARK` with the pipe's wall.

use std::collections::HashMap;
use std::f64::consts::TAU;

use glam::{DVec2, DVec3};

use super::builder::Builder;
use super::grading;
use super::meridian::Meridian;
use super::window::Hole;
use super::{FePart, NeckEnd};

/// Neck angle φ at the mid-point of nodes with angles `a` and `b` (the short way).
fn mid_angle(a: f64, b: f64) -> f64 {
    let d = (b - a + std::f64::consts::PI).rem_euclid(TAU) - std::f64::consts::PI;
    a + 0.5 * d
}

/// Meshes nozzle `hole` into `b`: the ring over its window (whose boundary
/// nodes are `rings[station][division]`) and the neck. Returns the neck's end.
pub fn mesh(
    b: &mut Builder,
    hole: &Hole,
    mer: &Meridian,
    rings: &[Vec<usize>],
    size: f64,
    tag: &str,
) -> NeckEnd {
    let n = rings[hole.i0].len();
    let (big_r, r) = (hole.big_r, hole.r);
    // The window's chart about the opening's centre → the host's surface.
    let on_course = |p: DVec2| hole.surface(mer, p);
    // The neck at angle φ, t along its axis; where it meets the course.
    let on_neck = |phi: f64, t: f64| hole.on_neck(phi, t);
    let h0 = |phi: f64| hole.meet(phi).unwrap_or(0.0);
    let curve_uv = |phi: f64| hole.curve_uv(phi);
    // The window boundary, counter-clockwise in (u, v) from its lower-left corner.
    let station_z = |i: usize| hole.station_v(mer, i);
    let node_at = |i: usize, k: i64| {
        let id = rings[i][k.rem_euclid(n as i64) as usize];
        let u = big_r * (TAU * k as f64 / n as f64 - hole.theta);
        (id, DVec2::new(u, station_z(i)))
    };
    let (a, bb) = (hole.a as i64, hole.i1 - hole.i0);
    let (k0, k1, i0, i1) = (hole.k0, hole.k0 + a, hole.i0, hole.i1);
    // Each boundary edge's cell beyond the window (its corner nodes), `None`
    // past the envelope's first or last station (a cap's rim).
    let cell = |i: usize, k: i64| {
        let k1 = k + 1;
        let at = |i: usize, k: i64| rings[i][k.rem_euclid(n as i64) as usize];
        [at(i, k), at(i, k1), at(i + 1, k1), at(i + 1, k)]
    };
    let last_station = rings.len() - 1;
    let mut outer = Vec::new();
    let mut beyond: Vec<Option<[usize; 4]>> = Vec::new();
    let mut corners = Vec::new();
    corners.push(outer.len());
    outer.extend((k0..k1).map(|k| node_at(i0, k)));
    beyond.extend((k0..k1).map(|k| (i0 > 0).then(|| cell(i0 - 1, k))));
    corners.push(outer.len());
    outer.extend((i0..i1).map(|i| node_at(i, k1)));
    beyond.extend((i0..i1).map(|i| Some(cell(i, k1))));
    corners.push(outer.len());
    outer.extend((k0 + 1..=k1).rev().map(|k| node_at(i1, k)));
    beyond.extend(
        (k0 + 1..=k1)
            .rev()
            .map(|k| (i1 < last_station).then(|| cell(i1, k - 1))),
    );
    corners.push(outer.len());
    outer.extend((i0 + 1..=i1).rev().map(|i| node_at(i, k0)));
    beyond.extend((i0 + 1..=i1).rev().map(|i| Some(cell(i - 1, k0 - 1))));
    let count = outer.len();
    debug_assert_eq!(count, 2 * (a as usize + bb));
    // Neck angles: each side's share of the curve between its corners' polar angles.
    let mut psi: Vec<f64> = corners
        .iter()
        .map(|&c| outer[c].1.y.atan2(outer[c].1.x))
        .collect();
    for k in 1..4 {
        while psi[k] < psi[k - 1] {
            psi[k] += TAU;
        }
    }
    psi.push(psi[0] + TAU);
    corners.push(count);
    let targets: Vec<f64> = (0..count)
        .map(|j| {
            let s = (0..4).rfind(|&s| corners[s] <= j).unwrap_or(0);
            let f = (j - corners[s]) as f64 / (corners[s + 1] - corners[s]) as f64;
            psi[s] + f * (psi[s + 1] - psi[s])
        })
        .collect();
    // Checked by the window's plan: the opening is star-shaped about its centre.
    let phis = super::window::phis_at(hole, &targets).unwrap_or(targets);
    let mut angle: HashMap<usize, f64> = HashMap::new();
    let curve: Vec<usize> = phis
        .iter()
        .map(|&phi| {
            let id = b.node(on_neck(phi, h0(phi)), None);
            angle.insert(id, phi);
            id
        })
        .collect();
    // The neck's rows, from the curve to its end, graded from the curve's
    // mean edge length.
    let first = TAU * r / count as f64;
    let length = hole.end
        - phis
            .iter()
            .map(|&p| h0(p))
            .fold(f64::NEG_INFINITY, f64::max);
    let vs = grading::layers(length, first, size, size);
    // Ring layers between the curve and the window, ray by ray (curve node j
    // to boundary node j), in one count: each ray graded from the neck's first
    // row there to the thickness that gives its outer element the area of the
    // cell beyond the window's edge, so the ring meets the neck and every
    // cell round the window at sizes near theirs (a window cut short by its
    // host's end, or on a head whose rows grow, has rays of very different
    // lengths and cells of different heights round it).
    let nodes = |b: &Builder, id: usize| b.mesh.nodes[id];
    let outer_edge =
        |b: &Builder, j: usize| nodes(b, outer[j].0).distance(nodes(b, outer[(j + 1) % count].0));
    let beyond_area = |b: &Builder, j: usize| match beyond[j] {
        Some(c) => {
            let p = c.map(|id| nodes(b, id));
            0.5 * (p[2] - p[0]).cross(p[3] - p[1]).length()
        }
        None => outer_edge(b, j).powi(2),
    };
    let beyond_t: Vec<f64> = (0..count)
        .map(|j| beyond_area(b, j) / outer_edge(b, j).max(1e-12))
        .collect();
    let rays: Vec<(f64, f64, f64)> = (0..count)
        .map(|j| {
            let gap = outer[j].1.distance(curve_uv(phis[j]));
            let inner = vs[1] * (hole.end - h0(phis[j]));
            let last = 0.5 * (beyond_t[(j + count - 1) % count] + beyond_t[j]);
            (gap, inner, last.min(size))
        })
        .collect();
    let ray_rows: Vec<f64> = rays
        .iter()
        .map(|&(gap, inner, last)| grading::rows(gap, inner, last, size, hole.growth))
        .collect();
    // The neck's first row of elements: their sizes (√area), against which
    // the ring's first layer is weighed.
    let neck_sizes: Vec<f64> = (0..count)
        .map(|j| {
            let j1 = (j + 1) % count;
            let at =
                |j: usize, v: f64| on_neck(phis[j], h0(phis[j]) + v * (hole.end - h0(phis[j])));
            let p = [at(j, 0.0), at(j1, 0.0), at(j1, vs[1]), at(j, vs[1])];
            (0.5 * (p[2] - p[0]).cross(p[3] - p[1]).length()).sqrt()
        })
        .collect();
    let beyond_sizes: Vec<Option<f64>> = (0..count)
        .map(|j| beyond[j].is_some().then(|| beyond_area(b, j).sqrt()))
        .collect();
    let starts: Vec<DVec2> = phis.iter().map(|&phi| curve_uv(phi)).collect();
    let ends: Vec<DVec2> = outer.iter().map(|o| o.1).collect();
    let worst =
        |lambdas: &[Vec<f64>]| worst_ratio(&starts, &ends, lambdas, &neck_sizes, &beyond_sizes);
    // Candidates: one layer spacing for every ray from the rays' mean length
    // (the window's cells' mean size at its edge), and each count between
    // the shortest and the longest ray's rows ray by ray; the one whose
    // worst neighbour ratio (in the chart, against the neck's first row and
    // the cells beyond the window) is least.
    let mean_gap = rays.iter().map(|r| r.0).sum::<f64>() / count as f64;
    let width = TAU * big_r / n as f64;
    let height = (station_z(i1) - station_z(i0)) / bb.max(1) as f64;
    let cell_size = (width * height).sqrt().min(size);
    let common = grading::layers_at(
        mean_gap,
        first,
        cell_size,
        width.max(height).min(size),
        hole.growth,
    );
    let mut best = vec![common; count];
    let mut best_worst = worst(&best);
    let lo = ray_rows.iter().copied().fold(f64::INFINITY, f64::min);
    let hi = ray_rows.iter().copied().fold(0.0, f64::max);
    let (lo, hi) = (
        lo.floor().max(1.0) as usize,
        (hi.ceil() as usize + 1).min(64),
    );
    for layer_count in lo..=hi.max(lo) {
        let lambdas: Vec<Vec<f64>> = rays
            .iter()
            .map(|&(gap, inner, last)| {
                grading::layers_count(gap, inner, last, size, hole.growth, layer_count)
            })
            .collect();
        let w = worst(&lambdas);
        if w < best_worst {
            (best, best_worst) = (lambdas, w);
        }
    }
    let lambdas = best;
    let layer_count = lambdas[0].len() - 1;
    let mut plane: HashMap<usize, DVec2> = HashMap::new();
    for &(id, p) in &outer {
        plane.insert(id, p);
    }
    for (j, &id) in curve.iter().enumerate() {
        plane.insert(id, curve_uv(phis[j]));
    }
    let mut layers = vec![curve.clone()];
    #[expect(clippy::needless_range_loop, reason = "`l` picks each ray's layer")]
    for l in 1..layer_count {
        let row = (0..count)
            .map(|j| {
                let lambda = lambdas[j][l];
                let p = curve_uv(phis[j]) * (1.0 - lambda) + outer[j].1 * lambda;
                let id = b.node(on_course(p), None);
                plane.insert(id, p);
                id
            })
            .collect();
        layers.push(row);
    }
    layers.push(outer.iter().map(|o| o.0).collect());
    let part = hole.part;
    for l in 0..layers.len() - 1 {
        for j in 0..count {
            let j1 = (j + 1) % count;
            let c = [
                layers[l][j],
                layers[l + 1][j],
                layers[l + 1][j1],
                layers[l][j1],
            ];
            b.quad(
                part,
                c,
                &mut |b, x, y| match (angle.get(&x), angle.get(&y)) {
                    (Some(&p), Some(&q)) => {
                        let phi = mid_angle(p, q);
                        b.mid(x, y, || on_neck(phi, h0(phi)))
                    }
                    _ => {
                        let p = 0.5 * (plane[&x] + plane[&y]);
                        b.mid(x, y, || on_course(p))
                    }
                },
            );
        }
    }
    // The neck, from the curve to its end.
    let neck_part = b.mesh.parts.len();
    b.mesh.parts.push(FePart {
        name: format!("{tag}/{}", hole.mark),
        id: hole.mark.clone(),
        thickness: hole.wall,
        offset: 0.0,
    });
    let mut at: HashMap<usize, (f64, f64)> = HashMap::new();
    for (j, &id) in curve.iter().enumerate() {
        at.insert(id, (phis[j], 0.0));
    }
    let h = |phi: f64, v: f64| h0(phi) + v * (hole.end - h0(phi));
    let mut rows = vec![curve.clone()];
    for &v in &vs[1..] {
        let row = phis
            .iter()
            .map(|&phi| {
                let id = b.node(on_neck(phi, h(phi, v)), None);
                at.insert(id, (phi, v));
                id
            })
            .collect();
        rows.push(row);
    }
    for m in 0..rows.len() - 1 {
        for j in 0..count {
            let j1 = (j + 1) % count;
            let c = [rows[m][j], rows[m][j1], rows[m + 1][j1], rows[m + 1][j]];
            b.quad(neck_part, c, &mut |b, x, y| {
                let ((p, v), (q, w)) = (at[&x], at[&y]);
                let phi = mid_angle(p, q);
                let v = 0.5 * (v + w);
                b.mid(x, y, || on_neck(phi, h(phi, v)))
            });
        }
    }
    let end = rows[rows.len() - 1].clone();
    let mids = if b.quadratic {
        (0..count)
            .map(|j| {
                let (x, y) = (end[j], end[(j + 1) % count]);
                b.mid(x, y, || hole.origin)
            })
            .collect()
    } else {
        Vec::new()
    };
    b.mesh.boundary.extend(end.iter().copied());
    NeckEnd {
        mark: hole.mark.clone(),
        part: neck_part,
        nodes: end,
        mids,
        centre: hole.origin + hole.axis * hole.end,
        axis: hole.axis,
        radius: hole.r,
    }
}

/// The largest size ratio (√area) of two neighbours among a ring's
/// elements laid out in the chart (ray j from `starts[j]` to `ends[j]`, its
/// layer boundaries at fractions `lambdas[j]`), the neck's first row
/// (`neck[j]` against the ring's first layer) and the cells beyond the
/// window (`beyond[j]` against its last layer); infinite when an element
/// folds over.
fn worst_ratio(
    starts: &[DVec2],
    ends: &[DVec2],
    lambdas: &[Vec<f64>],
    neck: &[f64],
    beyond: &[Option<f64>],
) -> f64 {
    let count = starts.len();
    let layers = lambdas[0].len() - 1;
    let at = |l: usize, j: usize| starts[j].lerp(ends[j], lambdas[j][l]);
    let signed = |l: usize, j: usize| {
        let j1 = (j + 1) % count;
        let p = [at(l, j), at(l + 1, j), at(l + 1, j1), at(l, j1)];
        0.5 * (p[2] - p[0]).perp_dot(p[3] - p[1])
    };
    let sign = signed(0, 0).signum();
    let mut size = vec![vec![0.0; count]; layers];
    for (l, row) in size.iter_mut().enumerate() {
        for (j, s) in row.iter_mut().enumerate() {
            let a = signed(l, j) * sign;
            if a <= 0.0 {
                return f64::INFINITY;
            }
            *s = a.sqrt();
        }
    }
    let ratio = |x: f64, y: f64| x.max(y) / x.min(y).max(1e-300);
    let mut worst = 1.0f64;
    for l in 0..layers {
        for j in 0..count {
            worst = worst.max(ratio(size[l][j], size[l][(j + 1) % count]));
            if l + 1 < layers {
                worst = worst.max(ratio(size[l][j], size[l + 1][j]));
            }
        }
    }
    for j in 0..count {
        worst = worst.max(ratio(size[0][j], neck[j]));
        if let Some(c) = beyond[j] {
            worst = worst.max(ratio(size[layers - 1][j], c));
        }
    }
    worst
}

/// Where a pad sits: the nozzle, its host part, and its axis.
#[derive(Clone, Debug, PartialEq)]
pub struct PadSite {
    /// Nozzle mark.
    pub mark: String,
    /// FE part index of the host.
    pub part: usize,
    /// A point of the nozzle axis inside the vessel.
    pub origin: DVec3,
    /// Unit nozzle axis, outwards.
    pub axis: DVec3,
    /// Pad (outside diameter, thickness), mm.
    pub pad: (f64, f64),
}

impl Hole {
    /// The pad's site, if the nozzle has a pad.
    pub fn pad_site(&self) -> Option<PadSite> {
        self.pad.map(|pad| PadSite {
            mark: self.mark.clone(),
            part: self.part,
            origin: self.origin,
            axis: self.axis,
            pad,
        })
    }
}

/// Moves the host elements under each pad of `sites` (those in front of the
/// axis's origin whose corners' centroid is within the pad's radius of the
/// axis) into a pad part `TAG/MARK/pad`, with the host's plus the pad's
/// thickness.
pub fn pads(b: &mut Builder, sites: &[PadSite], tag: &str) {
    for site in sites {
        let (od, t) = site.pad;
        let host = b.mesh.parts[site.part].thickness;
        let pad = b.mesh.parts.len();
        b.mesh.parts.push(FePart {
            name: format!("{tag}/{}/pad", site.mark),
            id: format!("{}/pad", site.mark),
            thickness: host + t,
            offset: 0.0,
        });
        let (o, d) = (site.origin, site.axis);
        let nodes = &b.mesh.nodes;
        for e in b.mesh.elements.iter_mut().filter(|e| e.part == site.part) {
            let nc = e.kind.corners();
            let c = e.nodes[..nc].iter().map(|&i| nodes[i]).sum::<DVec3>() / nc as f64;
            let rel = c - o;
            let off = rel - d * rel.dot(d);
            if rel.dot(d) > 0.0 && off.length() <= 0.5 * od {
                e.part = pad;
            }
        }
    }
}
