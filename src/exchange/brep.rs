//! The B-rep data of a vessel as the writers read it: edge curves, edges,
//! oriented edges with their pcurves, trimmed faces, shells (faces joined
//! through shared edges, closed when every edge is used twice) and nozzle
//! connection points. [`vessel_brep`](super::vessel_brep) builds it.

use std::collections::HashMap;

use glam::{DAffine3, DVec2, DVec3};

use crate::nurbs::{KnotVector, NurbsCurve, NurbsSurface};

/// An edge's curve, in the vessel frame.
#[derive(Clone, Debug, PartialEq)]
pub enum EdgeCurve {
    /// An exact isocurve of a patch, over its own parameter range.
    Nurbs(NurbsCurve),
    /// An opening's intersection loop, or an arc of it: a polynomial B-spline
    /// over the neck's parameter, the exact curve's samples joined by straight
    /// segments while the B-rep is built, fitted as a cubic within the exchange
    /// tolerance once it is (see `fit`). Each use's pcurve holds the control
    /// points of a B-spline in (u, v) on this curve's knots and degree.
    Loop(NurbsCurve),
}

impl EdgeCurve {
    /// The parameter range.
    pub fn domain(&self) -> (f64, f64) {
        match self {
            EdgeCurve::Nurbs(c) | EdgeCurve::Loop(c) => c.domain(),
        }
    }

    /// The point at parameter `t`.
    pub fn point(&self, t: f64) -> DVec3 {
        match self {
            EdgeCurve::Nurbs(c) | EdgeCurve::Loop(c) => c.point(t),
        }
    }

    /// A use's pcurve as a B-spline in (u, v) (z = 0) over this curve's
    /// parameter: a straight line over the range of an exact side, the
    /// control points `pcurve` on the loop's knots for a loop.
    ///
    /// # Errors
    ///
    /// The kernel's error where the points do not fit the knots.
    pub fn pcurve(&self, pcurve: &[DVec2]) -> Result<NurbsCurve, crate::nurbs::NurbsError> {
        let points: Vec<DVec3> = pcurve.iter().map(|p| p.extend(0.0)).collect();
        match self {
            EdgeCurve::Nurbs(c) => {
                let (a, b) = c.domain();
                NurbsCurve::try_polynomial(KnotVector::try_new(1, vec![a, a, b, b])?, &points)
            }
            EdgeCurve::Loop(c) => NurbsCurve::try_polynomial(c.knots().clone(), &points),
        }
    }
}

/// An edge between two vertices (equal for a closed edge).
#[derive(Clone, Debug, PartialEq)]
pub struct Edge {
    /// Index of the vertex at the curve's start.
    pub start: usize,
    /// Index of the vertex at the curve's end.
    pub end: usize,
    /// The curve.
    pub curve: EdgeCurve,
}

/// One use of an edge in a face's loop.
#[derive(Clone, Debug, PartialEq)]
pub struct OrientedEdge {
    /// Index of the edge.
    pub edge: usize,
    /// Whether the loop runs along the edge's curve direction.
    pub forward: bool,
    /// The pcurve in the face's (u, v), in the edge's direction and over its
    /// parameter ([`EdgeCurve::pcurve`]): two points for an exact edge (its
    /// ends, a straight line), control points on the curve's knots for a loop
    /// (the first and last are its ends).
    pub pcurve: Vec<DVec2>,
}

/// A face: one patch, trimmed.
#[derive(Clone, Debug, PartialEq)]
pub struct Face {
    /// Index of the part or nozzle in [`VesselBrep::nodes`].
    pub node: usize,
    /// Patch name (`"crown"`, `"leg 2"`).
    pub patch: String,
    /// The exact surface, vessel frame.
    pub surface: NurbsSurface,
    /// Outer loop, counter-clockwise in (u, v).
    pub outer: Vec<OrientedEdge>,
    /// Holes, clockwise in (u, v).
    pub holes: Vec<Vec<OrientedEdge>>,
}

/// Faces joined through shared edges.
#[derive(Clone, Debug, PartialEq)]
pub struct Shell {
    /// Indices of the faces.
    pub faces: Vec<usize>,
    /// Every edge of the shell is used twice.
    pub closed: bool,
}

/// A nozzle's connection point: where piping connects.
#[derive(Clone, Debug, PartialEq)]
pub struct Port {
    /// The nozzle's mark.
    pub mark: String,
    /// Flange gasket face centre, vessel frame, mm.
    pub origin: DVec3,
    /// Outward axis (unit).
    pub axis: DVec3,
    /// A unit direction across the axis (the nozzle frame's X).
    pub across: DVec3,
    /// Size, rating and facing, e.g. `"NPS 6 CL150 RF"`.
    pub description: String,
}

/// A vessel's B-rep, vessel frame.
#[derive(Clone, Debug, PartialEq)]
pub struct VesselBrep {
    /// Tag.
    pub tag: String,
    /// Vessel frame → plant frame.
    pub frame: DAffine3,
    /// Part ids and nozzle marks, design order.
    pub nodes: Vec<String>,
    /// Vertices.
    pub vertices: Vec<DVec3>,
    /// Edges.
    pub edges: Vec<Edge>,
    /// Faces.
    pub faces: Vec<Face>,
    /// Shells.
    pub shells: Vec<Shell>,
    /// Nozzle connection points.
    pub ports: Vec<Port>,
    /// The exchange tolerance its opening loops were fitted to, mm: each
    /// edge's curve and its pcurves' images lie within it of each other.
    pub tolerance: f64,
}

/// Faces joined by shared edges (union–find), in order of their first face.
pub(super) fn shells(faces: &[Face], edge_count: usize) -> Vec<Shell> {
    let mut parent: Vec<usize> = (0..faces.len()).collect();
    fn root(parent: &mut [usize], mut i: usize) -> usize {
        while parent[i] != i {
            parent[i] = parent[parent[i]];
            i = parent[i];
        }
        i
    }
    let mut first_face: Vec<Option<usize>> = vec![None; edge_count];
    let mut uses = vec![0usize; edge_count];
    for (f, face) in faces.iter().enumerate() {
        for e in face.outer.iter().chain(face.holes.iter().flatten()) {
            uses[e.edge] += 1;
            match first_face[e.edge] {
                None => first_face[e.edge] = Some(f),
                Some(g) => {
                    let (a, b) = (root(&mut parent, f), root(&mut parent, g));
                    parent[a.max(b)] = a.min(b);
                }
            }
        }
    }
    let mut shells: Vec<Shell> = Vec::new();
    let mut index: HashMap<usize, usize> = HashMap::new();
    for f in 0..faces.len() {
        let r = root(&mut parent, f);
        let s = *index.entry(r).or_insert_with(|| {
            shells.push(Shell {
                faces: Vec::new(),
                closed: true,
            });
            shells.len() - 1
        });
        shells[s].faces.push(f);
    }
    for shell in &mut shells {
        shell.closed = shell.faces.iter().all(|&f| {
            let face = &faces[f];
            face.outer
                .iter()
                .chain(face.holes.iter().flatten())
                .all(|e| uses[e.edge] == 2)
        });
    }
    shells
}
