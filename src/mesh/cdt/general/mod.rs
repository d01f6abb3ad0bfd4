//! The general path, which meshes any region: `seed` (a curvature-sized lattice
//! clipped to the region, in the size `metric` of the surface), `initial` (spade's
//! constrained Delaunay triangulation of the loop vertices and seeds, inside found
//! by flood fill) and `refine` (chordal refinement to a fixed point, with
//! metric-Delaunay flips). The structured path borrows its seeds and its spade
//! fill; refinement also finishes structured meshes the screen did not pass.

pub(super) mod initial;
pub(super) mod refine;
pub(super) mod seed;
