//! IGES 5.3 B-rep of a vessel (the manifold solid B-rep object entities): the
//! topology [`vessel_brep`](super::vessel_brep) builds for STEP, with its
//! shared edges, so that a receiver reads sewn shells and solids rather than
//! loose trimmed surfaces.
//!
//! One vertex list (502) holds the vessel's vertices and one edge list (504)
//! its edges, each on its model-space B-spline curve (126) between two of
//! those vertices. Each face (510) lies on its exact rational B-spline surface
//! (128) with its loops (508), outer first: each use of an edge names the edge
//! by its index in the list, whether the loop runs along the edge's curve, and
//! its pcurve, a B-spline curve in the surface's parameter space (126, z = 0)
//! in the edge's direction over the edge's parameter (the STEP file's pcurves).
//! A pole side is left out of its loop, as in the STEP file. Each shell of
//! faces joined through shared edges is a shell (514), form 1 when closed,
//! form 2 when open; with solids asked for, each closed shell is the shell of
//! a manifold solid (186), the vessel's displacement solid. Faces are named
//! `tag/id/patch` (406) and coloured as the trimmed surfaces are.

use super::brep::EdgeCurve;
use super::error::ExchangeError;
use super::iges::{Entry, Params, status};
use super::iges_entities::VesselWriter;

/// Writes the vessel's vertices, edges, faces and shells, each closed shell
/// wrapped in a manifold solid when `solids`; faces coloured by
/// `colours[node]`. Returns the pointers of the vessel's shells and solids
/// (the entities a receiver transfers).
///
/// # Errors
///
/// [`ExchangeError::Geometry`] where a surface or curve cannot be placed in
/// the plant frame.
pub(super) fn brep_entities(
    vessel: &mut VesselWriter,
    colours: &[usize],
    solids: bool,
) -> Result<Vec<usize>, ExchangeError> {
    let brep = vessel.brep;
    let frame = brep.frame;

    let mut p = Params::default();
    p.int(brep.vertices.len() as i64);
    for v in &brep.vertices {
        let q = frame.transform_point3(*v);
        p.reals([q.x, q.y, q.z]);
    }
    let entry = vessel.entry(502, 1, status::DEPENDENT, "VERTICES");
    let vertex_list = vessel.w.entity(&entry, &p);

    // Each edge's node, for the errors: the first face using it.
    let mut edge_node = vec![0usize; brep.edges.len()];
    for face in brep.faces.iter().rev() {
        for e in face.outer.iter().chain(face.holes.iter().flatten()) {
            edge_node[e.edge] = face.node;
        }
    }
    let mut curves = Vec::with_capacity(brep.edges.len());
    for (edge, &node) in brep.edges.iter().zip(&edge_node) {
        let (EdgeCurve::Nurbs(c) | EdgeCurve::Loop(c)) = &edge.curve;
        let c = c.transformed(&frame).map_err(vessel.fail(node))?;
        curves.push(vessel.nurbs(&c));
    }
    let mut p = Params::default();
    p.int(brep.edges.len() as i64);
    for (edge, &curve) in brep.edges.iter().zip(&curves) {
        p.ptr(curve).ptr(vertex_list).int(edge.start as i64 + 1);
        p.ptr(vertex_list).int(edge.end as i64 + 1);
    }
    let entry = vessel.entry(504, 1, status::DEPENDENT, "EDGES");
    let edge_list = vessel.w.entity(&entry, &p);

    let mut faces = Vec::with_capacity(brep.faces.len());
    for face in &brep.faces {
        let surface = vessel.placed(face)?;
        let geometry = vessel.fail(face.node);
        let s = vessel.surface(&surface);
        let mut loops = Vec::with_capacity(1 + face.holes.len());
        for lp in std::iter::once(&face.outer).chain(&face.holes) {
            let mut p = Params::default();
            p.int(lp.len() as i64);
            for e in lp {
                let pcurve = brep.edges[e.edge]
                    .curve
                    .pcurve(&e.pcurve)
                    .map_err(&geometry)?;
                let pcurve = vessel.spline2(&pcurve);
                p.int(0).ptr(edge_list).int(e.edge as i64 + 1);
                p.int(i64::from(e.forward)).int(1).int(0).ptr(pcurve);
            }
            let entry = vessel.entry(508, 1, status::DEPENDENT, "LOOP");
            loops.push(vessel.w.entity(&entry, &p));
        }
        let label = vessel.name(&vessel.face_name(face));
        let mut p = Params::default();
        p.ptr(s).int(loops.len() as i64).int(1);
        for &l in &loops {
            p.ptr(l);
        }
        p.int(0).int(1).ptr(label);
        let entry = Entry {
            colour: colours[face.node],
            subscript: faces.len() + 1,
            ..vessel.entry(510, 1, status::DEPENDENT, "FACE")
        };
        faces.push(vessel.w.entity(&entry, &p));
    }

    let mut roots = Vec::with_capacity(brep.shells.len());
    for (k, shell) in brep.shells.iter().enumerate() {
        let solid = solids && shell.closed;
        let mut p = Params::default();
        p.int(shell.faces.len() as i64);
        for &f in &shell.faces {
            p.ptr(faces[f]).int(1);
        }
        let entry = Entry {
            subscript: k + 1,
            ..vessel.entry(
                514,
                if shell.closed { 1 } else { 2 },
                if solid {
                    status::DEPENDENT
                } else {
                    status::INDEPENDENT
                },
                "SHELL",
            )
        };
        let id = vessel.w.entity(&entry, &p);
        if !solid {
            roots.push(id);
            continue;
        }
        let label = vessel.name(&format!("{} displacement", brep.tag));
        let mut p = Params::default();
        p.ptr(id).int(1).int(0).int(0).int(1).ptr(label);
        let entry = Entry {
            subscript: k + 1,
            ..vessel.entry(186, 0, status::INDEPENDENT, "SOLID")
        };
        roots.push(vessel.w.entity(&entry, &p));
    }
    Ok(roots)
}
