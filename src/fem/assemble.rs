//! A vessel's FE mesh from its pieces: the plan ([`super::envelope`]), the
//! pieces ([`super::piece`], through a [`FemCache`]), welded into one
//! conforming mesh — nodes of one [`NodeKey`] (a ring shared by two pieces,
//! the mid-side nodes of its edges) become one node, the first piece's; the
//! pieces' own parts are appended after the envelope's; boundary and junction
//! node lists lose the duplicates the shared rings give — and moved to the
//! plant frame last, so moving a vessel re-meshes nothing.

use std::collections::{HashMap, HashSet};

use glam::DVec3;

use super::builder::NodeKey;
use super::cache::FemCache;
use super::envelope::{FemOptions, plan};
use super::piece::Piece;
use super::{Element, FeMesh, FePart, FemError, NeckEnd};
use crate::constraints::ResolvedVessel;
use crate::design::VesselDesign;

/// The conforming shell mesh of the pressure envelope (courses, reducers,
/// heads) of `design`, resolved as `resolved`, in the plant frame: every piece
/// meshed afresh ([`build_envelope_cached`] with an empty cache).
///
/// # Errors
///
/// [`FemError`] for a part without thickness, a wall too thick for its shape,
/// a vessel with nothing to mesh, or options out of range.
pub fn build_envelope(
    design: &VesselDesign,
    resolved: &ResolvedVessel,
    options: &FemOptions,
) -> Result<FeMesh, FemError> {
    build_envelope_cached(design, resolved, options, &mut FemCache::default())
}

/// As [`build_envelope`], meshing only the pieces whose inputs differ from
/// those `cache` holds for this vessel and taking the others from it;
/// [`FemCache::counters`] then says which.
///
/// # Errors
///
/// As [`build_envelope`].
pub fn build_envelope_cached(
    design: &VesselDesign,
    resolved: &ResolvedVessel,
    options: &FemOptions,
    cache: &mut FemCache,
) -> Result<FeMesh, FemError> {
    let plan = plan(design, resolved, options)?;
    let inputs = super::piece::inputs(&plan);
    let pieces = cache.pieces(&plan, inputs);
    let mut mesh = assemble(&pieces, &plan.parts, plan.notes.clone());
    // Vessel frame → plant frame.
    let frame = resolved.frame;
    for p in &mut mesh.nodes {
        *p = frame.transform_point3(*p);
    }
    for end in &mut mesh.necks {
        end.centre = frame.transform_point3(end.centre);
        end.axis = frame.transform_vector3(end.axis).normalize();
    }
    mesh.axis = (
        frame.transform_point3(DVec3::ZERO),
        frame.transform_vector3(DVec3::Z).normalize(),
    );
    Ok(mesh)
}

/// The mesh of `pieces` (in order) on the envelope's parts `parts`, with the
/// plan's `notes` first, in the vessel frame.
pub fn assemble(pieces: &[std::sync::Arc<Piece>], parts: &[FePart], notes: Vec<String>) -> FeMesh {
    let mut mesh = FeMesh {
        parts: parts.to_vec(),
        notes,
        ..FeMesh::default()
    };
    let mut welded: HashMap<NodeKey, usize> = HashMap::new();
    let (mut boundary, mut junctions) = (HashSet::new(), HashSet::new());
    for piece in pieces {
        let own = &piece.mesh;
        let mut node = Vec::with_capacity(own.nodes.len());
        for (&p, key) in own.nodes.iter().zip(&piece.keys) {
            let fresh = mesh.nodes.len();
            let id = match key {
                Some(k) => *welded.entry(*k).or_insert(fresh),
                None => fresh,
            };
            if id == fresh {
                mesh.nodes.push(p);
            }
            node.push(id);
        }
        let part: Vec<usize> = own
            .parts
            .iter()
            .enumerate()
            .map(|(j, p)| {
                if j < piece.envelope_parts {
                    j
                } else {
                    mesh.parts.push(p.clone());
                    mesh.parts.len() - 1
                }
            })
            .collect();
        mesh.elements.extend(own.elements.iter().map(|e| Element {
            kind: e.kind,
            nodes: e.nodes.iter().map(|&i| node[i]).collect(),
            part: part[e.part],
        }));
        for &i in &own.boundary {
            if boundary.insert(node[i]) {
                mesh.boundary.push(node[i]);
            }
        }
        for &i in &own.junctions {
            if junctions.insert(node[i]) {
                mesh.junctions.push(node[i]);
            }
        }
        mesh.necks.extend(own.necks.iter().map(|end| NeckEnd {
            part: part[end.part],
            nodes: end.nodes.iter().map(|&i| node[i]).collect(),
            mids: end.mids.iter().map(|&i| node[i]).collect(),
            ..end.clone()
        }));
        mesh.notes.extend(own.notes.iter().cloned());
        mesh.structural
            .extend(own.structural.iter().map(|&p| part[p]));
    }
    mesh
}
