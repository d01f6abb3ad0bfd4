//! What the structured path (`structured`) builds: the lattice's chains (rows
//! seam to seam, or a pole) and the structured mesh of a whole closed patch with
//! the quarter-turn copies of a `sector`. A leaf of the mesher, so the cavities
//! (`cavity`), the sector turns and the output (`output`) read these types
//! without using the path that makes them.

use crate::mesh::cdt::trimesh::TriMesh;

/// A structured mesh of a whole closed patch.
pub(in crate::mesh::cdt) struct Rings {
    /// The triangles, strip by strip from the bottom chain up.
    pub mesh: TriMesh,
    /// The seam edges, as `(triangle, edge)`: left unfixed so that the checks probe
    /// them; the caller fixes them (with [`fix_seam`]) before output or refinement.
    pub seam: Vec<(u32, usize)>,
    /// For every triangle, whether the screen found it within the limits (`false`:
    /// measure it in full); `None` when the patch has no screen.
    pub within: Option<Vec<bool>>,
    /// Vertices added by mending (counted as refinement insertions).
    pub insertions: usize,
    /// For a whole turn of quarters (`sector`): which triangles of the later
    /// quarters are exact turned copies of the first quarter's.
    pub copies: Option<Copies>,
}

/// The triangles of a whole turn that are exact quarter turns of the first
/// quarter's: triangle `t` (past the first quarter) is one when
/// `exact[t % per_quarter]`, so the output's checks, which give a triangle and
/// its exact quarter turn the same verdict, need only the first quarter's.
pub(in crate::mesh::cdt) struct Copies {
    pub per_quarter: usize,
    pub exact: Vec<bool>,
}

/// What a chain of the structured mesh is: a row of vertices at constant v running
/// seam to seam, or a pole — one pole vertex under the middle of each segment of
/// the neighbouring row (they weld into one on output).
#[derive(Clone, Copy, Debug)]
pub(in crate::mesh::cdt) enum Kind {
    Row,
    Pole,
}

/// One chain: its vertices `first..first + len` of the mesh's vertices.
#[derive(Clone, Copy, Debug)]
pub(in crate::mesh::cdt) struct Chain {
    pub v: f64,
    pub kind: Kind,
    pub first: u32,
    pub len: usize,
}
