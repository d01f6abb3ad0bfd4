//! The `extras` metadata of vessel, part and nozzle nodes, from a design entry and
//! its resolved data.
//!
//! Scene builders (the direct [`build_scene`](super::build_scene) and the ECS model)
//! call these when they assemble a [`Scene`](super::Scene); the glTF writer copies
//! the values verbatim into each node's `extras`. Every object has
//!
//! - `id` — the vessel tag, part id or nozzle mark (a part's stable id is
//!   `tag/id`), and `kind` (`horizontal`, `vertical` or `tank` for a vessel;
//!   `shell`, `head`, … for a part; `nozzle`);
//! - `parameters` — the design entry as a canonical design file writes it;
//! - `resolved` — values the constraint stage derived (inherited diameters, spans,
//!   neck lengths, …).
//!
//! Lengths are mm, angles degrees, pressure kPa gauge, temperature °C, sizes NPS
//! inches, whatever the units of the source file. Objects are `serde_json` maps, so
//! keys come out sorted and the output is deterministic.

use serde::Serialize;
use serde_json::{Map, Value, json};

use crate::constraints::{PartGeometry, ResolvedNozzle, ResolvedPart, ResolvedVessel};
use crate::design::{NozzleDesign, PartDesign, VesselDesign, VesselKind};
use crate::parts::ReducerAlignment;
use crate::parts::heads::{Head, HeadKind};

/// `extras` of a vessel node: kind, placement and design conditions as written,
/// and the tangent length, largest course OD and axial extent, mm.
pub fn vessel_extras(design: &VesselDesign, resolved: &ResolvedVessel) -> Value {
    json!({
        "id": resolved.tag,
        "kind": vessel_kind(resolved.kind),
        "parameters": {
            "placement": to_value(&design.placement),
            "design": to_value(&design.design),
        },
        "resolved": {
            "tangent_length": resolved.tangent_length,
            "max_od": resolved.max_diameter,
            "extent": [resolved.extent.0, resolved.extent.1],
            "parts": resolved.parts.len(),
            "nozzles": resolved.nozzles.len(),
        },
    })
}

/// `extras` of a part node: id, kind, the design parameters as written, and the
/// resolved dimensions (inherited diameters filled in) and axial span, mm.
pub fn part_extras(design: &PartDesign, resolved: &ResolvedPart) -> Value {
    let mut values = geometry_values(&resolved.geometry);
    values.insert("span".into(), json!([resolved.span.0, resolved.span.1]));
    json!({
        "id": resolved.id,
        "kind": resolved.geometry.kind(),
        "parameters": part_parameters(design),
        "resolved": Value::Object(values),
    })
}

/// `extras` of a nozzle node: id (its mark), kind, the design entry as written (mark,
/// service, size, rating, facing, flange, schedule, host, orientation,
/// elevation or offset, inclination, projection, pad) and the resolved neck and flange
/// lengths, neck OD and bore, mm.
pub fn nozzle_extras(design: &NozzleDesign, resolved: &ResolvedNozzle) -> Value {
    let nozzle = &resolved.geometry;
    let mut values = Map::new();
    values.insert("size".into(), json!(nozzle.nps.label()));
    values.insert("rating".into(), json!(nozzle.class.rating()));
    values.insert("schedule".into(), json!(nozzle.schedule.label()));
    values.insert("neck_od".into(), json!(nozzle.outside_diameter()));
    values.insert("projection".into(), json!(nozzle.projection));
    // Both lengths exist for every resolved nozzle (its size and class were looked
    // up when it was resolved); a missing entry would only omit the key.
    if let Ok(length) = nozzle.flange_length() {
        values.insert("flange_length".into(), json!(length));
    }
    if let Ok(length) = nozzle.neck_length() {
        values.insert("neck_length".into(), json!(length));
    }
    if let Some((od, thickness)) = resolved.pad {
        values.insert("pad".into(), json!({ "od": od, "thickness": thickness }));
    }
    json!({
        "id": resolved.mark,
        "kind": "nozzle",
        "parameters": to_value(design),
        "resolved": Value::Object(values),
    })
}

/// The name of a vessel kind as design files write it.
fn vessel_kind(kind: VesselKind) -> &'static str {
    match kind {
        VesselKind::Horizontal => "horizontal",
        VesselKind::Vertical => "vertical",
        VesselKind::Tank => "tank",
    }
}

/// The body of a part entry (without its `{"kind": …}` wrapper), as written.
fn part_parameters(design: &PartDesign) -> Value {
    match design {
        PartDesign::Shell(p) => to_value(p),
        PartDesign::Head(p) => to_value(p),
        PartDesign::Reducer(p) => to_value(p),
        PartDesign::Skirt(p) => to_value(p),
        PartDesign::Saddle(p) => to_value(p),
        PartDesign::Legs(p) => to_value(p),
        PartDesign::Lugs(p) => to_value(p),
        PartDesign::Boot(p) => to_value(p),
    }
}

/// A design value as JSON. The design types are plain data with string keys,
/// whose serialization cannot fail; non-finite numbers become `null`.
fn to_value<T: Serialize>(value: &T) -> Value {
    serde_json::to_value(value).unwrap_or_default()
}

/// The resolved dimensions of a part, design-file names where there is one.
fn geometry_values(geometry: &PartGeometry) -> Map<String, Value> {
    let value = match geometry {
        PartGeometry::Shell(s) => json!({ "od": s.outside_diameter, "length": s.length }),
        PartGeometry::Head(h) => return head_values(h),
        PartGeometry::Reducer(r) => {
            let mut v = json!({
                "large_od": r.large_diameter,
                "small_od": r.small_diameter,
                "length": r.length,
                "half_angle": r.half_angle(),
                "alignment": "concentric",
            });
            if let ReducerAlignment::Eccentric { flat_side } = r.alignment {
                v["alignment"] = json!("eccentric");
                v["flat_side"] = json!(flat_side);
            }
            v
        }
        PartGeometry::Skirt(s) => json!({
            "top_od": s.top_diameter,
            "base_od": s.bottom_diameter(),
            "height": s.height,
            "flare_angle": s.flare_angle,
            "thickness": s.thickness,
            "base_ring_width": s.base_ring_width,
        }),
        PartGeometry::Saddle(s) => json!({
            "shell_od": s.shell_diameter,
            "contact_angle": s.contact_angle,
            "width": s.width,
            "height": s.height,
            "web_thickness": s.web_thickness,
            "base_length": s.base_length,
            "base_width": s.base_width,
            "base_thickness": s.base_thickness,
        }),
        PartGeometry::Legs(l) => json!({
            "count": l.count,
            "pipe_od": l.pipe_diameter,
            "length": l.length,
            "shell_od": l.shell_diameter,
            "first_angle_local": l.first_angle,
        }),
        PartGeometry::Lugs(l) => json!({
            "count": l.count,
            "shell_od": l.shell_diameter,
            "height": l.height,
            "projection": l.projection,
            "width": l.width,
            "first_angle_local": l.first_angle,
        }),
        PartGeometry::Boot(b) => {
            let mut v = json!({
                "od": b.diameter,
                "length": b.length,
                "host_od": b.host_diameter,
                "head": Value::Object(head_kind_values(&b.head)),
            });
            if let Ok(depth) = b.head_part().depth() {
                v["head"]["depth"] = json!(depth);
            }
            v
        }
    };
    match value {
        Value::Object(map) => map,
        _ => Map::new(),
    }
}

/// Resolved dimensions of a head: OD, straight flange, shape parameters (defaults
/// filled in) and dished depth.
fn head_values(head: &Head) -> Map<String, Value> {
    let mut map = head_kind_values(&head.kind);
    map.insert("od".into(), json!(head.outside_diameter));
    map.insert("straight_flange".into(), json!(head.straight_flange));
    // A resolved head has a valid profile, so its depth exists.
    if let Ok(depth) = head.depth() {
        map.insert("depth".into(), json!(depth));
    }
    map
}

/// The shape and shape parameters of a head kind, design-file names.
fn head_kind_values(kind: &HeadKind) -> Map<String, Value> {
    let mut map = Map::new();
    map.insert("shape".into(), json!(kind.name()));
    let mut put = |key: &str, value: f64| {
        map.insert(key.into(), json!(value));
    };
    match *kind {
        HeadKind::Hemispherical => {}
        HeadKind::Ellipsoidal { ratio } => put("ratio", ratio),
        HeadKind::Torispherical {
            crown_radius,
            knuckle_radius,
        } => {
            put("crown_radius", crown_radius);
            put("knuckle_radius", knuckle_radius);
        }
        HeadKind::Toriconical {
            half_angle,
            knuckle_radius,
        } => {
            put("half_angle", half_angle);
            put("knuckle_radius", knuckle_radius);
        }
        HeadKind::Conical {
            half_angle,
            small_diameter,
        } => {
            put("half_angle", half_angle);
            put("small_od", small_diameter);
        }
        HeadKind::Flat { knuckle_radius } => put("knuckle_radius", knuckle_radius),
    }
    map
}
