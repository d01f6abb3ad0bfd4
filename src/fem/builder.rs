//! Accumulates a mesh's nodes and elements: mid-side nodes keyed by their edge
//! so neighbouring elements share them, the plane coordinates of cap nodes, and
//! the envelope's ring nodes by station and division, so that pieces meshed
//! apart ([`super::piece`]) share the nodes of the rings between them
//! ([`NodeKey`]).

use std::collections::HashMap;

use glam::{DVec2, DVec3};

use super::{Element, ElementKind, FeMesh};

/// What a node is across pieces: a node of the envelope's rings (station,
/// division), or the mid-side node of the edge between two such nodes. Pieces
/// meshed apart weld their nodes of one key into one node.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum NodeKey {
    /// Corner node at meridian station `.0`, circumferential division `.1`.
    Ring(usize, usize),
    /// Mid-side node of the edge between two ring nodes (in ascending order).
    Mid((usize, usize), (usize, usize)),
}

/// Accumulates nodes and elements; mid-side nodes are keyed by their edge so
/// neighbouring elements share them.
#[derive(Default)]
pub struct Builder {
    /// The mesh so far.
    pub mesh: FeMesh,
    /// Plane coordinates of cap nodes (offset from the axis).
    plane: Vec<Option<DVec2>>,
    mids: HashMap<(usize, usize), usize>,
    /// Ring nodes: (station, division) by node index.
    rings: HashMap<usize, (usize, usize)>,
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

    /// Adds the ring node at meridian station `station`, division `division`.
    pub fn ring_node(
        &mut self,
        p: DVec3,
        plane: Option<DVec2>,
        station: usize,
        division: usize,
    ) -> usize {
        let id = self.node(p, plane);
        self.rings.insert(id, (station, division));
        id
    }

    /// The mesh and each node's key across pieces: ring nodes, and the
    /// mid-side nodes of edges between two ring nodes.
    pub fn finish(self) -> (FeMesh, Vec<Option<NodeKey>>) {
        let mut keys = vec![None; self.mesh.nodes.len()];
        for (&id, &(i, k)) in &self.rings {
            keys[id] = Some(NodeKey::Ring(i, k));
        }
        for (&(a, b), &id) in &self.mids {
            if let (Some(&x), Some(&y)) = (self.rings.get(&a), self.rings.get(&b)) {
                keys[id] = Some(NodeKey::Mid(x.min(y), x.max(y)));
            }
        }
        (self.mesh, keys)
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
