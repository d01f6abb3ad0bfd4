//! Nozzle: a pipe neck (ASME B36.10M) carrying a B16.5 flange, as exact surfaces of
//! revolution.
//!
//! Local frame: the nozzle axis is +Z. The origin is on the axis where the neck
//! starts, at the host surface reference point; the neck starts at z = 0 (a later
//! stage trims it with the exact neck–host intersection curve) and the flange gasket
//! face lies at z = `projection`, the plant-design projection of the nozzle.
//!
//! The outside surface is one meridian profile, each smooth piece revolved into its
//! own patch, from the neck start to the face:
//!
//! - `"neck"` — cylinder of the pipe OD, z = 0 up to the back of the flange body.
//! - Weld-neck and blind: `"hub"` — cone from the pipe OD (dimension A, which B16.5
//!   makes equal to the pipe OD) to the hub base X over Y − tf.
//! - Slip-on: `"hub end"` — annulus from the pipe OD out to X (normal −Z), then
//!   `"hub"` — cylinder of diameter X over Y − tf. B16.5 slip-on hubs taper only
//!   slightly and the tables carry only X, so the hub is modelled straight. The pipe
//!   end set back inside the flange and the fillet welds are not modelled: the
//!   neck simply continues through the hub.
//! - `"flange back"` — annulus X → O (normal −Z); `"flange rim"` — cylinder O over tf.
//! - Raised face and ring joint: `"flange face"` — annulus O → R (normal +Z);
//!   `"raised face rim"` — cylinder R over the raised-face height. A ring-joint
//!   flange is modelled as its raised face without the ring groove: the tables carry
//!   no ring-joint columns, so the raised portion takes the raised-face diameter R
//!   and [`raised_face_height`].
//! - `"gasket face"` — the plane z = `projection` (normal +Z): from R (or O for a
//!   flat face) in to the pipe bore (OD − 2 × wall of the schedule). The bore is an
//!   intended open end of the outside surface. For a blind the gasket face closes
//!   fully to the axis (a disk with its pole at the centre): the nozzle is a
//!   weld-neck body closed at its gasket plane; the blind cover beyond the gasket
//!   plane (its thickness and bolting) is not modelled.
//!
//! Lengths follow the B16.5 tables of [`tables`](super::tables): tf and Y exclude the
//! raised face, so the flange body measures Y + raised-face height from its back (the
//! hub end) to the gasket face. Every joint of the profile is a real corner: the
//! patches meet G0, not G1. Bolt holes are not modelled.

mod profile;

use std::f64::consts::TAU;

use glam::DVec3;

use super::check::{invalid, positive};
use super::tables::{
    FlangeClass, FlangeDimensions, Nps, PipeSchedule, flange, pipe, raised_face_height,
};
use super::{PartError, Patch};
use crate::nurbs::builders::revolve;
use profile::Resolved;

/// The B16.5 flange style of a nozzle.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum FlangeType {
    /// Weld-neck: a conical hub butt-welded to the neck; length through hub Y(WN).
    WeldNeck,
    /// Slip-on: a straight hub slipped over the neck; length through hub Y(SO).
    SlipOn,
    /// A weld-neck nozzle closed by a blind flange: the gasket face closes at the
    /// axis (see the module documentation).
    Blind,
}

/// The facing of the flange's gasket surface.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Facing {
    /// Raised face of diameter R and the class's [`raised_face_height`].
    RaisedFace,
    /// Flat face: the gasket face is the whole front of the flange.
    FlatFace,
    /// Ring-type joint, modelled as the raised face without the ring groove.
    RingJoint,
}

impl Facing {
    /// Height of the raised portion above the flange face for `class`, mm: 0 for a
    /// flat face, else [`raised_face_height`].
    pub fn height(self, class: FlangeClass) -> f64 {
        match self {
            Facing::FlatFace => 0.0,
            Facing::RaisedFace | Facing::RingJoint => raised_face_height(class),
        }
    }
}

/// Parameters of a flanged nozzle.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Nozzle {
    /// Nominal pipe size of the neck and flange.
    pub nps: Nps,
    /// Wall schedule of the neck pipe (sets the bore of the gasket face).
    pub schedule: PipeSchedule,
    /// B16.5 pressure class of the flange.
    pub class: FlangeClass,
    /// Flange style.
    pub flange: FlangeType,
    /// Gasket-face facing.
    pub facing: Facing,
    /// Distance from the neck start (z = 0) to the gasket face, mm.
    pub projection: f64,
}

const PART: &str = "nozzle";

impl Nozzle {
    /// Shortest neck allowed between the neck start and the back of the flange body,
    /// mm: room to weld the neck to the host and to the flange and to inspect both
    /// welds. One value for every size keeps the rule predictable; longer necks for
    /// stud withdrawal, insulation or a curved host are the designer's choice of
    /// `projection`.
    pub const MIN_NECK_LENGTH: f64 = 50.0;

    /// Checks the parameters: the size, schedule and class are listed in the
    /// tables ([`PartError::Table`] otherwise), and `projection` is a finite
    /// dimension of at least [`flange_length`](Self::flange_length) +
    /// [`MIN_NECK_LENGTH`](Self::MIN_NECK_LENGTH).
    pub fn validate(&self) -> Result<(), PartError> {
        self.resolve().map(|_| ())
    }

    /// Outside diameter of the neck, mm: the B36.10M pipe OD.
    pub fn outside_diameter(&self) -> f64 {
        pipe(self.nps).outside_diameter
    }

    /// Length of the flange body from its back (the hub end) to the gasket face,
    /// raised face included, mm. Does not depend on `projection`.
    ///
    /// # Errors
    ///
    /// [`PartError::Table`] where B16.5 lists no flange of this size and class.
    pub fn flange_length(&self) -> Result<f64, PartError> {
        let dims = flange(self.nps, self.class)?;
        Ok(self.hub_length(dims) + self.facing.height(self.class))
    }

    /// Length of the bare neck, `projection − flange_length`, mm. This is plain
    /// arithmetic on `projection`; [`validate`](Self::validate) is what checks it.
    ///
    /// # Errors
    ///
    /// [`PartError::Table`] as for [`flange_length`](Self::flange_length).
    pub fn neck_length(&self) -> Result<f64, PartError> {
        Ok(self.projection - self.flange_length()?)
    }

    /// The exact patches, outward normals, from the neck start to the gasket face:
    /// u around the axis (counter-clockwise from +X), v along the profile. Names and
    /// order are listed in the module documentation.
    pub fn patches(&self) -> Result<Vec<Patch>, PartError> {
        let resolved = self.resolve()?;
        profile::profile(&resolved)?
            .into_iter()
            .map(|s| {
                let surface = revolve(&s.curve, DVec3::ZERO, DVec3::Z, TAU)?;
                Ok(Patch::new(s.name, surface, s.analytic))
            })
            .collect()
    }

    /// Validates the parameters and resolves the table dimensions.
    fn resolve(&self) -> Result<Resolved, PartError> {
        let projection = positive(PART, "projection", self.projection)?;
        let dims = flange(self.nps, self.class)?;
        let pipe = pipe(self.nps);
        let wall = pipe.wall(self.schedule)?;
        let flange_length = self.flange_length()?;
        let shortest = flange_length + Self::MIN_NECK_LENGTH;
        if projection < shortest {
            return Err(invalid(
                PART,
                "projection",
                projection,
                format!(
                    "must be at least the flange length ({flange_length} mm) plus the \
                     minimum neck ({} mm) = {shortest} mm",
                    Self::MIN_NECK_LENGTH
                ),
            ));
        }
        Ok(Resolved {
            flange: self.flange,
            pipe_radius: pipe.outside_diameter / 2.0,
            bore_radius: pipe.outside_diameter / 2.0 - wall,
            hub_base_radius: dims.hub_base_diameter / 2.0,
            flange_radius: dims.outside_diameter / 2.0,
            raised_face_radius: dims.raised_face_diameter / 2.0,
            raised_face_height: self.facing.height(self.class),
            thickness: dims.thickness,
            hub_length: self.hub_length(dims),
            projection,
        })
    }

    /// Length through hub Y of this flange style, raised face excluded, mm.
    fn hub_length(&self, dims: &FlangeDimensions) -> f64 {
        match self.flange {
            FlangeType::WeldNeck | FlangeType::Blind => dims.weld_neck_length,
            FlangeType::SlipOn => dims.slip_on_length,
        }
    }
}
