//! Unrolled deviation maps in the scan report: every course and head of the
//! drum has a map (courses unrolled, heads polar) in the HTML, and a simulated
//! dent is its course's extreme cell, at the dent's orientation and elevation.

mod common;

use common::scan::{DRUM, envelope};
use vesselcad::scan::defects::parse_defects;
use vesselcad::scan::fit::FitOptions;
use vesselcad::scan::inspect::{InspectOptions, inspect};
use vesselcad::scan::report::to_html_with_maps;
use vesselcad::scan::simulate::{SimulateOptions, simulate};
use vesselcad::scan::unrolled::{Layout, unrolled_maps};

#[test]
fn each_part_has_a_map_and_a_dent_is_its_extreme_cell() {
    let env = envelope(DRUM);
    let scan = simulate(
        &env,
        &SimulateOptions {
            density: 400.0,
            noise: 1.5,
            occlusion: 0.0,
            seed: 5,
            site: None,
            defects: parse_defects("dent=25mm@EL4000/90°", &env).unwrap(),
        },
    )
    .unwrap();
    let options = InspectOptions {
        register: None,
        fit: FitOptions {
            noise: 1.5,
            ..FitOptions::DEFAULT
        },
        ..InspectOptions::DEFAULT
    };
    let inspection = inspect(&env, scan.points, &options).unwrap();
    let maps = unrolled_maps(&env, &inspection);
    let parts: Vec<(&str, Layout)> = maps.iter().map(|m| (m.part.as_str(), m.layout)).collect();
    assert_eq!(
        parts,
        [
            ("H1", Layout::Polar),
            ("S1", Layout::Unrolled),
            ("S2", Layout::Unrolled),
            ("H2", Layout::Polar)
        ]
    );
    for m in &maps {
        let extreme = m.extreme().expect("a map with data");
        eprintln!(
            "{}: {} × {}, extreme {extreme:?}",
            m.part, m.sectors, m.rows
        );
        assert_eq!(m.cells.len(), m.sectors * m.rows);
    }
    let s2 = maps.iter().find(|m| m.part == "S2").unwrap();
    let dent = s2.extreme().unwrap();
    let depth = dent.deviation.unwrap();
    assert!(depth < -10.0, "{dent:?}");
    let orientation = (dent.orientation.0 + dent.orientation.1) / 2.0;
    let elevation = (dent.band.0 + dent.band.1) / 2.0;
    assert!((orientation - 90.0).abs() <= 5.0, "{dent:?}");
    assert!((elevation - 4000.0).abs() <= 100.0, "{dent:?}");
    // Elsewhere the maps stay well inside the dent's depth.
    for m in maps.iter().filter(|m| m.part != "S2") {
        let d = m.extreme().unwrap().deviation.unwrap();
        assert!(d.abs() < depth.abs() / 2.0, "{}: {d} mm", m.part);
    }

    let html = to_html_with_maps(&inspection, &maps, 5.0);
    assert_eq!(html.matches("<svg class=\"map\"").count(), 4);
    for part in ["H1", "S1", "S2", "H2"] {
        assert!(html.contains(&format!("data-part=\"{part}\"")), "{part}");
    }
    assert!(html.contains("extreme cell"), "the extreme cell is named");
}
