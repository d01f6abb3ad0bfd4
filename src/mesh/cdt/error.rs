//! Errors of the constrained-Delaunay patch mesher.
//!
//! Every way [`mesh_region`](super::mesh_region) can fail is one variant here: bad
//! options or regions are rejected before any work, spade failures that would lose
//! a loop vertex or a loop segment are reported with the loop and vertex they hit,
//! and refinement that would exceed its vertex budget stops with a typed error
//! instead of running away.

use thiserror::Error;

use crate::mesh::OptionsError;

/// A failure of the constrained-Delaunay patch mesher.
#[derive(Debug, Error, Clone, PartialEq)]
pub enum CdtError {
    /// The tessellation options are invalid.
    #[error(transparent)]
    Options(#[from] OptionsError),
    /// A loop of the region is unusable (too few vertices, a non-finite or
    /// out-of-range coordinate, zero area or the wrong orientation).
    #[error("loop {loop_index} of the region: {reason}")]
    InvalidLoop {
        /// 0 for the outer loop, 1 + k for hole k.
        loop_index: usize,
        /// What is wrong with it.
        reason: &'static str,
    },
    /// The surface evaluated to a non-finite point or normal at a vertex.
    #[error("the surface is not finite at (u, v) = ({u}, {v})")]
    NonFiniteSurface {
        /// u parameter of the vertex (as given, before wrapping).
        u: f64,
        /// v parameter of the vertex.
        v: f64,
    },
    /// Spade rejected the vertex set.
    #[error("spade could not triangulate the region: {0}")]
    Triangulation(spade::InsertionError),
    /// A loop vertex was merged with another vertex at the same (u, v), so it would
    /// be lost from the output.
    #[error("loop {loop_index}, vertex {vertex}: coincides with another vertex in (u, v)")]
    LoopVertexLost {
        /// 0 for the outer loop, 1 + k for hole k.
        loop_index: usize,
        /// Index of the vertex in its loop.
        vertex: usize,
    },
    /// A loop segment could not be inserted as one constraint edge (it crosses or
    /// touches another loop), so the region's boundary would not be kept.
    #[error("loop {loop_index}, segment {segment}: cannot be a constraint edge ({reason})")]
    ConstraintFailed {
        /// 0 for the outer loop, 1 + k for hole k.
        loop_index: usize,
        /// Index of the segment's first vertex in its loop.
        segment: usize,
        /// Why spade refused it.
        reason: &'static str,
    },
    /// The loops do not bound a region: the inside leaks to the convex hull, so a
    /// loop is open, crosses another or has the wrong orientation.
    #[error("the loops do not enclose a region (crossing loops or wrong orientation)")]
    RegionNotClosed,
    /// The region lies on both sides of a loop: a loop inside a hole (nested
    /// holes, such as two openings one inside the other). Meshed, the outer hole
    /// would be covered and its loop left inside the mesh.
    #[error(
        "loop {loop_index} has the region on both sides: a loop lies inside a hole \
         (one opening inside another)"
    )]
    NestedLoop {
        /// 0 for the outer loop, 1 + k for hole k.
        loop_index: usize,
    },
    /// Meshing would need more vertices than the budget allows
    /// ([`TessellationOptions::max_vertices`](crate::mesh::TessellationOptions::max_vertices),
    /// `--max-vertices` on the command line).
    #[error(
        "the patch needs at least {needed} vertices, more than max_vertices = \
         {max_vertices} allows (--max-vertices; or the tolerance is too small for \
         the patch)"
    )]
    BudgetExceeded {
        /// The option's value: the most vertices one patch region may have.
        max_vertices: usize,
        /// Vertices the region was found to need when meshing stopped (its loop
        /// vertices included): at least this many, more than `max_vertices`.
        needed: usize,
    },
    /// Refinement would grow the mesh it was given many times over: the
    /// surface's sizing does not describe it (a degenerate or nearly degenerate
    /// patch), and going on would spend seconds and gigabytes before reaching
    /// the vertex budget. Stopped early, at a bound set from the seeded mesh.
    #[error(
        "refinement does not converge: it needs more than {limit} vertices from the \
         {seeded} the patch was seeded with (the patch is too thin or too curved for \
         the tolerance)"
    )]
    RefinementRunaway {
        /// Vertices of the mesh refinement started from.
        seeded: usize,
        /// The vertex count it was stopped at.
        limit: usize,
    },
    /// Refinement did not reach the tolerance within its pass limit.
    #[error("refinement did not converge in {passes} passes ({remaining} triangles still over)")]
    NotConverged {
        /// Passes run.
        passes: usize,
        /// Triangles still over the tolerance.
        remaining: usize,
    },
    /// A triangle of the result is inverted or of zero area in 3D although it is not
    /// collapsed at a pole or seam; the mesh is withheld rather than returned broken.
    #[error("triangle {triangle} is inverted or flat in 3D")]
    InvalidTriangle {
        /// Index of the triangle in the mesh being built.
        triangle: usize,
    },
}
