//! A vertical vessel's skirt as a shell part of the model, so the vessel rests
//! where it really does (the skirt's base on the foundation) rather than on a
//! ring of the envelope. The skirt is coaxial with the vessel, a cylinder or a
//! frustum flared downwards, so its mid-surface is swept on the envelope's
//! circumferential divisions: its top ring *is* the envelope's ring at the
//! skirt's top (the chain is split there so a ring stands exactly at that
//! height, graded as a junction), shared node for node, and its rings run
//! down to the base, graded from the junction's size at the top and at the
//! base (both discontinuities) to the target size between.
//!
//! The shell idealisation at the joint: the skirt's mid-surface is taken
//! through the envelope's ring (radius `r_env`, the bottom part's mid-surface)
//! and keeps its own flare below it, i.e. it is moved radially by the
//! difference of the two mid-surface radii there, (t_skirt − t_env)/2 for a
//! skirt of the course's outside diameter (0 when they are equally thick).
//! The base ring (the bearing plate) is not modelled: the skirt's bottom edge
//! is held in x, y and z (see [`super::conditions`]). The skirt carries no
//! pressure; it carries its own weight under gravity.

use std::f64::consts::TAU;

use glam::DVec3;

use super::builder::Builder;
use super::meridian::{GROWTH, Segment};
use super::{FePart, grading};
use crate::constraints::ResolvedVessel;
use crate::parts::PartGeometry;

/// A skirt of the vessel, in the vessel frame.
#[derive(Clone, Debug, PartialEq)]
pub struct SkirtShell {
    /// Part id.
    pub id: String,
    /// Axial position of its top, vessel frame, mm.
    pub top: f64,
    /// Height from its base to its top, mm.
    pub height: f64,
    /// Change of the mid-surface radius per mm downwards (tan of the flare).
    pub flare: f64,
    /// Plate thickness, mm.
    pub thickness: f64,
}

/// The skirt of `resolved`, if it has one.
pub fn find(resolved: &ResolvedVessel) -> Option<SkirtShell> {
    resolved.parts.iter().find_map(|part| match &part.geometry {
        PartGeometry::Skirt(s) => Some(SkirtShell {
            id: part.id.clone(),
            top: part
                .frame
                .transform_point3(DVec3::new(0.0, 0.0, s.height))
                .z,
            height: s.height,
            flare: s.flare_angle.to_radians().tan(),
            thickness: s.thickness,
        }),
        _ => None,
    })
}

/// Splits the segment of `chain` that crosses axial position `z` (strictly
/// inside its axial range) in two at `z`, so a station ring stands there.
/// Returns whether some segment ends at `z` afterwards.
pub fn split_at(chain: &mut Vec<Segment>, z: f64) -> bool {
    let tol = 1e-9 * z.abs().max(1.0);
    let ends = |s: &Segment| (s.rz(s.s0).y, s.rz(s.s1).y);
    if chain.iter().any(|s| {
        let (a, b) = ends(s);
        (a - z).abs() <= tol || (b - z).abs() <= tol
    }) {
        return true;
    }
    let Some(k) = chain.iter().position(|s| {
        let (a, b) = ends(s);
        a.min(b) < z && z < a.max(b)
    }) else {
        return false;
    };
    let seg = chain[k];
    let s = seg.piece.at_z(z);
    chain[k].s1 = s;
    chain.insert(k + 1, Segment { s0: s, ..seg });
    true
}

/// The envelope's ring a skirt hangs from.
#[derive(Clone, Debug, PartialEq)]
pub struct TopRing {
    /// Corner nodes, node k at angle 2πk/n.
    pub nodes: Vec<usize>,
    /// Centre on the axis, vessel frame.
    pub centre: DVec3,
    /// Mid-surface radius, mm.
    pub radius: f64,
    /// Length of the envelope's elements along the meridian at the ring, mm.
    pub first: f64,
}

/// Meshes `skirt` into `b` below the envelope's ring `top`, with elements of
/// about `size` away from its ends and `top.first` at them; adds the part
/// `TAG/ID` and returns its index and the base ring's corner nodes.
pub fn mesh(
    b: &mut Builder,
    skirt: &SkirtShell,
    top: &TopRing,
    size: f64,
    tag: &str,
) -> (usize, Vec<usize>) {
    let (top_ring, centre, r_env, first) = (&top.nodes, top.centre, top.radius, top.first);
    let n = top_ring.len();
    let part = b.mesh.parts.len();
    b.mesh.parts.push(FePart {
        name: format!("{tag}/{}", skirt.id),
        id: skirt.id.clone(),
        thickness: skirt.thickness,
        offset: 0.0,
    });
    let slant = skirt.height * (1.0 + skirt.flare * skirt.flare).sqrt();
    // Fractions of the height from the top down.
    let lambdas = grading::layers_at(slant, first, first, size, GROWTH);
    let rz = |lambda: f64| {
        let down = lambda * skirt.height;
        (r_env + skirt.flare * down, skirt.top - down)
    };
    let point = |lambda: f64, k: f64| {
        let (r, z) = rz(lambda);
        let (sin, cos) = (TAU * k / n as f64).sin_cos();
        DVec3::new(centre.x + r * cos, centre.y + r * sin, z)
    };
    // Rings from the base (index 0) up to the top (the envelope's ring).
    let count = lambdas.len() - 1;
    let mut rings: Vec<Vec<usize>> = Vec::with_capacity(count + 1);
    let mut level: Vec<f64> = Vec::with_capacity(count + 1);
    for j in 0..count {
        let lambda = lambdas[count - j];
        rings.push(
            (0..n)
                .map(|k| b.node(point(lambda, k as f64), None))
                .collect(),
        );
        level.push(lambda);
    }
    rings.push(top_ring.to_vec());
    level.push(0.0);
    for j in 0..count {
        let (lower, upper) = (level[j], level[j + 1]);
        for k in 0..n {
            let k1 = (k + 1) % n;
            let c = [rings[j][k], rings[j][k1], rings[j + 1][k1], rings[j + 1][k]];
            b.quad(part, c, &mut |b, x, y| {
                let (kx, ky) = (
                    c.iter().position(|&q| q == x).unwrap_or(0),
                    c.iter().position(|&q| q == y).unwrap_or(0),
                );
                let at = |corner: usize| if corner < 2 { lower } else { upper };
                let kk = |corner: usize| if corner == 0 || corner == 3 { k } else { k + 1 };
                if kx / 2 == ky / 2 {
                    // Along a ring.
                    let th = kk(kx).min(kk(ky)) as f64 + 0.5;
                    b.mid(x, y, || point(at(kx), th))
                } else {
                    b.mid(x, y, || point(0.5 * (lower + upper), kk(kx) as f64))
                }
            });
        }
    }
    (part, rings[0].clone())
}
