//! Constraint resolution: from one vessel's design to the resolved parameters and
//! frames of every part, nozzle and note.
//!
//! This is the Constrain stage of the data flow, written as a pure function so that
//! both the ECS systems (per dirty vessel) and the edit transactions (before anything
//! is written) use the same rules. It applies:
//!
//! - **implicit rules** of each part (the part builders' `validate`, plus vessel
//!   rules such as saddle width < L/2 or a nozzle smaller than its host);
//! - **explicit relations**: the stack layout along the axis (lengthening a course
//!   moves what is above it), heads take the OD of the course they close, reducer
//!   ends match the courses they join, the skirt top matches the bottom course,
//!   saddles fit the shell OD and default to 0.2 L from each tangent line, nozzles
//!   stay on their host (orientation and elevation kept, the neck adapts to keep the
//!   projection), notes follow their target;
//! - **carried data** that no builder reads (design conditions, wall thicknesses,
//!   corrosion allowance) must still make physical sense.
//!
//! Every broken rule becomes a [`RuleViolation`] with its JSON path; all of them are
//! reported, not only the first.

mod clearances;
mod conditions;
mod footprints;
mod frames;
mod head_limits;
mod head_seams;
mod names;
pub(crate) use head_limits::RATIO as ELLIPSOIDAL_RATIO;
pub(crate) use names::MAX_NAME_CHARS;
mod notes;
mod nozzles;
mod operating;
mod part_error;
mod shell_nozzle;
mod stack;
mod support_clearances;
mod supports;

pub use crate::parts::PartGeometry;
pub use conditions::{
    ABSOLUTE_ZERO, FULL_VACUUM, MAX_PRESSURE, MAX_REVISION, MAX_SPECTRAL_ACCELERATION,
    MAX_TEMPERATURE, MAX_TITLE_TEXT, MAX_WIND_SPEED,
};
pub use frames::{orientation_direction, vessel_frame};
pub use head_seams::unturned_frame;
pub use operating::{stack_of, state_of_design};
pub use shell_nozzle::{MAX_HILLSIDE, MAX_INCLINATION};

use glam::{DAffine3, DVec3};

use crate::format::{RuleViolation, VesselDesign, VesselKind};
use crate::parts::Nozzle;

/// A part with its resolved parameters and its place in the vessel.
#[derive(Clone, Debug, PartialEq)]
pub struct ResolvedPart {
    /// Part id.
    pub id: String,
    /// Part local frame → vessel local frame.
    pub frame: DAffine3,
    /// The resolved parameters the part builder takes.
    pub geometry: PartGeometry,
    /// Axial extent `[start, end]` of the part in the vessel frame, mm.
    pub span: (f64, f64),
    /// Index in [`ResolvedVessel::parts`] of the part this one is cut into, like a
    /// nozzle into its host: a boot's shell course. `None` for every other part.
    pub host: Option<usize>,
}

/// A nozzle with its resolved parameters and frame.
#[derive(Clone, Debug, PartialEq)]
pub struct ResolvedNozzle {
    /// Mark.
    pub mark: String,
    /// Index of the host part in [`ResolvedVessel::parts`].
    pub host: usize,
    /// Nozzle local frame (axis +Z, neck start at the origin) → vessel local frame.
    pub frame: DAffine3,
    /// The nozzle part parameters.
    pub geometry: Nozzle,
    /// Reinforcing pad `(outside diameter, thickness)`, mm.
    pub pad: Option<(f64, f64)>,
}

/// What a note points at.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum NoteTarget {
    /// The vessel itself.
    Vessel,
    /// A part, by index.
    Part(usize),
    /// A nozzle, by index.
    Nozzle(usize),
    /// Another note, by index.
    Note(usize),
}

/// A note with its resolved anchor.
#[derive(Clone, Debug, PartialEq)]
pub struct ResolvedNote {
    /// Note id.
    pub id: String,
    /// What it annotates.
    pub target: NoteTarget,
    /// The target's anchor point, vessel frame, mm.
    pub anchor: DVec3,
    /// Where the text sits: anchor + offset, vessel frame, mm.
    pub position: DVec3,
}

/// Everything the later stages need of one vessel, resolved and valid.
#[derive(Clone, Debug, PartialEq)]
pub struct ResolvedVessel {
    /// Tag.
    pub tag: String,
    /// Kind.
    pub kind: VesselKind,
    /// Vessel local frame → plant frame.
    pub frame: DAffine3,
    /// Parts in design order.
    pub parts: Vec<ResolvedPart>,
    /// Nozzles in design order.
    pub nozzles: Vec<ResolvedNozzle>,
    /// Notes in design order.
    pub notes: Vec<ResolvedNote>,
    /// Tangent-to-tangent length, mm.
    pub tangent_length: f64,
    /// Overall axial extent of the vessel incl. heads and supports, mm.
    pub extent: (f64, f64),
    /// Largest course outside diameter, mm.
    pub max_diameter: f64,
    /// The operating figures, when the vessel carries operating data (worked
    /// out while checking it; the model takes them rather than working them
    /// out again). `None` otherwise, or when not known.
    pub operating: Option<KnownOperating>,
}

/// Operating figures worked out while a vessel was checked, with the inputs
/// besides its resolved stack they were worked out from.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct KnownOperating {
    /// The vessel's operating data.
    pub data: Option<crate::format::OperatingDesign>,
    /// The metal density, kg/m³.
    pub metal_density: f64,
    /// The figures.
    pub state: crate::operating::OperatingFigures,
}

/// Collects violations with a common path prefix and entity naming.
pub(crate) struct Report<'a> {
    pub prefix: String,
    pub tag: &'a str,
    pub violations: Vec<RuleViolation>,
}

impl Report<'_> {
    /// Records a broken rule at `path` (relative to the vessel) for `entity`.
    ///
    /// The entity is `tag/id`; where the tag or id is empty (itself an error) it is
    /// named by its place instead (`vessels[0]`, `V-101/nozzles[2]`), so that every
    /// violation names an entity.
    pub fn push(
        &mut self,
        path: impl AsRef<str>,
        entity: Option<&str>,
        field: &str,
        value: impl ShowValue,
        rule: impl Into<String>,
    ) {
        let path = path.as_ref();
        let tag = if self.tag.trim().is_empty() {
            self.prefix.as_str()
        } else {
            self.tag
        };
        let entity = match entity {
            Some(id) if id.trim().is_empty() => {
                format!("{tag}/{}", path.split('.').next().unwrap_or(path))
            }
            Some(id) => format!("{tag}/{id}"),
            None => tag.to_string(),
        };
        self.violations.push(RuleViolation {
            path: format!("{}.{}", self.prefix, path),
            entity,
            field: field.to_string(),
            value: value.show(),
            rule: rule.into(),
        });
    }
}

/// How a violation shows the offending value: text as written, numbers compactly
/// (`1e300` rather than 301 digits).
pub(crate) trait ShowValue {
    /// The value as a violation shows it.
    fn show(&self) -> String;
}

impl ShowValue for f64 {
    fn show(&self) -> String {
        let magnitude = self.abs();
        if self.is_finite() && magnitude != 0.0 && !(1e-4..1e9).contains(&magnitude) {
            format!("{self:e}")
        } else {
            self.to_string()
        }
    }
}

impl ShowValue for u32 {
    fn show(&self) -> String {
        self.to_string()
    }
}

impl ShowValue for usize {
    fn show(&self) -> String {
        self.to_string()
    }
}

impl ShowValue for str {
    fn show(&self) -> String {
        self.to_string()
    }
}

impl ShowValue for String {
    fn show(&self) -> String {
        self.clone()
    }
}

impl<T: ShowValue + ?Sized> ShowValue for &T {
    fn show(&self) -> String {
        (**self).show()
    }
}

/// Resolves and checks one vessel. `index` is its position in the design's vessel
/// list (for error paths).
pub fn resolve_vessel(
    vessel: &VesselDesign,
    index: usize,
) -> Result<ResolvedVessel, Vec<RuleViolation>> {
    if names::too_long(&vessel.tag) {
        // Checked first and alone: every other violation would repeat the tag.
        let shown = names::shown(&vessel.tag);
        return Err(vec![RuleViolation {
            path: format!("vessels[{index}].tag"),
            entity: format!("vessels[{index}]"),
            field: "tag".into(),
            value: shown,
            rule: names::rule(),
        }]);
    }
    let mut report = Report {
        prefix: format!("vessels[{index}]"),
        tag: &vessel.tag,
        violations: Vec::new(),
    };
    let frame = frames::checked_vessel_frame(vessel, &mut report);
    frames::check_unique_ids(vessel, &mut report);
    let stack = stack::layout(vessel, &mut report);
    let mut parts = stack.parts;
    supports::place(
        vessel,
        &stack.courses,
        stack.tangent_length,
        &mut parts,
        &mut report,
    );
    conditions::check(vessel, &parts, &mut report);
    let operating = operating::check(vessel, frame, &parts, &mut report);
    let nozzles = nozzles::place(vessel, &parts, &stack.courses, &mut report);
    head_seams::choose(vessel, &mut parts, &nozzles, &mut report);
    let notes = notes::place(vessel, &parts, &nozzles, &mut report);
    if !report.violations.is_empty() {
        return Err(report.violations);
    }
    let parts: Vec<ResolvedPart> = parts.into_iter().flatten().collect();
    let extent = parts
        .iter()
        .fold((0.0f64, stack.tangent_length), |(lo, hi), p| {
            (lo.min(p.span.0), hi.max(p.span.1))
        });
    Ok(ResolvedVessel {
        tag: vessel.tag.clone(),
        kind: vessel.kind,
        frame,
        parts,
        nozzles,
        notes,
        tangent_length: stack.tangent_length,
        extent,
        max_diameter: stack
            .courses
            .iter()
            .map(|c| c.diameter_max())
            .fold(0.0, f64::max),
        operating,
    })
}
