//! IGES 5.3 of the exact model: the B-rep [`vessel_brep`](super::vessel_brep)
//! builds for STEP, written as trimmed surfaces (one exact model, two writers).
//!
//! Each face is a trimmed parametric surface (entity 144) on its exact rational
//! B-spline surface (128), bounded by curves on the surface (142), one per loop:
//! each pairs a composite curve (102) of the loop's curves in the surface's
//! parameter space with one of the same curves in model space, both B-spline
//! curves (126), the parameter-space ones preferred. An exact side is its
//! isocurve and a straight line in (u, v); an opening's loop is the sampled
//! curve and the samples' (u, v), as in the STEP file. Where a loop passes a
//! pole (the STEP face leaves that side out), the parameter-space curve runs
//! along the pole's side and the model-space one stays at the pole point. IGES
//! has no shared edges: each face carries its own copy of its boundary, and a
//! receiver sews them.
//!
//! Geometry is in the plant frame, millimetres. Each face is named
//! `tag/id/patch` by a name property (406 form 15) and coloured (314) by what
//! it belongs to: a part of the envelope, a nozzle, a support; each vessel's
//! faces are on level 1 + its index and in a group (402 form 7) named by its
//! tag.

use glam::{DAffine3, DVec3};
use rayon::prelude::*;

use super::blocks::ExchangeOptions;
use super::brep::{EdgeCurve, OrientedEdge, VesselBrep};
use super::error::ExchangeError;
use super::iges::{Entry, Global, IgesWriter, Params, status};
use super::source::{NodeKind, vessel_sources};
use super::topology::vessel_brep_with;
use crate::design::Design;
use crate::mesh::closed_in_u;
use crate::nurbs::{NurbsCurve, NurbsSurface};

/// Colours (per cent red, green, blue) and names of the three kinds of face.
const COLOURS: [(NodeKind, [f64; 3], &str); 3] = [
    (NodeKind::Part, [70.0, 72.0, 75.0], "shell"),
    (NodeKind::Nozzle, [25.0, 45.0, 80.0], "nozzle"),
    (NodeKind::Support, [45.0, 40.0, 35.0], "support"),
];

/// Writes the vessels of `design` tagged in `tags` (all when empty) as one
/// IGES 5.3 file named `name`.
///
/// # Errors
///
/// As [`export_step`](super::export_step): an invalid design or options, an
/// unknown tag, a part, opening or trim that cannot be built.
pub fn export_iges(
    design: &Design,
    tags: &[String],
    options: &ExchangeOptions,
    name: &str,
) -> Result<String, ExchangeError> {
    options.validate()?;
    let sources = vessel_sources(design, tags, options.tolerance)?;
    let vessels: Vec<(VesselBrep, Vec<NodeKind>)> = sources
        .par_iter()
        .map(|s| {
            let kinds = s.nodes.iter().map(|n| n.kind).collect();
            vessel_brep_with(s, options.solids).map(|b| (b, kinds))
        })
        .collect::<Result<_, _>>()?;
    write_iges(name, &vessels, options.tolerance)
}

/// Writes the file: colours, then each vessel's faces and group.
///
/// # Errors
///
/// [`ExchangeError::Geometry`] where a surface or curve cannot be placed in
/// the plant frame.
pub fn write_iges(
    name: &str,
    vessels: &[(VesselBrep, Vec<NodeKind>)],
    resolution: f64,
) -> Result<String, ExchangeError> {
    let mut w = IgesWriter::default();
    let colours: Vec<(NodeKind, usize)> = COLOURS
        .iter()
        .map(|(kind, rgb, label)| {
            let mut p = Params::default();
            p.reals(*rgb).string(label);
            let de = w.entity(
                &Entry {
                    kind: 314,
                    form: 0,
                    level: 0,
                    colour: 0,
                    status: status::DEFINITION,
                    label: "COLOUR",
                    subscript: 0,
                },
                &p,
            );
            (*kind, de)
        })
        .collect();
    let mut max_coordinate = 0.0f64;
    for (index, (brep, kinds)) in vessels.iter().enumerate() {
        let level = index + 1;
        let mut faces = Vec::with_capacity(brep.faces.len());
        for face in &brep.faces {
            let node = &brep.nodes[face.node];
            let geometry = |source| ExchangeError::Geometry {
                entity: format!("{}/{node}", brep.tag),
                source,
            };
            let surface = face.surface.transformed(&brep.frame).map_err(geometry)?;
            for p in surface.control_points() {
                max_coordinate = max_coordinate.max(p.abs().max_element());
            }
            let mut vessel = VesselWriter {
                w: &mut w,
                brep,
                level,
            };
            let s = vessel.surface(&surface);
            let mut bounds = Vec::with_capacity(1 + face.holes.len());
            for lp in std::iter::once(&face.outer).chain(&face.holes) {
                bounds.push(vessel.boundary(s, &face.surface, lp).map_err(geometry)?);
            }
            let label = vessel.name(&format!("{}/{node}/{}", brep.tag, face.patch));
            let colour = colours
                .iter()
                .find(|(k, _)| *k == kinds[face.node])
                .map_or(0, |c| c.1);
            let mut p = Params::default();
            p.ptr(s).int(1).int(bounds.len() as i64 - 1);
            for &b in &bounds {
                p.ptr(b);
            }
            p.int(0).int(1).ptr(label);
            faces.push(w.entity(
                &Entry {
                    kind: 144,
                    form: 0,
                    level,
                    colour,
                    status: status::INDEPENDENT,
                    label: "FACE",
                    subscript: faces.len() + 1,
                },
                &p,
            ));
        }
        let label = VesselWriter {
            w: &mut w,
            brep,
            level,
        }
        .name(&brep.tag);
        let mut p = Params::default();
        p.int(faces.len() as i64);
        for &f in &faces {
            p.ptr(f);
        }
        p.int(0).int(1).ptr(label);
        w.entity(
            &Entry {
                kind: 402,
                form: 7,
                level,
                colour: 0,
                status: status::INDEPENDENT,
                label: "VESSEL",
                subscript: level,
            },
            &p,
        );
    }
    Ok(w.finish(&Global {
        name,
        resolution,
        max_coordinate,
    }))
}

/// Writes one vessel's entities on its level.
struct VesselWriter<'a> {
    w: &'a mut IgesWriter,
    brep: &'a VesselBrep,
    level: usize,
}

impl VesselWriter<'_> {
    fn entry(&self, kind: u16, form: u16, status: &'static str, label: &'static str) -> Entry {
        Entry {
            kind,
            form,
            level: self.level,
            colour: 0,
            status,
            label,
            subscript: 0,
        }
    }

    /// A name property (406 form 15).
    fn name(&mut self, name: &str) -> usize {
        let mut p = Params::default();
        p.int(1).string(name);
        let entry = self.entry(406, 15, status::DEFINITION, "NAME");
        self.w.entity(&entry, &p)
    }

    /// A rational B-spline surface (128), u varying fastest.
    fn surface(&mut self, surface: &NurbsSurface) -> usize {
        let (nu, nv) = (surface.u_count(), surface.v_count());
        let (du, dv) = (surface.u_degree(), surface.v_degree());
        let h = surface.homogeneous_points();
        let polynomial = h.iter().all(|p| p.w == 1.0);
        let mut p = Params::default();
        p.int(nu as i64 - 1).int(nv as i64 - 1);
        p.int(du as i64).int(dv as i64);
        p.int(i64::from(closed_in_u(surface))).int(0);
        p.int(i64::from(polynomial)).int(0).int(0);
        p.reals(surface.u_knots().as_slice().iter().copied());
        p.reals(surface.v_knots().as_slice().iter().copied());
        let at = |i: usize, j: usize| h[i * nv + j];
        for j in 0..nv {
            for i in 0..nu {
                p.real(at(i, j).w);
            }
        }
        for j in 0..nv {
            for i in 0..nu {
                let q = at(i, j).truncate() / at(i, j).w;
                p.reals([q.x, q.y, q.z]);
            }
        }
        let ((u0, u1), (v0, v1)) = surface.domain();
        p.reals([u0, u1, v0, v1]);
        let entry = self.entry(128, 0, status::DEPENDENT, "SURFACE");
        self.w.entity(&entry, &p)
    }

    /// A B-spline curve (126): `points` with `weights` over `knots`; planar
    /// in z = 0 when `planar` (a parameter-space curve).
    fn curve(
        &mut self,
        degree: usize,
        knots: &[f64],
        points: &[DVec3],
        weights: Option<&[f64]>,
        planar: bool,
    ) -> usize {
        let mut p = Params::default();
        let closed = points
            .first()
            .zip(points.last())
            .is_some_and(|(a, b)| a == b);
        p.int(points.len() as i64 - 1).int(degree as i64);
        p.int(i64::from(planar)).int(i64::from(closed));
        p.int(i64::from(weights.is_none())).int(0);
        p.reals(knots.iter().copied());
        match weights {
            Some(w) => p.reals(w.iter().copied()),
            None => p.reals(points.iter().map(|_| 1.0)),
        };
        for q in points {
            p.reals([q.x, q.y, q.z]);
        }
        p.reals([knots[degree], knots[knots.len() - 1 - degree]]);
        p.reals(if planar { [0.0, 0.0, 1.0] } else { [0.0; 3] });
        let entry = if planar {
            self.entry(126, 0, status::PARAMETRIC, "PCURVE")
        } else {
            self.entry(126, 0, status::DEPENDENT, "CURVE")
        };
        self.w.entity(&entry, &p)
    }

    /// A degree-1 curve through `points`, parameter k at point k.
    fn polyline(&mut self, points: &[DVec3], planar: bool) -> usize {
        let n = points.len();
        let mut knots = Vec::with_capacity(n + 2);
        knots.push(0.0);
        knots.extend((0..n).map(|k| k as f64));
        knots.push((n - 1) as f64);
        self.curve(1, &knots, points, None, planar)
    }

    /// A polynomial B-spline in parameter space (z = 0).
    fn spline2(&mut self, c: &NurbsCurve) -> usize {
        let points = c.control_points();
        self.curve(c.degree(), c.knots().as_slice(), &points, None, true)
    }

    /// A NURBS curve in model space.
    fn nurbs(&mut self, c: &NurbsCurve) -> usize {
        let points = c.control_points();
        let weights = (!c.is_polynomial()).then(|| c.weights());
        self.curve(
            c.degree(),
            c.knots().as_slice(),
            &points,
            weights.as_deref(),
            false,
        )
    }

    /// A composite curve (102) of `curves`, or the one curve.
    fn composite(&mut self, curves: &[usize], planar: bool) -> usize {
        if let [one] = curves {
            return *one;
        }
        let mut p = Params::default();
        p.int(curves.len() as i64);
        for &c in curves {
            p.ptr(c);
        }
        let entry = if planar {
            self.entry(102, 0, status::PARAMETRIC, "PCURVES")
        } else {
            self.entry(102, 0, status::DEPENDENT, "CURVES")
        };
        self.w.entity(&entry, &p)
    }

    /// A loop as a curve on the surface (142): its curves in parameter and in
    /// model space, each in the loop's direction, with a segment along each
    /// pole side the loop leaves out. `local` is the surface in the vessel
    /// frame, where the edges are.
    fn boundary(
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
