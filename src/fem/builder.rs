//! Accumulates a mesh's nodes and elements: mid-side nodes keyed by their edge
//! so neighbouring elements share them, and the plane coordinates of cap nodes.

use std::collections::HashMap;

use glam::{DVec2, DVec3};

use super::{Element, ElementKind, FeMesh};

/// Accumulates nodes and elements; mid-side nodes are keyed by their edge so
/// neighbouring elements share them.
#[derive(Default)]
pub struct Builder {
    /// The mesh so far.
    pub mesh: FeMesh,
    /// Plane coordinates of cap nodes (offset from the axis).
    plane: Vec<Option<DVec2>>,
    mids: HashMap<(usize, usize), usize>,
    /// Whether elements get mid-side nodes.
    pub quadratic: bool,
}

impl Builder {
    /// An empty builder; `quadratic`: elements get mid-side nodes.
    pub fn new(quadratic: bool) -> Builder {
        Builder {
            quadratic,
            ..Builder::default()
        }
    }

    /// Adds a node.
    pub fn node(&mut self, p: DVec3, plane: Option<DVec2>) -> usize {
        self.mesh.nodes.push(p);
        self.plane.push(plane);
        self.mesh.nodes.len() - 1
    }

    /// Plane coordinates of node `i` (zero if it has none).
    pub fn plane(&self, i: usize) -> DVec2 {
        self.plane[i].unwrap_or(DVec2::ZERO)
    }

    /// The mid-side node of edge (a, b), made at `at()` if new.
    pub fn mid(&mut self, a: usize, b: usize, at: impl FnOnce() -> DVec3) -> usize {
        let key = (a.min(b), a.max(b));
        if let Some(&id) = self.mids.get(&key) {
            return id;
        }
        let id = self.node(at(), None);
        self.mids.insert(key, id);
        id
    }

    /// Whether edge (a, b) has a mid-side node already.
    pub fn has_mid(&self, a: usize, b: usize) -> bool {
        self.mids.contains_key(&(a.min(b), a.max(b)))
    }

    /// Adds a quadrilateral with corners `c`; `mid(b, x, y)` gives the mid-side
    /// node of edge (x, y) when the mesh is quadratic.
    pub fn quad(
        &mut self,
        part: usize,
        c: [usize; 4],
        mid: &mut dyn FnMut(&mut Builder, usize, usize) -> usize,
    ) {
        let mut nodes = c.to_vec();
        let kind = if self.quadratic {
            for k in 0..4 {
                let id = mid(self, c[k], c[(k + 1) % 4]);
                nodes.push(id);
            }
            ElementKind::Quad8
        } else {
            ElementKind::Quad4
        };
        self.mesh.elements.push(Element { kind, nodes, part });
    }
}
