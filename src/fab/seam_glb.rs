//! Seams in the main GLB: every longitudinal and circumferential seam of a
//! vessel's plan as a node with one `LINES` primitive, under the vessel's
//! node (vessel frame, metres), so the seams sit on the vessel as drawn.
//!
//! Seams are the plan's welds of kind long seam and circumferential seam, on
//! the vessel's outside surface: a long seam is the straight generatrix of its
//! course (two points, exact); a circumferential seam is its circle at the
//! outside radius of the thinner part at the joint (the rolled part's exact
//! outside at that height where it is rolled, else mid radius plus half the
//! thickness: the cylindrical end of a head), as a regular polygon whose
//! vertices are on the circle and whose chords stay within the tolerance.
//!
//! Extras per seam node: `{id, kind: "seam", category, weld_kind, joins,
//! operation, level}` (the operation that welds it and its level). The lines
//! are added to a finished GLB ([`add_seams`]): the JSON gains a material,
//! accessors, views, meshes and nodes, the `BIN` chunk the positions.

use std::f64::consts::PI;

use glam::{DAffine3, DVec3};
use serde_json::{Value, json};

use super::process::ProcessPlan;
use super::vessel_plan::FabPlan;
use super::weld_glb::operation_kind;
use super::welds::{Weld, WeldKind};

/// One seam as lines.
#[derive(Clone, Debug, PartialEq)]
pub struct SeamLine {
    /// The weld id (`L-…`, `C-…`).
    pub id: String,
    /// Segments' end points, pairs in order (glTF `LINES`), vessel frame, mm.
    pub points: Vec<DVec3>,
    /// The node's extras.
    pub extras: Value,
}

/// The seams of the vessel planned as `fab` with process plan `plan`, within
/// chordal `tolerance` (mm) of their exact curves.
pub fn seam_lines(fab: &FabPlan, plan: &ProcessPlan, tolerance: f64) -> Vec<SeamLine> {
    plan.welds
        .iter()
        .filter(|w| matches!(w.kind, WeldKind::LongSeam | WeldKind::CircSeam))
        .filter_map(|w| {
            let points = match w.kind {
                WeldKind::CircSeam => circ_points(fab, w, tolerance)?,
                _ => w.path.get(..2)?.to_vec(),
            };
            let op = format!("{}:{}", operation_kind(w.kind), w.item);
            let level = plan.operations.iter().find(|o| o.id == op).map(|o| o.level);
            Some(SeamLine {
                id: w.id.clone(),
                points,
                extras: json!({
                    "id": w.id,
                    "kind": "seam",
                    "weld_kind": w.kind,
                    "category": w.category.map(|c| format!("{c:?}")),
                    "joins": w.joins,
                    "length_mm": w.length,
                    "operation": level.map(|_| op),
                    "level": level,
                }),
            })
        })
        .collect()
}

/// A circumferential seam's circle (from its weld ring at mid radius) at the
/// outside radius, as segment pairs within `tolerance`.
fn circ_points(fab: &FabPlan, w: &Weld, tolerance: f64) -> Option<Vec<DVec3>> {
    let ring = &w.path;
    let n = ring.len();
    if n < 3 {
        return None;
    }
    let centre = ring.iter().copied().sum::<DVec3>() / n as f64;
    let u = ring[0] - centre;
    let axis = u.cross(ring[n / 4] - centre).try_normalize()?;
    let mid = u.length();
    let outside = fab
        .developments
        .rolled
        .iter()
        .filter(|r| w.joins.contains(&r.id) && r.thickness == w.thickness)
        .find_map(|r| {
            let local = r.frame.inverse().transform_point3(centre);
            let (z0, z1) = (r.z.0.min(r.z.1), r.z.0.max(r.z.1));
            let inside = local.z >= z0 - 1e-6 && local.z <= z1 + 1e-6;
            (inside && (r.radius_at(local.z) - mid).abs() <= 1e-6).then(|| r.outside_at(local.z))
        })
        .unwrap_or(mid + 0.5 * w.thickness);
    let frame = DAffine3::from_cols(
        u.normalize() * outside,
        axis.cross(u.normalize()) * outside,
        axis,
        centre,
    );
    let sag = (tolerance / outside).clamp(1e-12, 1.0);
    let segments = ((PI / (1.0 - sag).acos()).ceil() as usize).max(8);
    let at = |k: usize| {
        let a = 2.0 * PI * k as f64 / segments as f64;
        frame.transform_point3(DVec3::new(a.cos(), a.sin(), 0.0))
    };
    Some(
        (0..segments)
            .flat_map(|k| [at(k), at((k + 1) % segments)])
            .collect(),
    )
}

/// Why seams could not be added to a GLB.
#[derive(Debug, thiserror::Error)]
pub enum SeamGlbError {
    /// The bytes are not a GLB this writer made.
    #[error("not a binary glTF file: {0}")]
    NotGlb(&'static str),
    /// The JSON chunk cannot be read or written.
    #[error("the GLB's JSON chunk: {0}")]
    Json(#[from] serde_json::Error),
    /// Past the format's 4 GiB.
    #[error("the GLB would be larger than 4 GiB")]
    TooLarge,
}

/// `glb` with `seams` (vessel tag, its seams) added as line nodes under the
/// vessel nodes of the same name (seams of a vessel not in the file are left
/// out).
///
/// # Errors
///
/// [`SeamGlbError`] for bytes that are not a GLB.
pub fn add_seams(glb: &[u8], seams: &[(String, Vec<SeamLine>)]) -> Result<Vec<u8>, SeamGlbError> {
    let (mut doc, mut bin) = split(glb)?;
    let vessels: Vec<(usize, String)> = doc["nodes"]
        .as_array()
        .into_iter()
        .flatten()
        .enumerate()
        .filter_map(|(i, n)| Some((i, n["name"].as_str()?.to_string())))
        .collect();
    let mut material = None;
    for (tag, lines) in seams {
        // The vessel nodes are the plant node's children.
        let plant = doc["scenes"][0]["nodes"][0].as_u64().unwrap_or(0) as usize;
        let plant_children: Vec<usize> = doc["nodes"][plant]["children"]
            .as_array()
            .into_iter()
            .flatten()
            .filter_map(Value::as_u64)
            .map(|i| i as usize)
            .collect();
        let Some(&(vessel, _)) = vessels
            .iter()
            .find(|(i, name)| name == tag && plant_children.contains(i))
        else {
            continue;
        };
        for line in lines.iter().filter(|l| l.points.len() >= 2) {
            let material = *material.get_or_insert_with(|| {
                push(
                    &mut doc,
                    "materials",
                    json!({
                        "name": "seam",
                        "pbrMetallicRoughness": {
                            "baseColorFactor": [0.9, 0.1, 0.6, 1.0],
                            "metallicFactor": 0.0
                        }
                    }),
                )
            });
            let points: Vec<[f32; 3]> = line
                .points
                .iter()
                .map(|p| (*p * 1e-3).as_vec3().to_array())
                .collect();
            let (mut min, mut max) = ([f32::MAX; 3], [f32::MIN; 3]);
            let offset = bin.len().div_ceil(4) * 4;
            bin.resize(offset, 0);
            for p in &points {
                for (k, c) in p.iter().enumerate() {
                    min[k] = min[k].min(*c);
                    max[k] = max[k].max(*c);
                    bin.extend_from_slice(&c.to_le_bytes());
                }
            }
            let view = push(
                &mut doc,
                "bufferViews",
                json!({"buffer": 0, "byteOffset": offset, "byteLength": points.len() * 12, "target": 34962}),
            );
            let accessor = push(
                &mut doc,
                "accessors",
                json!({"bufferView": view, "componentType": 5126, "count": points.len(),
                       "type": "VEC3", "min": min, "max": max}),
            );
            let mesh = push(
                &mut doc,
                "meshes",
                json!({"name": format!("{tag}/seam {}", line.id),
                       "primitives": [{"attributes": {"POSITION": accessor},
                                       "material": material, "mode": 1}]}),
            );
            let node = push(
                &mut doc,
                "nodes",
                json!({"name": format!("seam {}", line.id), "mesh": mesh, "extras": line.extras}),
            );
            let children = &mut doc["nodes"][vessel]["children"];
            match children.as_array_mut() {
                Some(c) => c.push(json!(node)),
                None => *children = json!([node]),
            }
        }
    }
    if !bin.is_empty() {
        match doc["buffers"].as_array_mut().and_then(|b| b.first_mut()) {
            Some(b) => b["byteLength"] = json!(bin.len()),
            None => doc["buffers"] = json!([{"byteLength": bin.len()}]),
        }
    }
    crate::export::glb_container(&serde_json::to_vec(&doc)?, &bin)
        .map_err(|_| SeamGlbError::TooLarge)
}

/// Appends `value` to the array `key` of `doc`; returns its index.
fn push(doc: &mut Value, key: &str, value: Value) -> usize {
    let array = &mut doc[key];
    if !array.is_array() {
        *array = json!([]);
    }
    let a = array.as_array_mut().expect("an array was just put here");
    a.push(value);
    a.len() - 1
}

/// The JSON document and the `BIN` chunk's bytes (empty when absent).
fn split(glb: &[u8]) -> Result<(Value, Vec<u8>), SeamGlbError> {
    let word = |at: usize| -> Result<usize, SeamGlbError> {
        glb.get(at..at + 4)
            .map(|b| u32::from_le_bytes([b[0], b[1], b[2], b[3]]) as usize)
            .ok_or(SeamGlbError::NotGlb("truncated"))
    };
    if word(0)? != 0x4654_6C67 || word(4)? != 2 {
        return Err(SeamGlbError::NotGlb("no glTF 2 header"));
    }
    let json_len = word(12)?;
    if word(16)? != 0x4E4F_534A {
        return Err(SeamGlbError::NotGlb("the first chunk is not JSON"));
    }
    let json = glb
        .get(20..20 + json_len)
        .ok_or(SeamGlbError::NotGlb("truncated JSON chunk"))?;
    let doc: Value = serde_json::from_slice(json)?;
    let at = 20 + json_len;
    let bin = if glb.len() > at {
        let len = word(at)?;
        if word(at + 4)? != 0x004E_4942 {
            return Err(SeamGlbError::NotGlb("the second chunk is not BIN"));
        }
        glb.get(at + 8..at + 8 + len)
            .ok_or(SeamGlbError::NotGlb("truncated BIN chunk"))?
            .to_vec()
    } else {
        Vec::new()
    };
    Ok((doc, bin))
}
