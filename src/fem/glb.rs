//! A solved shell model as binary glTF: the deformed mid-surface (every node
//! moved by its displacement times a stated magnification), one mesh per part
//! named by its set (`V-101/S1`), with the von Mises stress at each node as a
//! vertex colour (`COLOR_0`) on a blue–cyan–green–yellow–red scale from zero to
//! the model's largest value. Quadratic elements are split at their mid-side
//! nodes (an 8-node quad into six triangles, a 6-node triangle into four) so
//! the colours follow the nodal values. Written by [`coloured_glb`]; the
//! magnification and the scale's top are in the
//! asset's extras (`vesselcad_fem`).

use crate::export::{ColouredMesh, coloured_glb};

use super::results::NodeResult;
use super::{ElementKind, FeMesh};

/// Share of the model's largest extent the largest displacement is drawn as.
pub const DRAWN_DISPLACEMENT: f64 = 0.05;

/// The colour of `t` in 0..=1 on the blue–cyan–green–yellow–red scale.
pub fn colour(t: f64) -> [f32; 3] {
    let t = if t.is_finite() {
        t.clamp(0.0, 1.0)
    } else {
        0.0
    };
    let stops = [
        [0.0, 0.0, 1.0],
        [0.0, 1.0, 1.0],
        [0.0, 1.0, 0.0],
        [1.0, 1.0, 0.0],
        [1.0, 0.0, 0.0],
    ];
    let x = t * 4.0;
    let k = (x.floor() as usize).min(3);
    let f = x - k as f64;
    let (a, b) = (stops[k], stops[k + 1]);
    [0, 1, 2].map(|i| (a[i] + (b[i] - a[i]) * f) as f32)
}

/// The magnification that draws the largest displacement of `results` as
/// [`DRAWN_DISPLACEMENT`] of the model's largest extent (1 when nothing moves).
pub fn magnification(mesh: &FeMesh, results: &[NodeResult]) -> f64 {
    let (lo, hi) = mesh.nodes.iter().fold(
        (
            glam::DVec3::splat(f64::INFINITY),
            glam::DVec3::splat(f64::NEG_INFINITY),
        ),
        |(lo, hi), &p| (lo.min(p), hi.max(p)),
    );
    let extent = (hi - lo).max_element();
    let umax = results
        .iter()
        .map(|r| r.displacement.length())
        .fold(0.0, f64::max);
    if umax > 0.0 && extent.is_finite() {
        DRAWN_DISPLACEMENT * extent / umax
    } else {
        1.0
    }
}

/// The triangles of one element, as node indices, following its orientation.
fn triangles(kind: ElementKind, n: &[usize]) -> Vec<[usize; 3]> {
    match kind {
        ElementKind::Quad4 => vec![[n[0], n[1], n[2]], [n[0], n[2], n[3]]],
        ElementKind::Tri3 => vec![[n[0], n[1], n[2]]],
        ElementKind::Quad8 => vec![
            [n[0], n[4], n[7]],
            [n[1], n[5], n[4]],
            [n[2], n[6], n[5]],
            [n[3], n[7], n[6]],
            [n[4], n[5], n[6]],
            [n[4], n[6], n[7]],
        ],
        ElementKind::Tri6 => vec![
            [n[0], n[3], n[5]],
            [n[1], n[4], n[3]],
            [n[2], n[5], n[4]],
            [n[3], n[4], n[5]],
        ],
    }
}

/// The deformed model `mesh` with `results` (one per node) as GLB bytes, named
/// `tag`.
pub fn von_mises_glb(mesh: &FeMesh, results: &[NodeResult], tag: &str) -> Vec<u8> {
    let scale = magnification(mesh, results);
    let top_stress = results.iter().map(|r| r.von_mises).fold(0.0, f64::max);
    let meshes: Vec<ColouredMesh> = mesh
        .parts
        .iter()
        .enumerate()
        .map(|(k, part)| {
            // This part's nodes, renumbered.
            let mut local: std::collections::HashMap<usize, u32> = Default::default();
            let mut out = ColouredMesh {
                name: part.name.clone(),
                node: part.name.clone(),
                ..Default::default()
            };
            for el in mesh.elements.iter().filter(|e| e.part == k) {
                for tri in triangles(el.kind, &el.nodes) {
                    for n in tri {
                        let next = local.len() as u32;
                        let id = *local.entry(n).or_insert_with(|| {
                            let r = results.get(n).copied().unwrap_or_default();
                            out.positions.push(
                                (mesh.nodes[n] + r.displacement * scale)
                                    .as_vec3()
                                    .to_array(),
                            );
                            let t = if top_stress > 0.0 {
                                r.von_mises / top_stress
                            } else {
                                0.0
                            };
                            out.colours.push(colour(t));
                            next
                        });
                        out.indices.push(id);
                    }
                }
            }
            out
        })
        .collect();
    let extras = serde_json::json!({
        "vesselcad_fem": {
            "displacement_magnification": scale,
            "von_mises_max_mpa": top_stress,
            "colours": "blue 0 MPa, cyan, green, yellow, red at von_mises_max_mpa",
        }
    });
    coloured_glb(&meshes, tag, "vesselcad fem", Some(extras))
}
