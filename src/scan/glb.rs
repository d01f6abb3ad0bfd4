//! The deviation map as binary glTF: each envelope patch's fitted surface (the
//! design where no points fell) as a grid mesh in the plant frame, with vertex
//! colours from blue (inward) through white to red (outward), written by
//! [`coloured_glb`].

use crate::export::{ColouredMesh, coloured_glb};

use super::envelope::Envelope;
use super::fit::deviation_at;
use super::inspect::Inspection;

/// Grid of each patch's mesh (u × v cells).
const CELLS: (usize, usize) = (96, 24);

/// The colour of a deviation `d` on a scale of ±`scale` mm.
pub fn colour(d: f64, scale: f64) -> [f32; 3] {
    let t = (d / scale).clamp(-1.0, 1.0) as f32;
    if t >= 0.0 {
        [1.0, 1.0 - t, 1.0 - t]
    } else {
        [1.0 + t, 1.0 + t, 1.0]
    }
}

/// The coloured deviation map of an inspection, as GLB bytes; `scale` mm is full
/// colour.
pub fn deviation_glb(envelope: &Envelope, inspection: &Inspection, scale: f64) -> Vec<u8> {
    let scale = if scale > 0.0 { scale } else { 1.0 };
    let (nu, nv) = CELLS;
    let at = |i: usize, j: usize| (i * (nv + 1) + j) as u32;
    let mut meshes = Vec::new();
    for (index, s) in envelope.surfaces.iter().enumerate() {
        if !envelope.parts[s.part].role.is_envelope() {
            continue;
        }
        let design = &s.patch.surface;
        let fit = inspection.fits.get(index).and_then(Option::as_ref);
        let ((u0, u1), (v0, v1)) = design.domain();
        let place = envelope.frame * s.frame;
        let mut mesh = ColouredMesh {
            name: format!("{} {}", envelope.parts[s.part].id, s.patch.name),
            node: format!("{}/{}", envelope.tag, envelope.parts[s.part].id),
            ..Default::default()
        };
        for i in 0..=nu {
            for j in 0..=nv {
                let u = u0 + (u1 - u0) * i as f64 / nu as f64;
                let v = v0 + (v1 - v0) * j as f64 / nv as f64;
                let (p, c) = match fit {
                    Some(f) => (
                        f.surface.point(u, v),
                        colour(deviation_at(design, &f.surface, u, v), scale),
                    ),
                    None => (design.point(u, v), [0.6, 0.6, 0.6]),
                };
                mesh.positions
                    .push(place.transform_point3(p).as_vec3().to_array());
                mesh.colours.push(c);
            }
        }
        for i in 0..nu {
            for j in 0..nv {
                mesh.indices
                    .extend([at(i, j), at(i + 1, j), at(i + 1, j + 1)]);
                mesh.indices
                    .extend([at(i, j), at(i + 1, j + 1), at(i, j + 1)]);
            }
        }
        meshes.push(mesh);
    }
    coloured_glb(&meshes, &envelope.tag, "vesselcad scan", None)
}
