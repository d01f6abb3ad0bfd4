//! The JSON Schema of the `vesselcad/1` format, for editors that complete and check
//! design files (`docs/vesselcad-1.schema.json` is this schema, checked in; a test
//! keeps it equal to [`json_schema`]'s output).
//!
//! The shape — fields, types, defaults, required fields, the enumerations' strings —
//! is derived by `schemars` from the serde types of [`crate::design`], so it cannot
//! drift from what the loader accepts. What a type cannot say (a contact angle lies
//! in 120–150°, a nozzle size is one of the twenty standard NPS, a length is
//! positive) is added here from the constants the design rules use, where those
//! constants are public, and from the rules' literal bounds otherwise. The schema is
//! a first check, not the whole one: rules that relate two fields (a knuckle smaller
//! than the crown, a nozzle inside its host) are only checked by
//! [`crate::design::validate`]. Length bounds are unit-free (`> 0`, `≥ 0`) because a file may
//! be written in inches.

use serde_json::{Value, json};

use crate::constraints::{
    ABSOLUTE_ZERO, ELLIPSOIDAL_RATIO, FULL_VACUUM, MAX_INCLINATION, MAX_NAME_CHARS, MAX_PRESSURE,
    MAX_REVISION, MAX_SPECTRAL_ACCELERATION, MAX_TEMPERATURE, MAX_TITLE_TEXT, MAX_WIND_SPEED,
};
use crate::design::{Design, FORMAT};
use crate::operating::MAX_DENSITY;
use crate::parts::tables::{FlangeClass, Nps, PipeSchedule};
use crate::parts::{MAX_LEGS, MAX_LUGS};

/// The `$id` of the schema: the file's path in the repository.
pub const SCHEMA_ID: &str = "docs/vesselcad-1.schema.json";

/// Largest angle either way of an orientation, a plan rotation or an eccentric
/// reducer's flat side, degrees (the rule of `constraints::frames::check_angle` and
/// of the legs', lugs' and reducer's builders).
const MAX_ANGLE: f64 = 360.0;

/// One bound the serde types cannot express: a keyword set on one property.
struct Bound {
    /// The type's name (`$defs` key), or `""` for the top-level `Design`.
    def: &'static str,
    /// The property's name as written in files.
    field: &'static str,
    /// The JSON Schema keyword (`minimum`, `enum`, …) and its value.
    keyword: &'static str,
    value: Value,
}

fn bound(def: &'static str, field: &'static str, keyword: &'static str, value: Value) -> Bound {
    Bound {
        def,
        field,
        keyword,
        value,
    }
}

/// Every bound, with the rule it comes from.
fn bounds() -> Vec<Bound> {
    let positive = || json!(0.0);
    let mut b = vec![
        bound("", "format", "const", json!(FORMAT)),
        // Identities: non-empty strings.
        bound("VesselDesign", "tag", "minLength", json!(1)),
        bound("NozzleDesign", "mark", "minLength", json!(1)),
        bound("NozzleDesign", "host", "minLength", json!(1)),
        bound("NoteDesign", "id", "minLength", json!(1)),
        bound("NoteDesign", "target", "minLength", json!(1)),
        // Design conditions (constraints::conditions).
        bound(
            "DesignConditions",
            "pressure",
            "minimum",
            json!(FULL_VACUUM),
        ),
        bound(
            "DesignConditions",
            "pressure",
            "maximum",
            json!(MAX_PRESSURE),
        ),
        bound(
            "DesignConditions",
            "temperature",
            "exclusiveMinimum",
            json!(ABSOLUTE_ZERO),
        ),
        bound(
            "DesignConditions",
            "temperature",
            "maximum",
            json!(MAX_TEMPERATURE),
        ),
        bound(
            "DesignConditions",
            "corrosion_allowance",
            "minimum",
            json!(0.0),
        ),
        bound(
            "DesignConditions",
            "external_pressure",
            "minimum",
            json!(0.0),
        ),
        bound(
            "DesignConditions",
            "external_pressure",
            "maximum",
            json!(MAX_PRESSURE),
        ),
        bound(
            "DesignConditions",
            "joint_efficiency",
            "exclusiveMinimum",
            json!(0.0),
        ),
        bound(
            "DesignConditions",
            "joint_efficiency",
            "maximum",
            json!(1.0),
        ),
        bound(
            "DesignConditions",
            "metal_density",
            "exclusiveMinimum",
            positive(),
        ),
        bound(
            "DesignConditions",
            "metal_density",
            "maximum",
            json!(MAX_DENSITY),
        ),
        bound("OperatingDesign", "liquid_level", "minimum", json!(0.0)),
        bound(
            "OperatingDesign",
            "liquid_density",
            "exclusiveMinimum",
            positive(),
        ),
        bound(
            "OperatingDesign",
            "liquid_density",
            "maximum",
            json!(MAX_DENSITY),
        ),
        // Title block (constraints::conditions).
        bound("DrawingInfo", "number", "maxLength", json!(MAX_TITLE_TEXT)),
        bound("DrawingInfo", "title", "maxLength", json!(MAX_TITLE_TEXT)),
        bound("DrawingInfo", "revision", "maxLength", json!(MAX_REVISION)),
        bound(
            "DrawingInfo",
            "date",
            "pattern",
            json!(r"^[0-9]{4}-[0-9]{2}-[0-9]{2}$"),
        ),
        // Head shapes (constraints::head_limits, parts::heads): the ellipsoidal
        // ratio the geometry is built and tested for, cone half-angle 1–89°.
        bound("HeadDesign", "ratio", "minimum", json!(ELLIPSOIDAL_RATIO.0)),
        bound("HeadDesign", "ratio", "maximum", json!(ELLIPSOIDAL_RATIO.1)),
        bound("HeadDesign", "half_angle", "minimum", json!(1.0)),
        bound("HeadDesign", "half_angle", "maximum", json!(89.0)),
        bound("HeadDesign", "crown_radius", "exclusiveMinimum", positive()),
        bound("HeadDesign", "knuckle_radius", "minimum", json!(0.0)),
        bound("HeadDesign", "small_od", "minimum", json!(0.0)),
        bound("HeadDesign", "straight_flange", "minimum", json!(0.0)),
        // Supports (parts::skirt, saddle, legs, lugs).
        bound("SkirtDesign", "flare_angle", "minimum", json!(0.0)),
        bound("SkirtDesign", "flare_angle", "maximum", json!(45.0)),
        bound("SkirtDesign", "base_ring_width", "minimum", json!(0.0)),
        bound("SaddleDesign", "contact_angle", "minimum", json!(120.0)),
        bound("SaddleDesign", "contact_angle", "maximum", json!(150.0)),
        bound("LegsDesign", "count", "minimum", json!(3)),
        bound("LegsDesign", "count", "maximum", json!(MAX_LEGS)),
        bound("LugsDesign", "count", "minimum", json!(2)),
        bound("LugsDesign", "count", "maximum", json!(MAX_LUGS)),
        // Nozzles (parts::tables): standard sizes, classes and schedules.
        bound("NozzleDesign", "size", "enum", json!(nps_sizes())),
        bound("LegsDesign", "size", "enum", json!(nps_sizes())),
        bound("NozzleDesign", "rating", "enum", json!(ratings())),
        bound("NozzleDesign", "schedule", "enum", json!(schedules())),
        // Shell nozzles (constraints::shell_nozzle): the inclination range; the
        // hillside offset is signed (a head nozzle's offset, ≥ 0, is a rule).
        bound(
            "NozzleDesign",
            "inclination",
            "minimum",
            json!(-MAX_INCLINATION),
        ),
        bound(
            "NozzleDesign",
            "inclination",
            "maximum",
            json!(MAX_INCLINATION),
        ),
        // Names (constraints::names).
        bound("VesselDesign", "tag", "maxLength", json!(MAX_NAME_CHARS)),
        bound("NozzleDesign", "mark", "maxLength", json!(MAX_NAME_CHARS)),
        bound("NoteDesign", "id", "maxLength", json!(MAX_NAME_CHARS)),
    ];
    // Part ids: non-empty (they share one namespace with marks and note ids).
    for def in [
        "ShellDesign",
        "HeadDesign",
        "ReducerDesign",
        "SkirtDesign",
        "SaddleDesign",
        "LegsDesign",
        "LugsDesign",
        "BootDesign",
    ] {
        b.push(bound(def, "id", "minLength", json!(1)));
        b.push(bound(def, "id", "maxLength", json!(MAX_NAME_CHARS)));
    }
    // Angles: within one turn either way.
    for (def, field) in [
        ("Placement", "rotation"),
        ("NozzleDesign", "orientation"),
        ("ReducerDesign", "eccentric"),
        ("LegsDesign", "orientation"),
        ("LugsDesign", "orientation"),
    ] {
        b.push(bound(def, field, "minimum", json!(-MAX_ANGLE)));
        b.push(bound(def, field, "maximum", json!(MAX_ANGLE)));
    }
    // Lengths a part needs: positive.
    for (def, field) in [
        ("ShellDesign", "od"),
        ("ShellDesign", "length"),
        ("ShellDesign", "thickness"),
        ("HeadDesign", "thickness"),
        ("ReducerDesign", "length"),
        ("ReducerDesign", "thickness"),
        ("SkirtDesign", "height"),
        ("SkirtDesign", "thickness"),
        ("SkirtDesign", "base_ring_thickness"),
        ("SaddleDesign", "width"),
        ("SaddleDesign", "height"),
        ("SaddleDesign", "web_thickness"),
        ("SaddleDesign", "wear_plate"),
        ("LegsDesign", "length"),
        ("LugsDesign", "height"),
        ("LugsDesign", "projection"),
        ("LugsDesign", "width"),
        ("BootDesign", "od"),
        ("BootDesign", "length"),
        ("NozzleDesign", "projection"),
        ("PadDesign", "od"),
        ("PadDesign", "thickness"),
    ] {
        b.push(bound(def, field, "exclusiveMinimum", positive()));
    }
    // Wind and earthquake (constraints::conditions::check_lateral), anchor bolts
    // (constraints::supports).
    for (def, field, keyword, value) in [
        ("WindDesign", "speed", "exclusiveMinimum", 0.0),
        ("WindDesign", "speed", "maximum", MAX_WIND_SPEED),
        ("WindDesign", "area_factor", "minimum", 1.0),
        ("WindDesign", "area_factor", "maximum", 5.0),
        ("WindDesign", "base_elevation", "minimum", 0.0),
        ("SeismicDesign", "sds", "minimum", 0.0),
        ("SeismicDesign", "sds", "maximum", MAX_SPECTRAL_ACCELERATION),
        ("SeismicDesign", "sd1", "minimum", 0.0),
        ("SeismicDesign", "sd1", "maximum", MAX_SPECTRAL_ACCELERATION),
        ("SeismicDesign", "response_modification", "minimum", 1.0),
        ("SeismicDesign", "response_modification", "maximum", 8.0),
        ("SeismicDesign", "importance", "minimum", 1.0),
        ("SeismicDesign", "importance", "maximum", 1.5),
        ("SeismicDesign", "period", "exclusiveMinimum", 0.0),
        ("SeismicDesign", "period", "maximum", 20.0),
        ("SkirtDesign", "anchor_bolts", "minimum", 2.0),
        ("SkirtDesign", "anchor_bolts", "maximum", 1000.0),
    ] {
        b.push(bound(def, field, keyword, json!(value)));
    }
    for field in [
        "importance",
        "topographic_factor",
        "directionality_factor",
        "gust_factor",
        "force_coefficient",
    ] {
        b.push(bound("WindDesign", field, "exclusiveMinimum", positive()));
        b.push(bound("WindDesign", field, "maximum", json!(5.0)));
    }
    b
}

/// The twenty standard nominal pipe sizes, inches.
fn nps_sizes() -> Vec<f64> {
    Nps::ALL.iter().map(|n| n.inches()).collect()
}

/// The flange pressure classes.
fn ratings() -> Vec<u32> {
    FlangeClass::ALL.iter().map(|c| c.rating()).collect()
}

/// The pipe schedules' names as written in files.
fn schedules() -> Vec<&'static str> {
    PipeSchedule::ALL.iter().map(|s| s.label()).collect()
}

/// The JSON Schema (draft 2020-12) of the `vesselcad/1` design format.
///
/// # Panics
///
/// If a bound names a type or field the serde types no longer have (a programmer
/// error, caught by the schema test).
pub fn json_schema() -> Value {
    let mut schema = schemars::schema_for!(Design).to_value();
    schema["$id"] = json!(SCHEMA_ID);
    schema["title"] = json!(format!("{FORMAT} design file"));
    for b in bounds() {
        let pointer = if b.def.is_empty() {
            format!("/properties/{}", b.field)
        } else {
            format!("/$defs/{}/properties/{}", b.def, b.field)
        };
        let property = schema
            .pointer_mut(&pointer)
            .and_then(Value::as_object_mut)
            .unwrap_or_else(|| panic!("the schema has no property at {pointer}"));
        property.insert(b.keyword.to_string(), b.value);
    }
    schema
}

/// [`json_schema`] as the checked-in file holds it: pretty-printed, with a final
/// newline.
pub fn json_schema_text() -> String {
    let mut text = serde_json::to_string_pretty(&json_schema())
        .expect("a serde_json::Value always serialises");
    text.push('\n');
    text
}
