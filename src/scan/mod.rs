//! As-built against as-designed: laser scans of a vessel compared with its exact
//! design surfaces, part by part, in the vessel's own coordinates.
//!
//! ```text
//! points (XYZ/CSV, PLY, LAS/LAZ; streamed) ──▶ register (ICP on the exact NURBS, trimmed)
//!   ──▶ project (point inversion: part, patch, u, v, signed normal deviation)
//!   ──▶ fit (least-squares NURBS per patch with smoothing, net grown to the noise;
//!       or, for an ordered CMM grid, exact interpolation: `grid`)
//!   ──▶ checks (UG-80 roundness, UG-81 heads, dents, peaking, plumbness,
//!       API 653 settlement, volume) ──▶ report (HTML, JSON) and a coloured GLB;
//!       the fitted patches as STEP faces (`step`)
//! ```
//!
//! `simulate` draws synthetic scans with known defects, noise, gaps and a site
//! pose from the same exact surfaces, for tests and demos.

mod band;
mod cells;
mod envelope;
mod error;
mod features;
mod las_file;
mod profile;
mod project;
mod random;
mod sample;

pub mod checks;
pub mod defects;
pub mod fit;
pub mod glb;
pub mod grid;
pub mod grid_file;
pub mod inspect;
pub mod points;
pub mod register;
pub mod report;
pub mod settlement;
pub mod simulate;
pub mod step;
pub mod unrolled;

pub use envelope::{Envelope, Role, ScanPart, ScanSurface, ShellMaterial};
pub use error::ScanError;
pub use profile::{angle_of_u, u_of_angle};
pub use project::{Foot, Targets};
pub use random::Random;
