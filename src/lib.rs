//! # vesselcad
//!
//! A data-oriented engine for parametric process vessels: shells, heads, cones,
//! skirts, saddles and nozzles described by parameters, kept as exact rational
//! NURBS surfaces.
//!
//! ## Pipeline
//!
//! ```text
//! parameters (mm, degrees) ──parts──▶ exact NURBS patches ──nurbs::grid──▶ samples
//! ```
//!
//! - [`nurbs`] — the kernel: knot vectors, basis functions, rational curves and
//!   surfaces, batched grid evaluation, refinement, transforms, point inversion.
//! - [`parts`] — functions from vessel-part parameters to their exact patches in the
//!   part's local frame (axis +Z).
//! - [`project`] — drawing views of each vessel (exact silhouettes, edges, hidden
//!   lines), cached per entity per view by the Project stage.
//! - [`drawing`] — drawing sheets from those views (layout, dimensions, tables),
//!   written as SVG and DXF: [`drawing::sheet_svg`].
//!
//! ## Units and tolerances
//!
//! Lengths are millimetres and angles degrees at every public boundary; radians are
//! used inside the kernel. The modelling tolerance [`MODEL_EPSILON`] (point
//! coincidence, knot equality) is separate from any meshing tolerance.

pub mod allocator;
#[path = "../components/mod.rs"]
pub mod components;
pub mod constraints;
pub mod design;
pub mod drawing;
pub mod exchange;
pub mod export;
pub mod mesh;
pub mod model;
pub mod nurbs;
pub mod operating;
pub mod parts;
pub mod plant;
pub mod project;
pub mod report;
pub mod server;
#[path = "../systems/mod.rs"]
pub mod systems;

/// Modelling epsilon in mm: two points closer than this are the same point.
/// Not a meshing tolerance.
pub const MODEL_EPSILON: f64 = 1e-9;
