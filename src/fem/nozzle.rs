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
    let mut outer = Vec::new();
    let mut corners = Vec::new();
    corners.push(outer.len());
    outer.extend((k0..k1).map(|k| node_at(i0, k)));
    corners.push(outer.len());
    outer.extend((i0..i1).map(|i| node_at(i, k1)));
    corners.push(outer.len());
    outer.extend((k0 + 1..=k1).rev().map(|k| node_at(i1, k)));
    corners.push(outer.len());
    outer.extend((i0 + 1..=i1).rev().map(|i| node_at(i, k0)));
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
    // Ring layers between the curve and the window.
    let first = TAU * r / count as f64;
    let gap = (0..count)
        .map(|j| outer[j].1.distance(curve_uv(phis[j])))
        .sum::<f64>()
        / count as f64;
    // The window's cells: its neighbours outside are about √(width·height).
    let width = TAU * big_r / n as f64;
    let height = (station_z(i1) - station_z(i0)) / bb.max(1) as f64;
    let cell = (width * height).sqrt().min(size);
    let lambdas = grading::layers_at(gap, first, cell, width.max(height).min(size), hole.growth);
    let mut plane: HashMap<usize, DVec2> = HashMap::new();
    for &(id, p) in &outer {
        plane.insert(id, p);
    }
    for (j, &id) in curve.iter().enumerate() {
        plane.insert(id, curve_uv(phis[j]));
    }
    let mut layers = vec![curve.clone()];
    for &lambda in &lambdas[1..lambdas.len() - 1] {
        let row = (0..count)
            .map(|j| {
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
    // The neck, from the curve to its end, graded from the curve's edge length.
    let neck_part = b.mesh.parts.len();
    b.mesh.parts.push(FePart {
        name: format!("{tag}/{}", hole.mark),
        id: hole.mark.clone(),
        thickness: hole.wall,
        offset: 0.0,
    });
    let length = hole.end
        - phis
            .iter()
            .map(|&p| h0(p))
            .fold(f64::NEG_INFINITY, f64::max);
    let vs = grading::layers(length, first, size, size);
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
