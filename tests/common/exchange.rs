//! Designs the exchange tests (STEP and IGES) share: two storage tanks, the
//! second with its roof vent on the roof's apex (an opening round its host's
//! pole), and the same with a nozzle facing its course's seam, with and
//! without a pad; repros by name;
//! the support edges lying on envelope edges (where sewing IGES faces differs
//! from STEP's shared edges).

use std::path::Path;

use glam::DVec3;
use serde_json::Value;
use vesselcad::design::{Design, parse};
use vesselcad::exchange::{Edge, NodeKind, VesselSource, vessel_brep_with};

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

/// [`across_seam`] with a reinforcing pad (500 mm OD) round that nozzle:
/// the pad's loop and the neck's both cross the course's seam.
pub fn across_seam_padded() -> Design {
    let mut json: Value = serde_json::to_value(across_seam()).expect("json");
    json["vessels"][1]["nozzles"][0]["pad"] = serde_json::json!({"od": 500, "thickness": 10});
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

/// Support edges used by one face that coincide with an envelope edge used by
/// two (sampled, 1e-2 mm: such edges lie on one another or millimetres apart).
pub fn support_edges_on_envelope(sources: &[VesselSource]) -> usize {
    let mut count = 0;
    for source in sources {
        let brep = vessel_brep_with(source, false).expect("brep");
        let mut uses = vec![(0usize, false); brep.edges.len()];
        for f in &brep.faces {
            let support = source.nodes[f.node].kind == NodeKind::Support;
            for e in f.outer.iter().chain(f.holes.iter().flatten()) {
                uses[e.edge].0 += 1;
                uses[e.edge].1 |= support;
            }
        }
        let samples = |e: &Edge, n: usize| -> Vec<DVec3> {
            let (a, b) = e.curve.domain();
            (0..=n)
                .map(|k| e.curve.point(a + (b - a) * k as f64 / n as f64))
                .collect()
        };
        // Each envelope edge's dense samples with their box.
        let envelope: Vec<(DVec3, DVec3, Vec<DVec3>)> = brep
            .edges
            .iter()
            .zip(&uses)
            .filter(|(_, u)| **u == (2, false))
            .map(|(e, _)| {
                let dense = samples(e, 4096);
                let lo = dense.iter().fold(DVec3::INFINITY, |m, p| m.min(*p));
                let hi = dense.iter().fold(DVec3::NEG_INFINITY, |m, p| m.max(*p));
                (lo - 1e-2, hi + 1e-2, dense)
            })
            .collect();
        for (e, _) in brep
            .edges
            .iter()
            .zip(&uses)
            .filter(|(_, u)| **u == (1, true))
        {
            let points = samples(e, 16);
            let on = |(lo, hi, dense): &(DVec3, DVec3, Vec<DVec3>)| {
                points
                    .iter()
                    .all(|p| p.cmpge(*lo).all() && p.cmple(*hi).all())
                    && points.iter().all(|p| {
                        dense
                            .windows(2)
                            .any(|w| segment_distance(*p, w[0], w[1]) <= 1e-2)
                    })
            };
            count += usize::from(envelope.iter().any(on));
        }
    }
    count
}

/// Distance from `p` to the segment `a`–`b`.
fn segment_distance(p: DVec3, a: DVec3, b: DVec3) -> f64 {
    let d = b - a;
    let t = if d.length_squared() > 0.0 {
        ((p - a).dot(d) / d.length_squared()).clamp(0.0, 1.0)
    } else {
        0.0
    };
    p.distance(a + d * t)
}
