//! A vessel with an eccentric reducer: the design the offset-axis tests
//! (`eccentric_reducer`, `mesh_watertight`) build.

use vesselcad::design::{Design, parse};

/// A vessel `tag` of `kind` with an eccentric reducer between a course of OD
/// `below` and one of OD `above`, flat side at `flat_side`: nozzle N1 on the
/// upper course and N3 on the top head (`nozzles[0]` and `[1]`), and with
/// `on_reducer` also N2 on the reducer (`nozzles[2]`).
pub fn eccentric_vessel(
    tag: &str,
    kind: &str,
    below: f64,
    above: f64,
    flat_side: f64,
    on_reducer: bool,
) -> Design {
    let n2 = if on_reducer {
        r#",
            {"mark": "N2", "size": 2, "rating": 150, "host": "R1", "orientation": 200,
              "elevation": 2400, "projection": 1300}"#
    } else {
        ""
    };
    parse(&format!(
        r#"{{"format": "vesselcad/1", "vessels": [{{"tag": "{tag}", "kind": "{kind}",
          "parts": [
            {{"head": {{"id": "H1", "shape": "ellipsoidal"}}}},
            {{"shell": {{"id": "S1", "od": {below}, "length": 2000}}}},
            {{"reducer": {{"id": "R1", "length": 800, "eccentric": {flat_side}}}}},
            {{"shell": {{"id": "S2", "od": {above}, "length": 2000}}}},
            {{"head": {{"id": "H2", "shape": "ellipsoidal"}}}}
          ],
          "nozzles": [
            {{"mark": "N1", "size": 4, "rating": 150, "host": "S2", "orientation": 30,
              "elevation": 3800, "projection": 1200}},
            {{"mark": "N3", "size": 3, "rating": 150, "host": "H2", "orientation": 45,
              "offset": 200, "projection": 600}}{n2}
          ]}}]}}"#
    ))
    .unwrap()
}
