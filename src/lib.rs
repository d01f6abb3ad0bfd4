//! # vesselcad
//!
//! A data-oriented engine for parametric process vessels: shells, heads, cones,
//! skirts, saddles, legs, lugs, boots and nozzles described by parameters, kept as
//! exact rational NURBS surfaces, meshed within a chordal tolerance, and written as
//! glTF and drawing sheets — incrementally, so an edit redoes only the work that
//! depends on it.
//!
//! ## Pipeline
//!
//! ```text
//! design file / edit ──design──▶ checked Design ──model──▶ ECS entities
//!   ──systems: Validate → Constrain → Geometry → Tessellate → Project → Export──▶
//!   exact NURBS patches, packed meshes, views ──export / drawing──▶ GLB, SVG, DXF
//! ```
//!
//! ## Modules, bottom of the data flow first
//!
//! - [`nurbs`] — the kernel: knot vectors, basis functions, rational curves and
//!   surfaces, batched grid evaluation, refinement, transforms, point inversion,
//!   intersections. Knows nothing of ECS or vessels.
//! - [`parts`] — vessel-part parameters to their exact patches in the part's local
//!   frame (axis +Z), with standard pipe and flange tables.
//! - [`format`](mod@format) — the `vesselcad/1` types: serde types, errors
//!   naming a value by its JSON path, unit conversion. A leaf: the rules read it.
//! - [`design`] — design files: loading with exact error paths, rule checks,
//!   canonical save; re-exports [`format`](mod@format)'s types.
//! - [`constraints`] — one vessel's rules and resolution: the stack along the axis,
//!   inherited diameters, nozzles on hosts, clearances, frames.
//! - [`operating`] — liquid volume at a level, operating weight, centre of gravity.
//! - [`mesh`] — render meshes: opening cuts, a patch's (u, v) region, the
//!   constrained-Delaunay mesher and the content-keyed stores of meshes and cuts.
//! - [`project`] — drawing views of each vessel (exact silhouettes, edges, hidden
//!   lines).
//! - [`components`] and [`systems`] — every ECS component and resource, and the
//!   staged schedule that keeps derived data consistent.
//! - [`model`] — the `World`, the schedule and transactional [`model::Edit`]s: the
//!   front door.
//! - [`export`] — scenes written as binary glTF (whole or deltas).
//! - [`drawing`] — drawing sheets from the views, written as SVG and DXF.
//! - [`json_schema`] — the JSON Schema of the design format, with the rules' ranges.
//! - [`report`] — the figures `vesselcad info` prints.
//! - [`plant`] — plant generation, simulation and the plant-scale bench.
//! - [`server`] — live redesign sessions (`vesselcad serve`).
//! - [`allocator`] — the binary's allocator settings.
//!
//! ## Units and tolerances
//!
//! Lengths are millimetres and angles degrees at every public boundary; radians are
//! used inside the kernel. The modelling tolerance [`MODEL_EPSILON`] (point
//! coincidence, knot equality) is separate from the chordal tolerance of meshes
//! ([`mesh::TessellationOptions`]).

pub mod allocator;
pub mod calc;
#[path = "../components/mod.rs"]
pub mod components;
pub mod constraints;
pub mod design;
pub mod drawing;
pub mod exchange;
pub mod export;
pub mod fab;
pub mod fem;
pub mod format;
pub mod json_schema;
pub mod mesh;
pub mod model;
pub mod nurbs;
pub mod operating;
pub mod parts;
pub mod plant;
pub mod project;
pub mod report;
pub mod scan;
pub mod server;
pub mod store;
#[path = "../systems/mod.rs"]
pub mod systems;
pub mod weights;

/// The README's Rust snippets, compiled and run as doctests.
#[cfg(doctest)]
#[doc = include_str!("../README.md")]
pub struct ReadmeDoctests;

/// Modelling epsilon in mm: two points closer than this are the same point.
/// Not a meshing tolerance.
pub const MODEL_EPSILON: f64 = 1e-9;
