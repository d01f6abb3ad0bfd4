//! What the last run of the schedule could not do ([`ModelErrors`]): rule
//! violations found in the world (normally none: edits are checked before they
//! are written), and parts, nozzles and patches whose geometry could not be
//! built ([`BuildFailure`]). A build failure is not a broken design rule: it
//! names the part or nozzle by its design path and stable id, the stage that
//! failed, and the typed cause ([`BuildCause`]: the cutter's [`CutError`], the
//! layout's [`LayoutError`], the mesher's [`CdtError`] or the part builder's
//! [`PartError`]).

use bevy_ecs::resource::Resource;
use thiserror::Error;

use crate::format::RuleViolation;
use crate::mesh::cdt::CdtError;
use crate::mesh::{CutError, LayoutError};
use crate::parts::PartError;

/// Why a part, nozzle or one of their patches could not be built, by the stage
/// that failed.
#[derive(Debug, Error, Clone, PartialEq)]
pub enum BuildCause {
    /// The part's exact patches could not be built from its parameters.
    #[error("its shape cannot be built: {0}")]
    Shape(PartError),
    /// The nozzle's (or boot's) opening cannot be cut in its host.
    #[error("its opening in {host} cannot be cut: {source}")]
    Opening {
        /// The host part's stable id, e.g. `V-101/S1`.
        host: String,
        /// Why the cutter failed.
        source: CutError,
    },
    /// A patch's region (its boundary with the opening loops) cannot be laid out.
    #[error("the region of its patch {patch:?} cannot be laid out: {source}")]
    Region {
        /// The patch, e.g. `crown` or `knuckle 2`.
        patch: String,
        /// Why the layout failed.
        source: LayoutError,
    },
    /// A patch cannot be meshed.
    #[error("its patch {patch:?} cannot be meshed: {source}")]
    Mesh {
        /// The patch, e.g. `crown` or `knuckle 2`.
        patch: String,
        /// Why the mesher failed.
        source: CdtError,
    },
}

impl BuildCause {
    /// The stage that failed: `shape`, `opening`, `region` or `mesh`.
    pub fn stage(&self) -> &'static str {
        match self {
            BuildCause::Shape(_) => "shape",
            BuildCause::Opening { .. } => "opening",
            BuildCause::Region { .. } => "region",
            BuildCause::Mesh { .. } => "mesh",
        }
    }

    /// The patch that failed, for a region or mesh failure.
    pub fn patch(&self) -> Option<&str> {
        match self {
            BuildCause::Region { patch, .. } | BuildCause::Mesh { patch, .. } => Some(patch),
            BuildCause::Shape(_) | BuildCause::Opening { .. } => None,
        }
    }
}

/// A part, nozzle or boot whose geometry the model could not build.
#[derive(Debug, Error, Clone, PartialEq)]
#[error("{path}: {entity}: {cause}")]
pub struct BuildFailure {
    /// JSON path of the part or nozzle in the design, e.g. `vessels[0].nozzles[2]`
    /// (as a [`RuleViolation`]'s), empty for an entity of no vessel.
    pub path: String,
    /// Its stable id, e.g. `V-101/N3`.
    pub entity: String,
    /// What failed and why.
    pub cause: BuildCause,
}

impl BuildFailure {
    /// As JSON (`check --json`, the server's error bodies): `path`, `entity`,
    /// `stage` (`shape`, `opening`, `region`, `mesh`), `patch` (for a region
    /// or mesh failure, else null) and `cause` (the typed cause's message).
    pub fn to_json(&self) -> serde_json::Value {
        serde_json::json!({
            "path": self.path, "entity": self.entity, "stage": self.cause.stage(),
            "patch": self.cause.patch(), "cause": self.cause.to_string(),
        })
    }
}

/// One thing the last run found wrong.
#[derive(Debug, Clone, PartialEq)]
pub enum ModelFailure {
    /// A vessel (by tag) whose rules do not hold in the world.
    Rules(String, Vec<RuleViolation>),
    /// A part, nozzle or patch that could not be built.
    Build(BuildFailure),
}

/// What the last run found wrong (normally nothing).
#[derive(Resource, Default, Debug)]
pub struct ModelErrors(pub Vec<ModelFailure>);

impl ModelErrors {
    /// The build failures, in the order found.
    pub fn build_failures(&self) -> impl Iterator<Item = &BuildFailure> {
        self.0.iter().filter_map(|f| match f {
            ModelFailure::Build(b) => Some(b),
            ModelFailure::Rules(..) => None,
        })
    }

    /// The rule violations, in the order found.
    pub fn violations(&self) -> impl Iterator<Item = &RuleViolation> {
        self.0.iter().flat_map(|f| match f {
            ModelFailure::Rules(_, v) => v.as_slice(),
            ModelFailure::Build(_) => &[],
        })
    }
}

impl std::fmt::Display for ModelFailure {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            ModelFailure::Rules(tag, violations) => {
                write!(f, "vessel {tag}: {} broken rule(s)", violations.len())?;
                for v in violations {
                    write!(f, "\n  - {v}")?;
                }
                Ok(())
            }
            ModelFailure::Build(b) => b.fmt(f),
        }
    }
}
