//! The search features of a vessel: the few numbers and words an engineer looks
//! for a previous vessel by (kind, diameter, length, head, pressure, temperature,
//! material, nozzles), one row of the `vessels` table per vessel of each design's
//! newest revision.

use serde::Serialize;

use crate::design::{PartDesign, VesselDesign};

/// One vessel's features. Units: mm, kPa gauge, °C, NPS inches.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Features {
    /// The vessel's tag.
    pub tag: String,
    /// `horizontal`, `vertical` or `tank`.
    pub kind: String,
    /// The first head's shape (`ellipsoidal`, …), `none` without heads.
    pub head: String,
    /// The material specification, empty when not given.
    pub material: String,
    /// The largest shell course's outside diameter, mm.
    pub od: f64,
    /// Tangent-to-tangent length: shell courses and reducers, mm.
    pub length: f64,
    /// Design pressure, kPa gauge (0 when not given).
    pub pressure: f64,
    /// Design temperature, °C (0 when not given).
    pub temperature: f64,
    /// How many nozzles.
    pub nozzles: i64,
    /// The largest nozzle, NPS (0 without nozzles).
    pub max_nozzle: f64,
    /// The sum of the nozzle sizes, NPS.
    pub nozzle_total: f64,
}

/// A serde enum's name (`"ellipsoidal"`), or `""`.
fn name_of(value: &impl Serialize) -> String {
    serde_json::to_value(value)
        .ok()
        .and_then(|v| v.as_str().map(str::to_string))
        .unwrap_or_default()
}

impl Features {
    /// The features of `vessel` (a design in mm).
    pub fn of(vessel: &VesselDesign) -> Features {
        let mut od: f64 = 0.0;
        let mut length = 0.0;
        let mut head = None;
        for part in &vessel.parts {
            match part {
                PartDesign::Shell(s) => {
                    od = od.max(s.od);
                    length += s.length;
                }
                PartDesign::Reducer(r) => length += r.length,
                PartDesign::Head(h) if head.is_none() => head = Some(name_of(&h.shape)),
                _ => {}
            }
        }
        let sizes = vessel.nozzles.iter().map(|n| n.size);
        Features {
            tag: vessel.tag.clone(),
            kind: name_of(&vessel.kind),
            head: head.unwrap_or_else(|| "none".into()),
            material: vessel.design.material.clone().unwrap_or_default(),
            od,
            length,
            pressure: vessel.design.pressure.unwrap_or(0.0),
            temperature: vessel.design.temperature.unwrap_or(0.0),
            nozzles: vessel.nozzles.len() as i64,
            max_nozzle: sizes.clone().fold(0.0, f64::max),
            nozzle_total: sizes.sum(),
        }
    }
}
