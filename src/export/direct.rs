//! The direct, non-incremental scene build: design → resolved vessels → patches →
//! meshes → [`Scene`], all in one call.
//!
//! This runs the whole data flow (Constrain, Geometry, Tessellate) from scratch,
//! without ECS: it is the reference the incremental model's scenes are compared
//! against, and the baseline of the benchmarks. Patch building and tessellation run
//! in parallel with rayon (tessellation over every patch of the plant at once); the
//! result is assembled in design order, so it does not depend on scheduling.

use std::collections::HashMap;
use std::sync::Arc;

use rayon::prelude::*;

use super::error::ExportError;
use super::extras::{nozzle_extras, part_extras, vessel_extras};
use super::openings::{Opening, SharedMarches, cut_opening, openings};
use super::scene::{Scene, SceneNode, SceneNodeKind, ScenePatch, SceneVessel};
use crate::constraints::PartGeometry;
use crate::design::{Design, resolve};
use crate::mesh::cdt::mesh_patch_region;
use crate::mesh::{
    HostTrim, Notch, PackedMesh, PadCut, TessellationOptions, host_region, pad_region,
    patch_extent, storage_options,
};
use crate::nurbs::intersect::IntersectionLoop;
use crate::parts::{Nozzle, PartError, Patch};

/// Builds the scene of a whole design: every vessel, its parts then its nozzles in
/// design order, each with its patches meshed to `options`.
///
/// # Errors
///
/// [`ExportError::Options`] for out-of-range options, [`ExportError::Design`] when
/// the design breaks a rule, [`ExportError::Part`] when a resolved part cannot
/// build its patches (the first such part in design order).
pub fn build_scene(design: &Design, options: &TessellationOptions) -> Result<Scene, ExportError> {
    options.validate()?;
    let resolved = resolve(design)?;

    // The scene without meshes, and what builds each node's patches, in design
    // order. `resolve` returns one vessel per design vessel, one part per design
    // part and one nozzle per design nozzle, each in design order.
    let mut vessels = Vec::with_capacity(resolved.len());
    let mut sources = Vec::new();
    for (vessel_design, vessel) in design.vessels.iter().zip(&resolved) {
        let mut nodes = Vec::with_capacity(vessel.parts.len() + vessel.nozzles.len());
        for (part_design, part) in vessel_design.parts.iter().zip(&vessel.parts) {
            sources.push(Source::Part(&part.geometry));
            nodes.push(SceneNode {
                id: part.id.clone(),
                kind: SceneNodeKind::Part,
                frame: part.frame,
                extras: part_extras(part_design, part),
                patches: Vec::new(),
            });
        }
        for (nozzle_design, nozzle) in vessel_design.nozzles.iter().zip(&vessel.nozzles) {
            sources.push(Source::Nozzle(&nozzle.geometry));
            nodes.push(SceneNode {
                id: nozzle.mark.clone(),
                kind: SceneNodeKind::Nozzle,
                frame: nozzle.frame,
                extras: nozzle_extras(nozzle_design, nozzle),
                patches: Vec::new(),
            });
        }
        vessels.push(SceneVessel {
            tag: vessel.tag.clone(),
            frame: vessel.frame,
            extras: vessel_extras(vessel_design, vessel),
            nodes,
        });
    }

    // Geometry: every node's patches, in parallel; the first error in design order
    // wins, whatever the scheduling.
    let built: Vec<Result<Vec<Patch>, PartError>> =
        sources.par_iter().map(Source::patches).collect();
    let mut patches = Vec::with_capacity(built.len());
    let node_slots = vessels
        .iter()
        .enumerate()
        .flat_map(|(v, vessel)| (0..vessel.nodes.len()).map(move |n| (v, n)));
    for ((v, n), result) in node_slots.zip(built) {
        match result {
            Ok(node_patches) => patches.push(((v, n), node_patches)),
            Err(source) => {
                let entity = format!("{}/{}", vessels[v].tag, vessels[v].nodes[n].id);
                return Err(ExportError::Part { entity, source });
            }
        }
    }

    // Storage precision: mesh to the tolerance less the f32 rounding of the
    // largest part (see `mesh::storage_options`), as the model does.
    let extent = patches
        .iter()
        .flat_map(|(_, list)| list.iter())
        .map(patch_extent)
        .fold(0.0, f64::max);
    let stored = storage_options(options, extent);
    let options = &stored;

    // Openings: every boot's shell and every nozzle's neck cut against its host
    // (`openings`, shared with the exchange), in parallel. Per vessel the boots
    // come first, then the nozzles in design order: the order the model relates
    // them to their hosts, so holes are listed alike.
    let by_node: HashMap<(usize, usize), &Vec<Patch>> =
        patches.iter().map(|(k, list)| (*k, list)).collect();
    let jobs: Vec<(usize, Opening)> = resolved
        .iter()
        .enumerate()
        .flat_map(|(v, vessel)| openings(vessel).into_iter().map(move |o| (v, o)))
        .collect();
    let shared = SharedMarches::default();
    let cut: Vec<_> = jobs
        .par_iter()
        .map(|&(v, opening)| {
            let (n, h) = (opening.neck, opening.host);
            let hosts = by_node.get(&(v, h)).map_or(&[][..], |l| l.as_slice());
            let neck = by_node.get(&(v, n)).and_then(|l| l.first());
            let frames = (&vessels[v].nodes[n].frame, &vessels[v].nodes[h].frame);
            let result = cut_opening(
                neck,
                opening.pad_od,
                frames,
                hosts,
                options.tolerance,
                &shared,
            )
            .map(|c| (c.cut, c.pad));
            ((v, n, h), result)
        })
        .collect();
    let mut holes: HashMap<(usize, usize, usize), Vec<IntersectionLoop>> = HashMap::new();
    let mut notches: HashMap<(usize, usize, usize), Vec<Notch>> = HashMap::new();
    let mut bottoms: HashMap<(usize, usize), IntersectionLoop> = HashMap::new();
    let mut pads: Vec<((usize, usize), PadCut)> = Vec::new();
    for ((v, n, h), result) in cut {
        match result {
            Ok((cut, pad)) => {
                for (k, trim) in &cut.hosts {
                    match trim {
                        HostTrim::Hole => {
                            let hole = cut.pad.clone().unwrap_or_else(|| cut.neck.clone());
                            holes.entry((v, h, *k)).or_default().push(hole);
                        }
                        HostTrim::Notches(list) => notches
                            .entry((v, h, *k))
                            .or_default()
                            .extend(list.iter().cloned()),
                    }
                }
                if let Some(pad) = pad {
                    pads.push(((v, n), pad));
                }
                bottoms.insert((v, n), cut.neck);
            }
            Err(message) => {
                let entity = format!("{}/{}", vessels[v].tag, vessels[v].nodes[n].id);
                return Err(ExportError::Mesh { entity, message });
            }
        }
    }

    // Tessellation: every patch of the plant (pads after their nozzle's patches),
    // in parallel, collected in order.
    let pad_of: HashMap<(usize, usize), usize> =
        pads.iter().enumerate().map(|(i, p)| (p.0, i)).collect();
    let mut flat: Vec<(usize, usize, usize, &Patch, bool)> = Vec::new();
    for ((v, n), list) in &patches {
        flat.extend(list.iter().enumerate().map(|(k, p)| (*v, *n, k, p, false)));
        if let Some(&i) = pad_of.get(&(*v, *n)) {
            flat.push((*v, *n, usize::MAX, &pads[i].1.patch, true));
        }
    }
    let meshes: Vec<Result<PackedMesh, String>> = flat
        .par_iter()
        .map(|&(v, n, k, patch, is_pad)| {
            let region = if is_pad {
                let (_, pad) = &pads[pad_of[&(v, n)]];
                pad_region(&patch.surface, options, &pad.outer, &pad.inner)
            } else {
                let hole_list: Vec<&IntersectionLoop> = holes
                    .get(&(v, n, k))
                    .map(|l| l.iter().collect())
                    .unwrap_or_default();
                let notch_list: Vec<&Notch> = notches
                    .get(&(v, n, k))
                    .map(|l| l.iter().collect())
                    .unwrap_or_default();
                let bottom = if k == 0 { bottoms.get(&(v, n)) } else { None };
                host_region(&patch.surface, options, &hole_list, &notch_list, bottom)
            }
            .map_err(|e| e.to_string())?;
            mesh_patch_region(patch, &region, options)
                .map(|out| PackedMesh::pack_marked(&out.mesh, &out.on_loops))
                .map_err(|e| e.to_string())
        })
        .collect();
    for ((v, n, _, patch, _), mesh) in flat.into_iter().zip(meshes) {
        let mesh = mesh.map_err(|message| ExportError::Mesh {
            entity: format!("{}/{}", vessels[v].tag, vessels[v].nodes[n].id),
            message,
        })?;
        vessels[v].nodes[n].patches.push(ScenePatch {
            name: patch_name(patch),
            mesh: Arc::new(mesh),
        });
    }
    Ok(Scene { vessels })
}

/// The scene name of a patch: its name, followed by its index when that is > 0
/// (`"leg 2"`).
pub fn patch_name(patch: &Patch) -> String {
    if patch.index > 0 {
        format!("{} {}", patch.name, patch.index)
    } else {
        patch.name.to_string()
    }
}

/// What builds one node's patches.
enum Source<'a> {
    /// A part.
    Part(&'a PartGeometry),
    /// A nozzle.
    Nozzle(&'a Nozzle),
}

impl Source<'_> {
    /// The node's exact patches in its local frame.
    fn patches(&self) -> Result<Vec<Patch>, PartError> {
        match self {
            Source::Part(geometry) => geometry.patches(),
            Source::Nozzle(nozzle) => nozzle.patches(),
        }
    }
}
