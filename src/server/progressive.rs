//! Progressive loading: what a viewer needs to draw the plant before any mesh
//! arrives — each vessel's bounding box — and the per-vessel GLBs it then fetches
//! nearest first.
//!
//! The protocol (with [`super::broadcast`]'s messages): a viewer connecting to
//! `/ws?progressive=1` gets a hello of every stable id and every vessel's box,
//! with no GLB, and draws the boxes at once (the coarse whole). It then asks
//! `GET /vessel.glb?tag=T` for each vessel, ordered by distance from its camera;
//! each answer is the vessel's node tree exactly as in `/model.glb`, with the
//! revision it shows (`x-vesselcad-revision`) and an `ETag` of tag and
//! revision. Deltas stream over the socket as before; a vessel GLB older than a
//! delta that touched the vessel is fetched again.

use glam::DVec3;
use serde_json::{Value, json};

use crate::export::Scene;

/// A vessel's axis-aligned bounding box in glTF's frame (Y up, metres):
/// `[[min x, y, z], [max x, y, z]]`.
pub type Bounds = [[f64; 3]; 2];

/// The bounding box of each vessel of `scene` (its meshes' vertices through
/// their frames), by tag; a vessel without meshes is left out.
pub fn vessel_bounds(scene: &Scene) -> Vec<(String, Bounds)> {
    let mut out = Vec::new();
    for vessel in &scene.vessels {
        let mut lo = DVec3::splat(f64::INFINITY);
        let mut hi = DVec3::splat(f64::NEG_INFINITY);
        for node in &vessel.nodes {
            let frame = vessel.frame * node.frame;
            for patch in &node.patches {
                let Some((a, b)) = patch.mesh.bounds() else {
                    continue;
                };
                for k in 0..8 {
                    let corner = DVec3::new(
                        if k & 1 == 0 { a.x } else { b.x },
                        if k & 2 == 0 { a.y } else { b.y },
                        if k & 4 == 0 { a.z } else { b.z },
                    );
                    let p = frame.transform_point3(corner);
                    lo = lo.min(p);
                    hi = hi.max(p);
                }
            }
        }
        if lo.x <= hi.x {
            out.push((vessel.tag.clone(), to_gltf(lo, hi)));
        }
    }
    out
}

/// A plant box (Z up, mm) in glTF's frame: (x, y, z) → (x, z, −y), metres.
fn to_gltf(lo: DVec3, hi: DVec3) -> Bounds {
    let m = 1e-3;
    [
        [lo.x * m, lo.z * m, -hi.y * m],
        [hi.x * m, hi.z * m, -lo.y * m],
    ]
}

/// The `vessels` list of a progressive hello: `[{"tag", "min", "max"}, …]`.
pub fn bounds_json(bounds: &[(String, Bounds)]) -> Value {
    Value::Array(
        bounds
            .iter()
            .map(|(tag, [min, max])| json!({ "tag": tag, "min": min, "max": max }))
            .collect(),
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_plant_box_turns_y_up_in_metres() {
        let b = to_gltf(
            DVec3::new(0.0, 1000.0, -500.0),
            DVec3::new(2000.0, 3000.0, 500.0),
        );
        assert_eq!(b, [[0.0, -0.5, -3.0], [2.0, 0.5, -1.0]]);
    }
}
