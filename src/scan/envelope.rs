//! The surfaces a scan is compared with: one vessel's exact patches in the vessel
//! frame, each tagged with the part it belongs to and the role that part plays
//! (course, head, cone, nozzle, support).
//!
//! Built from the resolved design like [`crate::exchange`]'s sources (resolve,
//! then each part's and nozzle's `patches()` in its own frame), without cutting
//! openings: a scan sees the shell around a nozzle, and a point in the opening
//! lies on the neck, which is a surface here too. Patches swept about their
//! part's axis (every course, head, concentric cone and nozzle patch) carry
//! their meridian [`Profile`], so a point projects onto them by a one-variable
//! Newton on the meridian instead of a search over the surface.

use glam::{DAffine3, DVec3};

use super::ScanError;
use super::profile::Profile;
use crate::calc::MaterialTable;
use crate::constraints::{PartGeometry, ResolvedVessel};
use crate::design::{Design, VesselKind, resolve};
use crate::nurbs::Aabb;
use crate::parts::Patch;

/// What a part is, for the checks that apply to it.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Role {
    /// A cylindrical shell course (UG-80 roundness, peaking, plumbness).
    Course,
    /// A formed head (UG-81 shape).
    Head,
    /// A conical reducer.
    Cone,
    /// A nozzle: used to register, not fitted.
    Nozzle,
    /// A support or boot: not scanned, not fitted.
    Support,
}

impl Role {
    /// Whether the part belongs to the pressure envelope a scan is fitted to.
    pub fn is_envelope(self) -> bool {
        matches!(self, Role::Course | Role::Head | Role::Cone)
    }
}

/// One part or nozzle of the vessel.
#[derive(Clone, Debug)]
pub struct ScanPart {
    /// Part id or nozzle mark.
    pub id: String,
    /// What it is.
    pub role: Role,
    /// Local frame → vessel frame.
    pub frame: DAffine3,
    /// Axial extent in the vessel frame, mm.
    pub span: (f64, f64),
    /// Largest outside diameter of its patches about its own axis, mm.
    pub diameter: f64,
}

/// One exact patch placed in the vessel frame.
#[derive(Clone, Debug)]
pub struct ScanSurface {
    /// Index in [`Envelope::parts`].
    pub part: usize,
    /// The patch, in its part's local frame.
    pub patch: Patch,
    /// Local frame → vessel frame.
    pub frame: DAffine3,
    /// Vessel frame → local frame.
    pub inverse: DAffine3,
    /// Bounding box of the control net in the vessel frame.
    pub bbox: Aabb,
    /// The meridian, for a patch swept a full turn about its local +Z.
    pub profile: Option<Profile>,
}

/// The shell material's strength, for API 653 Annex B's allowable out-of-plane
/// settlement.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct ShellMaterial {
    /// Specification, as the materials table names it.
    pub name: String,
    /// Specified minimum yield strength, MPa.
    pub yield_strength: f64,
    /// Modulus of elasticity, MPa.
    pub modulus: f64,
}

/// One vessel's parts and patches, vessel frame.
#[derive(Clone, Debug)]
pub struct Envelope {
    /// Tag.
    pub tag: String,
    /// Vertical, horizontal or tank.
    pub kind: VesselKind,
    /// The plan rotation of the vessel's placement, degrees.
    pub rotation: f64,
    /// Vessel frame → plant frame.
    pub frame: DAffine3,
    /// Plant up (+Z) in the vessel frame.
    pub up: DVec3,
    /// Parts in design order, then nozzles in design order.
    pub parts: Vec<ScanPart>,
    /// Every patch of every part and nozzle.
    pub surfaces: Vec<ScanSurface>,
    /// The vessel's material (`design.material`) from the built-in table, if it
    /// names one there.
    pub material: Option<ShellMaterial>,
}

/// Samples per direction of [`extent`]'s grid (the domain's ends included).
const EXTENT_SAMPLES: usize = 33;

/// The largest diameter of `patch` about its local axis and its axial span in the
/// vessel frame (`frame`: local → vessel), from points of the surface itself.
///
/// Not from the control net: a full-turn revolution's corner control points lie
/// √2 farther out than its circle, which would make a course of OD 2000 read
/// 2828. Every patch of revolution takes its largest radius and its extreme
/// heights on a domain edge or on a whole isocurve, which the grid (ends
/// included) holds.
fn extent(patch: &Patch, frame: &DAffine3) -> (f64, (f64, f64)) {
    let s = &patch.surface;
    let ((u0, u1), (v0, v1)) = s.domain();
    let mut diameter: f64 = 0.0;
    let mut span = (f64::INFINITY, f64::NEG_INFINITY);
    let n = EXTENT_SAMPLES - 1;
    for i in 0..=n {
        for j in 0..=n {
            let u = u0 + (u1 - u0) * i as f64 / n as f64;
            let v = v0 + (v1 - v0) * j as f64 / n as f64;
            let p = s.point(u, v);
            diameter = diameter.max(2.0 * p.truncate().length());
            let z = frame.transform_point3(p).z;
            span = (span.0.min(z), span.1.max(z));
        }
    }
    (diameter, span)
}

impl Envelope {
    /// The envelope of the vessel tagged `tag` in `design`.
    ///
    /// # Errors
    ///
    /// [`ScanError::Design`] for a design breaking a rule,
    /// [`ScanError::UnknownVessel`] for a tag not in it, [`ScanError::Part`]
    /// where a part cannot build its patches.
    pub fn of_design(design: &Design, tag: &str) -> Result<Self, ScanError> {
        let resolved = resolve(design)?;
        let vessel =
            resolved
                .iter()
                .find(|v| v.tag == tag)
                .ok_or_else(|| ScanError::UnknownVessel {
                    tag: tag.to_string(),
                })?;
        let given = design.vessels.iter().find(|v| v.tag == tag);
        let rotation = given.map_or(0.0, |v| v.placement.rotation);
        let mut envelope = Self::of_vessel(vessel, rotation)?;
        envelope.material = given
            .and_then(|v| v.design.material.as_deref())
            .and_then(|name| MaterialTable::builtin().get(name).ok().cloned())
            .map(|m| ShellMaterial {
                name: m.name,
                yield_strength: m.yield_strength.value,
                modulus: m.modulus.value,
            });
        Ok(envelope)
    }

    /// The envelope of one resolved vessel placed with plan `rotation` degrees.
    fn of_vessel(vessel: &ResolvedVessel, rotation: f64) -> Result<Self, ScanError> {
        let entity = |id: &str| format!("{}/{}", vessel.tag, id);
        let mut parts = Vec::new();
        let mut surfaces = Vec::new();
        let mut add = |id: &str,
                       role: Role,
                       frame: DAffine3,
                       patches: Vec<Patch>,
                       parts: &mut Vec<ScanPart>| {
            let index = parts.len();
            let mut diameter: f64 = 0.0;
            let mut span = (f64::INFINITY, f64::NEG_INFINITY);
            for patch in patches {
                let (d, (z0, z1)) = extent(&patch, &frame);
                diameter = diameter.max(d);
                span = (span.0.min(z0), span.1.max(z1));
                let points = patch.surface.control_points();
                let bbox = Aabb::from_points(points.iter().map(|&p| frame.transform_point3(p)));
                let profile = Profile::of_patch(&patch);
                surfaces.push(ScanSurface {
                    part: index,
                    patch,
                    frame,
                    inverse: frame.inverse(),
                    bbox,
                    profile,
                });
            }
            parts.push(ScanPart {
                id: id.to_string(),
                role,
                frame,
                span,
                diameter,
            });
        };
        for part in &vessel.parts {
            let patches = part.geometry.patches().map_err(|source| ScanError::Part {
                entity: entity(&part.id),
                source,
            })?;
            let role = match part.geometry {
                PartGeometry::Shell(_) => Role::Course,
                PartGeometry::Head(_) => Role::Head,
                PartGeometry::Reducer(_) => Role::Cone,
                _ => Role::Support,
            };
            add(&part.id, role, part.frame, patches, &mut parts);
        }
        for nozzle in &vessel.nozzles {
            let patches = nozzle
                .geometry
                .patches()
                .map_err(|source| ScanError::Part {
                    entity: entity(&nozzle.mark),
                    source,
                })?;
            add(
                &nozzle.mark,
                Role::Nozzle,
                nozzle.frame,
                patches,
                &mut parts,
            );
        }
        let up = vessel.frame.matrix3.inverse() * DVec3::Z;
        Ok(Self {
            tag: vessel.tag.clone(),
            kind: vessel.kind,
            rotation,
            frame: vessel.frame,
            up: up.normalize(),
            parts,
            surfaces,
            material: None,
        })
    }

    /// The orientation (degrees, the plant convention of the vessel's kind: from
    /// north clockwise in plan, or about a drum's axis from the top) of the
    /// direction of `p` from the vessel axis, `p` in the vessel frame.
    pub fn orientation_of(&self, p: DVec3) -> f64 {
        let theta = p.y.atan2(p.x).to_degrees();
        let o = match self.kind {
            VesselKind::Vertical | VesselKind::Tank => 90.0 - theta + self.rotation,
            VesselKind::Horizontal => theta - 90.0,
        };
        o.rem_euclid(360.0)
    }

    /// The angle about the vessel axis (radians, counter-clockwise from +X in the
    /// vessel frame) of an orientation in degrees: the inverse of
    /// [`orientation_of`](Self::orientation_of).
    pub fn angle_of_orientation(&self, orientation: f64) -> f64 {
        let theta = match self.kind {
            VesselKind::Vertical | VesselKind::Tank => 90.0 - orientation + self.rotation,
            VesselKind::Horizontal => orientation + 90.0,
        };
        theta.to_radians()
    }

    /// Index of the part with id `id`.
    pub fn part_index(&self, id: &str) -> Option<usize> {
        self.parts.iter().position(|p| p.id == id)
    }
}
