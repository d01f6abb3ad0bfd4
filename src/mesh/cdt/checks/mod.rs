//! The checks every path's triangles are held to, apart from the paths that make
//! them: `measure` (a probe's deviation from the surface, the probes of an edge),
//! `certify` (closed-form bounds over a whole triangle on planes, cylinders and
//! spheres), `peak` (the cubic deviation model and where it peaks) and `screen`
//! (the structured path's batch screen of whole strips, built from the three).
//! The general path's refinement assesses triangles with the same three. A leaf
//! group of the mesher: it uses only the shared types (`patch`, `trimesh`).

pub(super) mod certify;
pub(super) mod measure;
pub(super) mod peak;
pub(super) mod screen;
