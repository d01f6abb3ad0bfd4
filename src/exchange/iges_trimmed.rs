//! IGES 5.3 trimmed surfaces: a vessel's faces written one by one, each a
//! trimmed parametric surface (144) on its exact rational B-spline surface
//! (128), bounded by curves on the surface (142), one per loop: each pairs a
//! composite curve (102) of the loop's curves in the surface's parameter space
//! with one of the same curves in model space, both B-spline curves (126), the
//! parameter-space ones preferred. Where a loop passes a pole (the STEP face
//! leaves that side out), the parameter-space curve runs along the pole's side
//! and the model-space one stays at the pole point. Trimmed surfaces share no
//! edges: each face carries its own copy of its boundary, and a receiver sews
//! them (the representation every importer reads; the B-rep of `iges_brep` is
//! the default).

use glam::DAffine3;

use super::brep::{EdgeCurve, OrientedEdge};
use super::error::ExchangeError;
use super::iges::{Entry, Params, status};
use super::iges_entities::VesselWriter;
use crate::nurbs::NurbsSurface;

/// Writes each face of the vessel as a 144 coloured by `colours[node]`;
/// returns their pointers.
///
/// # Errors
///
/// [`ExchangeError::Geometry`] where a surface or curve cannot be placed in
/// the plant frame.
pub(super) fn trimmed_faces(
    vessel: &mut VesselWriter,
    colours: &[usize],
) -> Result<Vec<usize>, ExchangeError> {
    let brep = vessel.brep;
    let mut faces = Vec::with_capacity(brep.faces.len());
    for face in &brep.faces {
        let surface = vessel.placed(face)?;
        let geometry = vessel.fail(face.node);
        let s = vessel.surface(&surface);
        let mut bounds = Vec::with_capacity(1 + face.holes.len());
        for lp in std::iter::once(&face.outer).chain(&face.holes) {
            bounds.push(vessel.boundary(s, &face.surface, lp).map_err(&geometry)?);
        }
        let label = vessel.name(&vessel.face_name(face));
        let mut p = Params::default();
        p.ptr(s).int(1).int(bounds.len() as i64 - 1);
        for &b in &bounds {
            p.ptr(b);
        }
        p.int(0).int(1).ptr(label);
        let entry = Entry {
            colour: colours[face.node],
            subscript: faces.len() + 1,
            ..vessel.entry(144, 0, status::INDEPENDENT, "FACE")
        };
        faces.push(vessel.w.entity(&entry, &p));
    }
    Ok(faces)
}

impl VesselWriter<'_> {
    /// A loop as a curve on the surface (142): its curves in parameter and in
    /// model space, each in the loop's direction, with a segment along each
    /// pole side the loop leaves out. `local` is the surface in the vessel
    /// frame, where the edges are.
    pub(super) fn boundary(
        &mut self,
        surface: usize,
        local: &NurbsSurface,
        uses: &[OrientedEdge],
    ) -> Result<usize, crate::nurbs::NurbsError> {
        let frame: DAffine3 = self.brep.frame;
        let mut params = Vec::with_capacity(uses.len() + 1);
        let mut models = Vec::with_capacity(uses.len() + 1);
        let ends = |e: &OrientedEdge| {
            let (a, b) = (e.pcurve[0], e.pcurve[e.pcurve.len() - 1]);
            if e.forward { (a, b) } else { (b, a) }
        };
        for (k, e) in uses.iter().enumerate() {
            let edge = &self.brep.edges[e.edge];
            let (EdgeCurve::Nurbs(c) | EdgeCurve::Loop(c)) = &edge.curve;
            let c = c.transformed(&frame)?;
            let c = if e.forward { c } else { c.reversed() };
            let model = self.nurbs(&c);
            let pcurve = edge.curve.pcurve(&e.pcurve)?;
            let pcurve = if e.forward { pcurve } else { pcurve.reversed() };
            params.push(self.spline2(&pcurve));
            models.push(model);
            // A pole side left out between this use and the next.
            let end = ends(e).1;
            let next = ends(&uses[(k + 1) % uses.len()]).0;
            if end.distance(next) > 1e-12 {
                params.push(self.polyline(&[end.extend(0.0), next.extend(0.0)], true));
                let pole = frame.transform_point3(local.point(end.x, end.y));
                models.push(self.polyline(&[pole, pole], false));
            }
        }
        let b = self.composite(&params, true);
        let c = self.composite(&models, false);
        let mut p = Params::default();
        p.int(0).ptr(surface).ptr(b).ptr(c).int(1);
        let entry = self.entry(142, 0, status::DEPENDENT, "BOUNDARY");
        Ok(self.w.entity(&entry, &p))
    }
}
