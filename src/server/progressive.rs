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

use std::collections::HashSet;
use std::sync::Arc;

use glam::{DAffine3, DVec3};
use serde_json::{Value, json};

use crate::export::{Scene, SceneNode, SceneNodeKind, ScenePatch, SceneVessel};
use crate::mesh::{Mesh, PackedMesh};

/// A vessel's axis-aligned bounding box in glTF's frame (Y up, metres):
/// `[[min x, y, z], [max x, y, z]]`.
pub type Bounds = [[f64; 3]; 2];

/// The bounding box of each vessel of `scene` (its meshes' vertices through
/// their frames), by tag; a vessel without meshes is left out.
pub fn vessel_bounds(scene: &Scene) -> Vec<(String, Bounds)> {
    plant_boxes(scene)
        .into_iter()
        .map(|(tag, lo, hi)| (tag, to_gltf(lo, hi)))
        .collect()
}

/// The box of each vessel with meshes in the plant frame (Z up, mm):
/// `(tag, min, max)`.
fn plant_boxes(scene: &Scene) -> Vec<(String, DVec3, DVec3)> {
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
            out.push((vessel.tag.clone(), lo, hi));
        }
    }
    out
}

/// The coarse whole a plain viewer of a large plant gets first: each vessel
/// of `scene` as its bounding box, a node `box` under the vessel's node (its
/// frame the identity, the box in plant coordinates; the vessel's extras are
/// `{"coarse": true}`), replaced by the vessel's own node tree when that
/// arrives.
pub fn coarse_scene(scene: &Scene) -> Scene {
    let vessels = plant_boxes(scene)
        .into_iter()
        .map(|(tag, lo, hi)| SceneVessel {
            tag,
            frame: DAffine3::IDENTITY,
            extras: json!({ "coarse": true }),
            nodes: vec![SceneNode {
                id: "box".to_string(),
                kind: SceneNodeKind::Part,
                frame: DAffine3::IDENTITY,
                extras: json!({ "kind": "box" }),
                patches: vec![ScenePatch {
                    name: "box".to_string(),
                    mesh: Arc::new(PackedMesh::pack(&box_mesh(lo, hi))),
                }],
            }],
        })
        .collect();
    Scene { vessels }
}

/// A closed box from `lo` to `hi`: four vertices per face with the face's
/// normal, two counter-clockwise triangles per face seen from outside.
fn box_mesh(lo: DVec3, hi: DVec3) -> Mesh {
    let mut mesh = Mesh::default();
    for axis in 0..3 {
        for side in [-1.0, 1.0] {
            let mut normal = DVec3::ZERO;
            normal[axis] = side;
            // u × v = normal: the face's corners counter-clockwise about it.
            let (u, v) = ((axis + 1) % 3, (axis + 2) % 3);
            let (u, v) = if side > 0.0 { (u, v) } else { (v, u) };
            let base = mesh.positions.len() as u32;
            for (a, b) in [(0, 0), (1, 0), (1, 1), (0, 1)] {
                let mut p = if side > 0.0 { hi } else { lo };
                p[u] = if a == 0 { lo[u] } else { hi[u] };
                p[v] = if b == 0 { lo[v] } else { hi[v] };
                mesh.positions.push(p);
                mesh.normals.push(normal);
            }
            mesh.indices
                .extend([base, base + 1, base + 2, base, base + 2, base + 3]);
        }
    }
    mesh
}

/// About how many bytes [`crate::export::write_glb`] writes for `scene`
/// (`f32` positions and normals, `u32` indices, each distinct mesh once, and
/// a few hundred bytes of JSON per node): what decides whether a plain viewer
/// gets the whole model in its hello, without writing it.
pub fn estimated_glb_bytes(scene: &Scene) -> u64 {
    const JSON_PER_PATCH: u64 = 300;
    const JSON_PER_NODE: u64 = 600;
    let mut seen = HashSet::new();
    let mut bytes = 0u64;
    for vessel in &scene.vessels {
        bytes += JSON_PER_NODE;
        for node in &vessel.nodes {
            bytes += JSON_PER_NODE;
            for patch in &node.patches {
                bytes += JSON_PER_PATCH;
                if seen.insert(Arc::as_ptr(&patch.mesh)) {
                    let m = &patch.mesh;
                    bytes += 24 * m.vertex_count() as u64 + 4 * m.index_count() as u64;
                }
            }
        }
    }
    bytes
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
