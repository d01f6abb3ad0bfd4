//! Designs and helpers of the scan suites: a small vertical drum with nozzles
//! around it (they fix its turn about the axis) and a small tank.

use vesselcad::design::{Design, parse};
use vesselcad::scan::Envelope;

/// A vertical drum D = 2000 mm, two 3 m courses, ellipsoidal heads, four nozzles.
pub const DRUM: &str = r#"{
  "format": "vesselcad/1", "units": "mm",
  "vessels": [{
    "tag": "V-1", "kind": "vertical",
    "placement": { "position": [5000, 3000, 0], "rotation": 0 },
    "design": { "pressure": 500, "temperature": 100, "corrosion_allowance": 3, "material": "SA-516-70" },
    "parts": [
      { "head": { "id": "H1", "shape": "ellipsoidal", "straight_flange": 50, "thickness": 12 } },
      { "shell": { "id": "S1", "od": 2000, "length": 3000, "thickness": 12 } },
      { "shell": { "id": "S2", "od": 2000, "length": 3000, "thickness": 12 } },
      { "head": { "id": "H2", "shape": "ellipsoidal", "straight_flange": 50, "thickness": 12 } }
    ],
    "nozzles": [
      { "mark": "N1", "service": "inlet", "size": 8, "rating": 150, "facing": "RF", "host": "S2", "orientation": 30, "elevation": 5000, "projection": 1400 },
      { "mark": "N2", "service": "outlet", "size": 6, "rating": 150, "facing": "RF", "host": "S1", "orientation": 160, "elevation": 800, "projection": 1300 },
      { "mark": "N3", "service": "level", "size": 4, "rating": 150, "facing": "RF", "host": "S1", "orientation": 250, "elevation": 2200, "projection": 1250 },
      { "mark": "M1", "service": "manway", "size": 20, "rating": 150, "facing": "RF", "host": "S2", "orientation": 300, "elevation": 4200, "projection": 1500 }
    ]
  }]
}"#;

/// A tank D = 6000 mm, 6 m high in two courses, flat bottom, conical roof.
pub const TANK: &str = r#"{
  "format": "vesselcad/1", "units": "mm",
  "vessels": [{
    "tag": "TK-1", "kind": "tank",
    "placement": { "position": [0, 0, 0], "rotation": 0 },
    "design": { "pressure": 2, "temperature": 40, "corrosion_allowance": 1.5, "material": "A283-C" },
    "parts": [
      { "head": { "id": "BTM", "shape": "flat", "thickness": 8 } },
      { "shell": { "id": "S1", "od": 6000, "length": 3000, "thickness": 10 } },
      { "shell": { "id": "S2", "od": 6000, "length": 3000, "thickness": 8 } },
      { "head": { "id": "ROOF", "shape": "conical", "half_angle": 80, "thickness": 6 } }
    ],
    "nozzles": [
      { "mark": "N1", "service": "inlet", "size": 6, "rating": 150, "facing": "FF", "host": "S2", "orientation": 30, "elevation": 5200, "projection": 3400 },
      { "mark": "N2", "service": "outlet", "size": 8, "rating": 150, "facing": "FF", "host": "S1", "orientation": 210, "elevation": 600, "projection": 3400 }
    ]
  }]
}"#;

/// The design parsed.
pub fn design(text: &str) -> Design {
    parse(text).expect("test design parses")
}

/// The envelope of the design's only vessel.
pub fn envelope(text: &str) -> Envelope {
    let d = design(text);
    let tag = d.vessels[0].tag.clone();
    Envelope::of_design(&d, &tag).expect("envelope builds")
}

/// A vertical drum D = 2000 mm (S1, 3 m) reduced by the cone R1 (900 mm long)
/// to D = 1400 mm (S2, 2 m), ellipsoidal heads, nozzles around both courses.
pub const CONED: &str = r#"{
  "format": "vesselcad/1", "units": "mm",
  "vessels": [{
    "tag": "V-2", "kind": "vertical",
    "placement": { "position": [0, 0, 0], "rotation": 0 },
    "design": { "pressure": 350, "temperature": 100, "corrosion_allowance": 3, "material": "SA-516-70" },
    "parts": [
      { "head": { "id": "H1", "shape": "ellipsoidal", "straight_flange": 50, "thickness": 12 } },
      { "shell": { "id": "S1", "od": 2000, "length": 3000, "thickness": 12 } },
      { "reducer": { "id": "R1", "length": 900, "thickness": 12 } },
      { "shell": { "id": "S2", "od": 1400, "length": 2000, "thickness": 10 } },
      { "head": { "id": "H2", "shape": "ellipsoidal", "straight_flange": 50, "thickness": 10 } }
    ],
    "nozzles": [
      { "mark": "N1", "service": "inlet", "size": 6, "rating": 150, "facing": "RF", "host": "S2", "orientation": 30, "elevation": 5000, "projection": 1100 },
      { "mark": "N2", "service": "outlet", "size": 6, "rating": 150, "facing": "RF", "host": "S1", "orientation": 160, "elevation": 800, "projection": 1300 }
    ]
  }]
}"#;

/// The coned drum of [`CONED`] with a torispherical bottom head H1 (crown
/// 1600, knuckle 200: two patches under the flange) and an eccentric reducer
/// R1, flat side at 90°.
pub const TORI_ECCENTRIC: &str = r#"{
  "format": "vesselcad/1", "units": "mm",
  "vessels": [{
    "tag": "V-3", "kind": "vertical",
    "placement": { "position": [0, 0, 0], "rotation": 0 },
    "design": { "pressure": 350, "temperature": 100, "corrosion_allowance": 3, "material": "SA-516-70" },
    "parts": [
      { "head": { "id": "H1", "shape": "torispherical", "crown_radius": 1600, "knuckle_radius": 200, "straight_flange": 50, "thickness": 12 } },
      { "shell": { "id": "S1", "od": 2000, "length": 3000, "thickness": 12 } },
      { "reducer": { "id": "R1", "length": 900, "thickness": 12, "eccentric": 90 } },
      { "shell": { "id": "S2", "od": 1400, "length": 2000, "thickness": 10 } },
      { "head": { "id": "H2", "shape": "ellipsoidal", "straight_flange": 50, "thickness": 10 } }
    ],
    "nozzles": [
      { "mark": "N1", "service": "inlet", "size": 6, "rating": 150, "facing": "RF", "host": "S2", "orientation": 30, "elevation": 5000, "projection": 1100 },
      { "mark": "N2", "service": "outlet", "size": 6, "rating": 150, "facing": "RF", "host": "S1", "orientation": 160, "elevation": 800, "projection": 1300 }
    ]
  }]
}"#;
