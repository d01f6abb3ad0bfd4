//! The IGES entities both representations of a vessel are written with: its
//! faces' rational B-spline surfaces (128), B-spline curves (126) in model
//! space and in a surface's parameter space, composites (102) and name
//! properties (406), each on the vessel's level. [`VesselWriter`] appends them
//! to the file's [`IgesWriter`] and returns their pointers.

use glam::DVec3;

use super::brep::{Face, VesselBrep};
use super::error::ExchangeError;
use super::iges::{Entry, IgesWriter, Params, status};
use crate::mesh::closed_in_u;
use crate::nurbs::{NurbsCurve, NurbsError, NurbsSurface};

/// Writes one vessel's entities on its level.
pub(super) struct VesselWriter<'a> {
    /// The file being written.
    pub(super) w: &'a mut IgesWriter,
    /// The vessel.
    pub(super) brep: &'a VesselBrep,
    /// Its level.
    pub(super) level: usize,
    /// Largest absolute coordinate of the surfaces placed so far, mm.
    pub(super) extent: f64,
}

impl<'a> VesselWriter<'a> {
    /// The vessel's writer on `level`.
    pub(super) fn new(w: &'a mut IgesWriter, brep: &'a VesselBrep, level: usize) -> Self {
        Self {
            w,
            brep,
            level,
            extent: 0.0,
        }
    }

    /// The error of a surface or curve of `node` that cannot be placed.
    pub(super) fn fail(&self, node: usize) -> impl Fn(NurbsError) -> ExchangeError + 'a {
        let brep = self.brep;
        move |source| ExchangeError::Geometry {
            entity: format!("{}/{}", brep.tag, brep.nodes[node]),
            source,
        }
    }

    /// A face's surface in the plant frame (and the extent grown to it).
    ///
    /// # Errors
    ///
    /// [`ExchangeError::Geometry`] where it cannot be transformed.
    pub(super) fn placed(&mut self, face: &Face) -> Result<NurbsSurface, ExchangeError> {
        let surface = face
            .surface
            .transformed(&self.brep.frame)
            .map_err(self.fail(face.node))?;
        for p in surface.control_points() {
            self.extent = self.extent.max(p.abs().max_element());
        }
        Ok(surface)
    }

    /// A face's name, `tag/id/patch`.
    pub(super) fn face_name(&self, face: &Face) -> String {
        format!(
            "{}/{}/{}",
            self.brep.tag, self.brep.nodes[face.node], face.patch
        )
    }
}

impl VesselWriter<'_> {
    pub(super) fn entry(
        &self,
        kind: u16,
        form: u16,
        status: &'static str,
        label: &'static str,
    ) -> Entry {
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
    pub(super) fn name(&mut self, name: &str) -> usize {
        let mut p = Params::default();
        p.int(1).string(name);
        let entry = self.entry(406, 15, status::DEFINITION, "NAME");
        self.w.entity(&entry, &p)
    }

    /// A rational B-spline surface (128), u varying fastest.
    pub(super) fn surface(&mut self, surface: &NurbsSurface) -> usize {
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
    pub(super) fn curve(
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
    pub(super) fn polyline(&mut self, points: &[DVec3], planar: bool) -> usize {
        let n = points.len();
        let mut knots = Vec::with_capacity(n + 2);
        knots.push(0.0);
        knots.extend((0..n).map(|k| k as f64));
        knots.push((n - 1) as f64);
        self.curve(1, &knots, points, None, planar)
    }

    /// A polynomial B-spline in parameter space (z = 0).
    pub(super) fn spline2(&mut self, c: &NurbsCurve) -> usize {
        let points = c.control_points();
        self.curve(c.degree(), c.knots().as_slice(), &points, None, true)
    }

    /// A NURBS curve in model space.
    pub(super) fn nurbs(&mut self, c: &NurbsCurve) -> usize {
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
    pub(super) fn composite(&mut self, curves: &[usize], planar: bool) -> usize {
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
}
