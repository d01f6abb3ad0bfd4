//! Finite-element shell models of a vessel's pressure envelope, for analysis
//! rather than display: the same exact geometry as the render meshes, but
//! meshed conformingly (parts share the nodes of their junction rings), with
//! quadratic shell elements on each part's mid-surface, loads, supports and
//! materials, written for CalculiX/Abaqus (`.inp`), Gmsh (`.msh` 4.1) and
//! ParaView (`.vtu`), and read back from CalculiX's `.frd` results.
//!
//! The pipeline: [`meridian`] walks the vessel's mid-surface profile (closed
//! form, from [`crate::operating::profile`]) and places stations along it,
//! graded towards every junction; [`envelope`] sweeps the stations into rings of
//! 8-node quadrilaterals (S8R) and closes each pole with a quadrilateral O-grid
//! ([`cap`]); [`conditions`] attaches a load case; [`inp`], [`msh`] and [`vtu`]
//! write it; [`frd`] and [`results`] read a CalculiX run back and classify the
//! stresses per part, and [`glb`] draws the deformed shape with von Mises
//! colours; [`quality`] measures the mesh and [`quality_table`] reports it. Nozzles: [`window`] and [`nozzle`]
//! on cylindrical courses (radial or not) and off a head's centre (charted by
//! [`head_window`]), [`head_nozzle`] on a head's centre.
//! Supports: a vertical vessel's [`skirt`] is a shell part hanging from the
//! envelope's ring at its top, held at its base; a horizontal vessel's
//! [`saddle`]s are shell parts (top plate bonded to the course, web, base
//! plate) sharing the course's ring at the web, held at their base plates.
//!
//! Incremental: [`envelope::plan`] lays out the stations, divisions and
//! windows; each [`piece`] (an envelope part with its nozzles, saddles and
//! pads, or the skirt) is meshed from its own inputs, or taken from a
//! [`FemCache`] while they are unchanged, and [`assemble`] welds the pieces on
//! their shared rings.

pub mod assemble;
pub mod builder;
pub mod cache;
pub mod cap;
pub mod conditions;
pub mod envelope;
pub mod error;
pub mod frd;
pub mod glb;
pub mod grading;
pub mod head_nozzle;
pub mod head_window;
pub mod inp;
pub mod meridian;
pub mod msh;
pub mod nozzle;
pub mod piece;
pub mod quality;
pub mod quality_table;
pub mod results;
pub mod saddle;
pub mod skirt;
pub mod vtu;
pub mod window;
pub mod zones;

pub use assemble::{build_envelope, build_envelope_cached};
pub use cache::{FemCache, FemCounters};
pub use conditions::{FeModel, LoadCase, Support};
pub use envelope::FemOptions;
pub use error::FemError;

use glam::DVec3;

/// The kind of a shell element. Node order is Abaqus's: corners counter-clockwise
/// about the outward normal, then the mid-side nodes of edges 1-2, 2-3, ...
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum ElementKind {
    /// 4-node quadrilateral (S4R).
    Quad4,
    /// 8-node quadrilateral (S8R).
    Quad8,
    /// 3-node triangle (S3).
    Tri3,
    /// 6-node triangle (S6).
    Tri6,
}

impl ElementKind {
    /// Number of corner nodes.
    pub fn corners(self) -> usize {
        match self {
            ElementKind::Quad4 | ElementKind::Quad8 => 4,
            ElementKind::Tri3 | ElementKind::Tri6 => 3,
        }
    }

    /// Whether the element has mid-side nodes.
    pub fn quadratic(self) -> bool {
        matches!(self, ElementKind::Quad8 | ElementKind::Tri6)
    }
}

/// One shell element: its kind, node indices (0-based, Abaqus order) and part.
#[derive(Clone, Debug, PartialEq)]
pub struct Element {
    /// Kind.
    pub kind: ElementKind,
    /// Node indices.
    pub nodes: Vec<usize>,
    /// Index into [`FeMesh::parts`].
    pub part: usize,
}

/// A part of the mesh: a design part (`V-101/S1`) with its shell thickness.
#[derive(Clone, Debug, PartialEq)]
pub struct FePart {
    /// Set name: vessel tag and part id, `V-101/S1`.
    pub name: String,
    /// Design part id.
    pub id: String,
    /// Shell thickness, mm.
    pub thickness: f64,
    /// Where the nodes sit in the section, in thicknesses along the element
    /// normal (CalculiX's `OFFSET`: the mid-surface lies `offset × thickness`
    /// behind the nodes): 0 on the mid-surface; a plate bonded onto a course's
    /// outside is offset so that its inner face is the course's.
    pub offset: f64,
}

/// A conforming shell mesh in the plant frame, mm.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct FeMesh {
    /// Node positions.
    pub nodes: Vec<DVec3>,
    /// Elements.
    pub elements: Vec<Element>,
    /// Parts (element sets).
    pub parts: Vec<FePart>,
    /// Nodes on a real boundary of the shell (an open end), by index.
    pub boundary: Vec<usize>,
    /// Nodes on a discontinuity inside a part (a tangent line between two of
    /// its pieces, e.g. a head's knuckle and crown); junctions between parts
    /// are the nodes their elements share.
    pub junctions: Vec<usize>,
    /// The vessel axis in the plant frame: a point and a unit direction.
    pub axis: (DVec3, DVec3),
    /// The open ends of the nozzle necks meshed.
    pub necks: Vec<NeckEnd>,
    /// What the mesh leaves out of the design, and why.
    pub notes: Vec<String>,
    /// Parts outside the pressure envelope (a skirt): no pressure acts on
    /// them and they bound no liquid.
    pub structural: Vec<usize>,
}

/// The open end of a nozzle neck (the flange's back), where the closed
/// flange's pressure thrust is applied.
#[derive(Clone, Debug, PartialEq)]
pub struct NeckEnd {
    /// Nozzle mark.
    pub mark: String,
    /// Index of the neck's part.
    pub part: usize,
    /// Corner nodes round the end, in order.
    pub nodes: Vec<usize>,
    /// Mid-side node of the edge from `nodes[j]` to `nodes[j + 1]` (empty for
    /// linear elements).
    pub mids: Vec<usize>,
    /// Centre of the end on the neck axis, plant frame.
    pub centre: DVec3,
    /// Unit neck axis, outwards, plant frame.
    pub axis: DVec3,
    /// Neck mid-surface radius, mm.
    pub radius: f64,
}

impl FeMesh {
    /// The node indices used by the elements of part `part`, sorted.
    pub fn part_nodes(&self, part: usize) -> Vec<usize> {
        let mut out: Vec<usize> = self
            .elements
            .iter()
            .filter(|e| e.part == part)
            .flat_map(|e| e.nodes.iter().copied())
            .collect();
        out.sort_unstable();
        out.dedup();
        out
    }
}

/// The FE model of vessel `tag` of `design`: its envelope mesh with load case
/// `case` attached.
///
/// # Errors
///
/// [`FemError`]: an unknown tag, an invalid design (its rule violations, as
/// text), or what [`build_envelope`] and [`conditions::conditions`] refuse.
pub fn vessel_model(
    design: &crate::design::Design,
    tag: &str,
    options: &FemOptions,
    case: LoadCase,
    table: &crate::calc::MaterialTable,
) -> Result<FeModel, FemError> {
    vessel_model_cached(design, tag, options, case, table, &mut FemCache::default())
}

/// As [`vessel_model`], meshing only the pieces of the envelope whose inputs
/// differ from those `cache` holds ([`build_envelope_cached`]); loads,
/// supports and materials are attached afresh.
///
/// # Errors
///
/// As [`vessel_model`].
pub fn vessel_model_cached(
    design: &crate::design::Design,
    tag: &str,
    options: &FemOptions,
    case: LoadCase,
    table: &crate::calc::MaterialTable,
    cache: &mut FemCache,
) -> Result<FeModel, FemError> {
    let index = design
        .vessels
        .iter()
        .position(|v| v.tag == tag)
        .ok_or_else(|| FemError::NoVessel {
            tag: tag.into(),
            known: design
                .vessels
                .iter()
                .map(|v| v.tag.as_str())
                .collect::<Vec<_>>()
                .join(", "),
        })?;
    let vessel = &design.vessels[index];
    let resolved = crate::constraints::resolve_vessel(vessel, index).map_err(|violations| {
        FemError::Profile {
            vessel: tag.into(),
            message: violations
                .iter()
                .map(|v| v.to_string())
                .collect::<Vec<_>>()
                .join("; "),
        }
    })?;
    let mesh = build_envelope_cached(vessel, &resolved, options, cache)?;
    conditions::conditions(mesh, vessel, &resolved, case, table)
}
