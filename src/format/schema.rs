//! The design file's data model: what a designer writes, as serde types.
//!
//! This is the top of the data flow: a design file (or an edit) is parsed into these
//! types, checked by [`crate::design::validate`], and then becomes parameter components on
//! ECS entities. Every entity has a stable id — the vessel `tag`, a part `id`, a
//! nozzle `mark`, a note `id` — which edits and viewers use.
//!
//! Lengths are mm and angles degrees once loaded (a file may declare
//! `"units": "in"`; see [`super::units`]). Enumerations are lowercase strings; parts
//! are externally tagged objects (`{"shell": {...}}`) so that every error can name
//! its exact JSON path.

use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

/// The format tag every design file carries.
pub const FORMAT: &str = "vesselcad/1";

/// A whole design file: one vessel or a plant of many.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct Design {
    /// Always [`FORMAT`].
    pub format: String,
    /// Length unit of the file; loaded designs are always in mm.
    #[serde(default)]
    pub units: Units,
    /// The vessels, each with a unique tag.
    pub vessels: Vec<VesselDesign>,
}

/// Length unit declared by a design file.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "lowercase")]
pub enum Units {
    /// Millimetres (the default, and what loaded designs use).
    #[default]
    Mm,
    /// Inches, converted to mm on load.
    In,
}

/// One vessel: its identity, placement, design data, parts, nozzles and notes.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct VesselDesign {
    /// Unique tag, e.g. `"V-101"`.
    pub tag: String,
    /// Horizontal drum, vertical vessel or column, or storage tank.
    pub kind: VesselKind,
    /// Where the vessel stands in the plant.
    #[serde(default)]
    pub placement: Placement,
    /// Design conditions, carried as data.
    #[serde(default)]
    pub design: DesignConditions,
    /// Title-block data of the vessel's drawing.
    #[serde(default, skip_serializing_if = "DrawingInfo::is_empty")]
    pub drawing: DrawingInfo,
    /// Parts: the stack (heads, shell courses, reducers) in order along the axis —
    /// bottom to top for vertical vessels, left to right for horizontal ones — and the
    /// attached parts (skirt, saddles, legs, lugs, boot) anywhere in the list.
    pub parts: Vec<PartDesign>,
    /// Nozzles and manways.
    #[serde(default)]
    pub nozzles: Vec<NozzleDesign>,
    /// Notes attached to the vessel or to one of its parts or nozzles.
    #[serde(default)]
    pub notes: Vec<NoteDesign>,
    /// Operating state: liquid level and density. Absent: empty.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub operating: Option<OperatingDesign>,
}

/// A vessel's operating state: how full it is and of what.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct OperatingDesign {
    /// Height of the liquid surface above the lowest point of the vessel's interior,
    /// mm (0 = empty; at most the interior's height). The boot of a horizontal drum
    /// is not counted in the interior.
    pub liquid_level: f64,
    /// Liquid density, kg/m³; default [`WATER_DENSITY`].
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub liquid_density: Option<f64>,
}

/// Density of water, the default liquid, kg/m³.
pub const WATER_DENSITY: f64 = 1000.0;

/// What kind of vessel this is; decides the local frame's orientation in the plant.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "lowercase")]
pub enum VesselKind {
    /// Axis horizontal; local +Y is plant up.
    Horizontal,
    /// Axis vertical (plant +Z).
    Vertical,
    /// Vertical storage tank (flat bottom, roof on top).
    Tank,
}

/// Placement of the vessel's datum (the bottom or left tangent line on the axis)
/// in the plant frame (X east, Y north, Z up), mm.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct Placement {
    /// Datum position `[east, north, up]`, mm.
    #[serde(default)]
    pub position: [f64; 3],
    /// Plan rotation, degrees clockwise from north: for a horizontal vessel the
    /// bearing of its axis, for a vertical one its turn about its axis.
    #[serde(default)]
    pub rotation: f64,
}

/// Design conditions of a vessel (data for drawings and weights).
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct DesignConditions {
    /// Design pressure, kPa gauge.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub pressure: Option<f64>,
    /// Design temperature, °C.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub temperature: Option<f64>,
    /// Corrosion allowance, mm.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub corrosion_allowance: Option<f64>,
    /// Material specification, e.g. `"SA-516-70"`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub material: Option<String>,
    /// Density of the vessel's metal, kg/m³. Default: from the material
    /// specification (stainless grades 8000, otherwise carbon steel 7850); see
    /// `operating::metal_density`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub metal_density: Option<f64>,
    /// Joint efficiency E of the longitudinal and circumferential welds (ASME
    /// VIII-1 UW-12), 0 < E ≤ 1; default 0.85 (spot radiography).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub joint_efficiency: Option<f64>,
    /// External design pressure (vacuum: 101.3), kPa: checked by ASME VIII-1
    /// UG-28 (cylinders) and UG-33 (heads) in the elastic range. Default: none.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub external_pressure: Option<f64>,
    /// Wind on the vessel (ASCE 7-16 Chapters 26 and 29), checked on a vertical
    /// vessel's skirt, legs or lugs. Default: none.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub wind: Option<Box<WindDesign>>,
    /// Earthquake on the vessel (ASCE 7-16 §12.8 equivalent lateral force, as
    /// §15.4 allows for nonbuilding structures), checked on a vertical vessel's
    /// skirt, legs or lugs. Default: none.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub seismic: Option<Box<SeismicDesign>>,
}

/// Wind inputs of a vessel (ASCE 7-16): velocity pressure
/// qz = 0.613·Kz·Kzt·Kd·I·V² (Pa, V in m/s, z above grade) on the projected width, force
/// qz·G·Cf per unit area (§29.4), combined as 0.6·W (allowable stress design,
/// §2.4.1).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct WindDesign {
    /// Basic wind speed V, m/s: the 3-second gust at 10 m in Exposure C of the
    /// structure's risk category (ASCE 7-16 Figures 26.5-1).
    pub speed: f64,
    /// Exposure category (ASCE 7-16 §26.7): `B`, `C` or `D`.
    pub exposure: Exposure,
    /// Importance factor on the velocity pressure; default 1.0 (ASCE 7-10 and
    /// later carry the risk category in the wind speed map; ASCE 7-05 used
    /// 0.87–1.15).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub importance: Option<f64>,
    /// Topographic factor Kzt (§26.8); default 1.0 (flat terrain).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub topographic_factor: Option<f64>,
    /// Directionality factor Kd (Table 26.6-1); default 0.95 (round chimneys
    /// and tanks).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub directionality_factor: Option<f64>,
    /// Gust-effect factor G (§26.11); default 0.85 (rigid structure).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub gust_factor: Option<f64>,
    /// Force coefficient Cf on the projected area (Figure 29.4-1); default 0.7
    /// (round, moderately smooth, h/D = 25).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub force_coefficient: Option<f64>,
    /// Factor ≥ 1 on the projected width for platforms, ladders, piping and
    /// insulation; default 1.0.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub area_factor: Option<f64>,
    /// Height of the vessel's lowest point (its skirt's or legs' base) above
    /// grade, mm; default 0 (standing at grade). The wind's heights are measured
    /// from grade.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub base_elevation: Option<f64>,
}

/// Wind exposure category (ASCE 7-16 §26.7.3).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, Deserialize, JsonSchema)]
pub enum Exposure {
    /// Urban and suburban areas, wooded areas.
    B,
    /// Open terrain with scattered obstructions.
    C,
    /// Flat, unobstructed areas and water surfaces.
    D,
}

/// Earthquake inputs of a vessel (ASCE 7-16 §12.8, §15.4): base shear
/// V = Cs·W with Cs = SDS/(R/Ie), at most SD1/(T·R/Ie) when the period is
/// given, at least max(0.044·SDS·Ie, 0.03) (Eq. 15.4-1), combined as 0.7·E with
/// the vertical effect 0.2·SDS·D (§2.4.1, §12.4.2.2).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct SeismicDesign {
    /// Design spectral response acceleration at short periods SDS, g.
    pub sds: f64,
    /// Design spectral response acceleration at 1 s SD1, g.
    pub sd1: f64,
    /// Response modification coefficient R (Table 15.4-2; e.g. 2 for skirt-
    /// supported vertical vessels not of the building type, 3 on legs).
    pub response_modification: f64,
    /// Importance factor Ie (Table 1.5-2); default 1.0.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub importance: Option<f64>,
    /// Fundamental period T, s. Default: none, and Cs is taken on the plateau
    /// SDS/(R/Ie) (12.8-3 can only lower it) with the vertical distribution's
    /// exponent k = 2 (its largest base moment).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub period: Option<f64>,
}

/// Title-block data of a vessel's drawing sheet; every field optional.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct DrawingInfo {
    /// Drawing number, e.g. `"D-201-001"`; default: the vessel's tag.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub number: Option<String>,
    /// Title; default: the vessel's kind and tag.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub title: Option<String>,
    /// Revision, e.g. `"A"` or `"2"` (at most 8 characters).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub revision: Option<String>,
    /// Date of the revision, ISO 8601 `YYYY-MM-DD`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub date: Option<String>,
}

impl DrawingInfo {
    /// True when no field is given.
    pub fn is_empty(&self) -> bool {
        *self == DrawingInfo::default()
    }
}

/// One part, tagged by its kind: `{"shell": {...}}`, `{"head": {...}}`, ….
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "lowercase")]
pub enum PartDesign {
    /// A cylindrical shell course.
    Shell(ShellDesign),
    /// A head closing an end of the stack.
    Head(HeadDesign),
    /// A conical reducer between two courses.
    Reducer(ReducerDesign),
    /// A skirt under a vertical vessel.
    Skirt(SkirtDesign),
    /// A saddle under a horizontal vessel.
    Saddle(SaddleDesign),
    /// Pipe legs.
    Legs(LegsDesign),
    /// Support lugs.
    Lugs(LugsDesign),
    /// A boot (small drum) under a horizontal vessel.
    Boot(BootDesign),
}

/// A cylindrical shell course.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct ShellDesign {
    /// Part id, unique in the vessel.
    pub id: String,
    /// Outside diameter, mm.
    pub od: f64,
    /// Length along the axis, mm.
    pub length: f64,
    /// Wall thickness, mm.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub thickness: Option<f64>,
}

/// Shape of a head.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "lowercase")]
pub enum HeadShape {
    /// Half sphere.
    Hemispherical,
    /// Semi-ellipsoidal (`ratio`, default 2 for 2:1).
    Ellipsoidal,
    /// Flanged and dished (`crown_radius`, `knuckle_radius`; default ASME F&D).
    Torispherical,
    /// Cone with knuckle (`half_angle`, `knuckle_radius`).
    Toriconical,
    /// Cone without knuckle (`half_angle`, optional `small_od`).
    Conical,
    /// Flat plate (optional `knuckle_radius` for a flanged flat head).
    Flat,
}

/// A head. Its outside diameter is the OD of the course it closes.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct HeadDesign {
    /// Part id, unique in the vessel.
    pub id: String,
    /// Head shape.
    pub shape: HeadShape,
    /// Ellipsoidal: D / (2 h); default 2.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub ratio: Option<f64>,
    /// Torispherical: crown radius, mm; default = OD.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub crown_radius: Option<f64>,
    /// Torispherical, toriconical, flat: knuckle radius, mm; defaults 0.06 × crown
    /// radius (torispherical), 0.06 × OD (toriconical), 0 (flat).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub knuckle_radius: Option<f64>,
    /// Toriconical, conical: half-angle, degrees; default 30.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub half_angle: Option<f64>,
    /// Conical: small-end outside diameter, mm; default 0 (apex).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub small_od: Option<f64>,
    /// Straight flange length, mm; default 0.
    #[serde(default, skip_serializing_if = "is_zero")]
    pub straight_flange: f64,
    /// Thickness, mm.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub thickness: Option<f64>,
}

/// A conical reducer; its end diameters are those of the courses it joins.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct ReducerDesign {
    /// Part id, unique in the vessel.
    pub id: String,
    /// Axial length, mm.
    pub length: f64,
    /// For an eccentric reducer, the angle of its flat side (degrees about the
    /// vessel axis, the same convention as nozzle orientations); absent: concentric.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub eccentric: Option<f64>,
    /// Thickness, mm.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub thickness: Option<f64>,
}

/// A skirt; its top diameter is the OD of the bottom course.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct SkirtDesign {
    /// Part id, unique in the vessel.
    pub id: String,
    /// Height from the base to the bottom tangent line, mm.
    pub height: f64,
    /// Flare angle, degrees, 0–45; default 0 (straight).
    #[serde(default, skip_serializing_if = "is_zero")]
    pub flare_angle: f64,
    /// Base ring radial width, mm; default 0 (none).
    #[serde(default, skip_serializing_if = "is_zero")]
    pub base_ring_width: f64,
    /// Base ring thickness, mm; default the skirt's thickness. The skirt
    /// calculation checks it against the bearing pressure under the ring.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub base_ring_thickness: Option<f64>,
    /// Thickness, mm.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub thickness: Option<f64>,
    /// Number of anchor bolts, on the circle through the middle of the base
    /// ring: the calculation gives the load per bolt. Default: none (the load is
    /// given per mm of the bolt circle).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub anchor_bolts: Option<u32>,
}

/// A saddle; it fits the OD of the course it stands under.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct SaddleDesign {
    /// Part id, unique in the vessel.
    pub id: String,
    /// Position of the saddle centre along the axis from the left tangent line, mm.
    /// Default: 0.2 L from the nearer tangent line (first saddle left, second right).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub position: Option<f64>,
    /// Contact angle, degrees, 120–150; default 120.
    #[serde(default = "default_contact_angle")]
    pub contact_angle: f64,
    /// Width along the vessel axis, mm.
    pub width: f64,
    /// Height from the base to the vessel axis, mm.
    pub height: f64,
    /// Web thickness, mm; default 12.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub web_thickness: Option<f64>,
    /// Thickness of a wear plate welded to the shell over the saddle and reaching
    /// at least R/10 above its horns, mm: Zick's saddle check counts it in the
    /// horn and bottom stresses. Default: none.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub wear_plate: Option<f64>,
}

/// Pipe legs around a small vertical vessel.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct LegsDesign {
    /// Part id, unique in the vessel.
    pub id: String,
    /// Number of legs, ≥ 3.
    pub count: u32,
    /// Leg pipe size, NPS inches.
    pub size: f64,
    /// Length from the floor to the bottom tangent line, mm.
    pub length: f64,
    /// Orientation of the first leg, degrees; default 0.
    #[serde(default, skip_serializing_if = "is_zero")]
    pub orientation: f64,
}

/// Support lugs on a vertical vessel.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct LugsDesign {
    /// Part id, unique in the vessel.
    pub id: String,
    /// Number of lugs, ≥ 2.
    pub count: u32,
    /// Elevation of the bearing plate from the datum, mm.
    pub elevation: f64,
    /// Gusset height, mm.
    pub height: f64,
    /// Radial projection from the shell, mm.
    pub projection: f64,
    /// Distance between the two gussets, mm.
    pub width: f64,
    /// Orientation of the first lug, degrees; default 0.
    #[serde(default, skip_serializing_if = "is_zero")]
    pub orientation: f64,
}

/// A boot under a horizontal vessel.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct BootDesign {
    /// Part id, unique in the vessel.
    pub id: String,
    /// Position of the boot axis along the vessel axis from the left tangent line, mm.
    pub position: f64,
    /// Boot outside diameter, mm.
    pub od: f64,
    /// Length below the vessel shell, mm.
    pub length: f64,
    /// Shape of its bottom head; default ellipsoidal 2:1.
    #[serde(default = "default_boot_head")]
    pub head: HeadShape,
}

/// Flange facing.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, Deserialize, JsonSchema)]
pub enum FacingDesign {
    /// Raised face.
    #[serde(rename = "RF")]
    RaisedFace,
    /// Flat face.
    #[serde(rename = "FF")]
    FlatFace,
    /// Ring-type joint.
    #[serde(rename = "RTJ")]
    RingJoint,
}

/// Flange type of a nozzle.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, Serialize, Deserialize, JsonSchema)]
pub enum FlangeDesign {
    /// Weld-neck (the default).
    #[default]
    #[serde(rename = "WN")]
    WeldNeck,
    /// Slip-on.
    #[serde(rename = "SO")]
    SlipOn,
    /// Closed by a blind flange.
    #[serde(rename = "blind")]
    Blind,
}

/// A nozzle or manway mounted on a host part (a shell course or a head).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct NozzleDesign {
    /// Mark, unique in the vessel: `N1`, `M1` (manway), ….
    pub mark: String,
    /// Service, e.g. `"inlet"`.
    #[serde(default, skip_serializing_if = "String::is_empty")]
    pub service: String,
    /// Size, NPS inches (1/2 to 24).
    pub size: f64,
    /// Pressure class: 150, 300, 600 or 900.
    pub rating: u32,
    /// Flange facing.
    #[serde(default = "default_facing")]
    pub facing: FacingDesign,
    /// Flange type; default weld-neck.
    #[serde(default)]
    pub flange: FlangeDesign,
    /// Neck pipe schedule: `"STD"`, `"XS"`, `"40"`, `"80"`, `"160"`, `"XXS"`; default STD.
    #[serde(default = "default_schedule")]
    pub schedule: String,
    /// Id of the host part.
    pub host: String,
    /// Orientation, degrees: for vertical vessels the plan angle from plant north,
    /// clockwise; for horizontal ones the angle about the axis from the top,
    /// clockwise looking from the left end.
    pub orientation: f64,
    /// Shell nozzles: elevation of the nozzle axis above the datum (vertical) or its
    /// position along the axis from the left tangent line (horizontal), mm.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub elevation: Option<f64>,
    /// Head nozzles: distance of the nozzle axis from the head centreline, mm;
    /// default 0. Shell nozzles (on a cylindrical course): the hillside offset,
    /// the distance of the nozzle axis from the radial plane of its orientation,
    /// mm, positive towards larger orientation angles; the axis stays parallel
    /// to that plane. Default 0 (radial); a tangential nozzle has |offset| close
    /// to the course radius minus half the neck OD. |offset| plus half the neck
    /// (or pad) OD may reach 0.98 of the course's outside radius.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub offset: Option<f64>,
    /// Shell nozzles on a cylindrical course: inclination of the nozzle axis
    /// from the course's cross-section plane, degrees, −45 to 45, positive
    /// towards the vessel's top (vertical) or right end (horizontal); the axis
    /// still crosses the vessel axis (or, with an offset, the plane through it)
    /// at `elevation`. Default 0 (square to the axis).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub inclination: Option<f64>,
    /// Distance from the vessel axis (shell nozzles; measured along the nozzle
    /// axis from where it crosses the vessel axis, or for a hillside nozzle the
    /// plane through it) or from the head tangent line (head nozzles) to the
    /// flange face, mm.
    pub projection: f64,
    /// Reinforcing pad.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub pad: Option<PadDesign>,
}

/// A reinforcing pad around a nozzle.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct PadDesign {
    /// Pad outside diameter, mm.
    pub od: f64,
    /// Pad thickness, mm.
    pub thickness: f64,
}

/// A note: text anchored to a target (vessel tag, part id or nozzle mark).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct NoteDesign {
    /// Note id, unique in the vessel.
    pub id: String,
    /// The text.
    pub text: String,
    /// What it annotates: the vessel's tag, a part id or a nozzle mark.
    pub target: String,
    /// Offset of the text from the target's anchor, in the vessel frame, mm.
    #[serde(default)]
    pub offset: [f64; 3],
}

fn is_zero(v: &f64) -> bool {
    *v == 0.0
}

fn default_contact_angle() -> f64 {
    120.0
}

fn default_boot_head() -> HeadShape {
    HeadShape::Ellipsoidal
}

fn default_facing() -> FacingDesign {
    FacingDesign::RaisedFace
}

fn default_schedule() -> String {
    "STD".to_string()
}

impl PartDesign {
    /// The part's id.
    pub fn id(&self) -> &str {
        match self {
            PartDesign::Shell(p) => &p.id,
            PartDesign::Head(p) => &p.id,
            PartDesign::Reducer(p) => &p.id,
            PartDesign::Skirt(p) => &p.id,
            PartDesign::Saddle(p) => &p.id,
            PartDesign::Legs(p) => &p.id,
            PartDesign::Lugs(p) => &p.id,
            PartDesign::Boot(p) => &p.id,
        }
    }

    /// The kind's name as written in files: `"shell"`, `"head"`, ….
    pub fn kind(&self) -> &'static str {
        match self {
            PartDesign::Shell(_) => "shell",
            PartDesign::Head(_) => "head",
            PartDesign::Reducer(_) => "reducer",
            PartDesign::Skirt(_) => "skirt",
            PartDesign::Saddle(_) => "saddle",
            PartDesign::Legs(_) => "legs",
            PartDesign::Lugs(_) => "lugs",
            PartDesign::Boot(_) => "boot",
        }
    }

    /// True for parts of the axial stack (heads, shells, reducers).
    pub fn in_stack(&self) -> bool {
        matches!(
            self,
            PartDesign::Shell(_) | PartDesign::Head(_) | PartDesign::Reducer(_)
        )
    }
}
