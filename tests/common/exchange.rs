//! Designs the exchange tests (STEP and IGES) share: two storage tanks, the
//! second with its roof vent on the roof's apex (an opening round its host's
//! pole), and the same with a nozzle facing its course's seam.

use std::path::Path;

use serde_json::Value;
use vesselcad::design::{Design, parse};

/// The storage tank with its roof vent moved onto the roof's apex (an opening
/// round the pole of its host) and a second tank beside it.
pub fn two_tanks() -> Design {
    let text = std::fs::read_to_string(
        Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/designs/storage-tank.json"),
    )
    .expect("example reads");
    let mut json: Value = serde_json::from_str(&text).expect("json");
    let mut second = json["vessels"][0].clone();
    second["tag"] = "TK-302".into();
    second["placement"]["position"] = serde_json::json!([20000, 25000, 0]);
    second["placement"]["rotation"] = 30.into();
    second["nozzles"][2]["offset"] = 0.into();
    json["vessels"]
        .as_array_mut()
        .expect("vessels")
        .push(second);
    parse(&json.to_string()).expect("two tanks are valid")
}

/// [`two_tanks`] with the second tank's first nozzle at 60°, its opening across
/// the course's seam.
pub fn across_seam() -> Design {
    let mut json: Value = serde_json::to_value(two_tanks()).expect("json");
    json["vessels"][1]["nozzles"][0]["orientation"] = 60.into();
    serde_json::from_value(json).expect("design")
}

/// A repro design of `tests/repros` by name.
pub fn repro(name: &str) -> Design {
    vesselcad::design::load(
        Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("tests/repros")
            .join(format!("{name}.json")),
    )
    .expect("the repro loads")
}
