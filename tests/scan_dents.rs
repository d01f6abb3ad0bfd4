//! Dents and bulges on every part of the envelope: a simulated dent on a head,
//! on a concentric and on an eccentric cone is found within 10 % of its depth
//! and 100 mm of its place; a dent across a head's knuckle–crown line is one
//! dent, not one per patch; a clean scan reports none on its heads, cones and
//! courses, even when the fit is told a noise below the scan's (its net then
//! follows the noise, and overshoots where few points hold it, at the courses'
//! ends).

mod common;

use common::scan::{CONED, DRUM, TORI_ECCENTRIC, envelope};
use glam::DVec3;
use vesselcad::scan::Envelope;
use vesselcad::scan::checks::Finding;
use vesselcad::scan::defects::parse_defects;
use vesselcad::scan::fit::FitOptions;
use vesselcad::scan::inspect::{InspectOptions, Inspection, inspect};
use vesselcad::scan::simulate::{SimulateOptions, simulate};

/// A scan in the plant frame: 1.5 mm noise, a fifth of it hidden.
fn scan(env: &Envelope, defects: &str, density: f64, seed: u64) -> Vec<DVec3> {
    simulate(
        env,
        &SimulateOptions {
            density,
            noise: 1.5,
            occlusion: 0.2,
            seed,
            site: None,
            defects: parse_defects(defects, env).unwrap(),
        },
    )
    .unwrap()
    .points
}

/// Inspected in the plant frame, the fit told `noise`.
fn inspected(env: &Envelope, points: Vec<DVec3>, noise: f64) -> Inspection {
    let options = InspectOptions {
        register: None,
        fit: FitOptions {
            noise,
            ..FitOptions::DEFAULT
        },
        ..InspectOptions::DEFAULT
    };
    inspect(env, points, &options).unwrap()
}

fn local(findings: &[Finding]) -> Vec<&Finding> {
    findings
        .iter()
        .filter(|f| f.kind == "dent" || f.kind == "bulge")
        .collect()
}

/// The deepest dent on `part`.
fn dent<'a>(findings: &'a [Finding], part: &str) -> &'a Finding {
    findings
        .iter()
        .filter(|f| f.kind == "dent" && f.part == part)
        .max_by(|a, b| a.size.total_cmp(&b.size))
        .unwrap_or_else(|| panic!("no dent on {part}: {findings:#?}"))
}

/// Distance along a circle of radius `r` between two orientations, mm.
fn arc(r: f64, a: f64, b: f64) -> f64 {
    let d = (a - b).rem_euclid(360.0);
    r * d.min(360.0 - d).to_radians()
}

#[test]
fn dents_on_a_head_and_a_cone_are_found_in_depth_and_place() {
    let env = envelope(CONED);
    // R1 runs from EL3000 (D 2000) to EL3900 (D 1400): radius 850 at EL3450.
    // H1's ellipsoid (depth 500) falls from EL−50: radius 866 at EL−300.
    let points = scan(
        &env,
        "dent=20mm@EL3450/120°,dent=20mm@EL-300/240°",
        400.0,
        21,
    );
    let i = inspected(&env, points, 1.5);
    let f = &i.checks.findings;
    let cone = dent(f, "R1");
    assert!((cone.size - 20.0).abs() <= 2.0, "{cone:?}");
    assert!((cone.elevation - 3450.0).abs() <= 100.0, "{cone:?}");
    assert!(arc(850.0, cone.orientation, 120.0) <= 100.0, "{cone:?}");
    assert!(
        cone.extent.is_some_and(|e| e > 200.0 && e < 900.0),
        "{cone:?}"
    );
    let head = dent(f, "H1");
    assert!((head.size - 20.0).abs() <= 2.0, "{head:?}");
    assert!((head.elevation + 300.0).abs() <= 100.0, "{head:?}");
    assert!(arc(866.0, head.orientation, 240.0) <= 100.0, "{head:?}");
    // Nothing else of a dent's size.
    let others: Vec<&Finding> = local(f)
        .into_iter()
        .filter(|x| !std::ptr::eq(*x, cone) && !std::ptr::eq(*x, head) && x.size > 7.5)
        .collect();
    assert!(others.is_empty(), "{others:#?}");
    // In the JSON report as every finding is.
    let json = serde_json::to_value(&i.checks).unwrap();
    let listed = json["findings"]
        .as_array()
        .unwrap()
        .iter()
        .filter(|x| x["kind"] == "dent" && (x["part"] == "R1" || x["part"] == "H1"))
        .count();
    assert!(listed >= 2, "{json}");
}

#[test]
fn a_clean_scan_of_heads_and_a_cone_reports_no_dents() {
    let env = envelope(CONED);
    let i = inspected(&env, scan(&env, "", 400.0, 22), 1.5);
    assert!(
        local(&i.checks.findings).is_empty(),
        "{:#?}",
        i.checks.findings
    );
}

#[test]
fn a_fit_told_less_noise_than_the_scan_has_finds_no_dents() {
    // The scan's noise is 1.5 mm; told 0.75 mm the net grows to its floor and
    // follows the noise.
    for (design, seed) in [(DRUM, 12), (CONED, 23)] {
        let env = envelope(design);
        let i = inspected(&env, scan(&env, "", 400.0, seed), 0.75);
        assert!(
            local(&i.checks.findings).is_empty(),
            "{}: {:#?}",
            env.tag,
            i.checks.findings
        );
    }
}

#[test]
fn a_dent_across_a_heads_knuckle_and_crown_is_one_dent() {
    let env = envelope(TORI_ECCENTRIC);
    // H1 (crown 1600, knuckle 200, flange 50): knuckle and crown meet 164.2 mm
    // above the tangent line, at radius 914.3: EL −214.2. A 300 mm dent there
    // lies half on the knuckle, half on the crown.
    let points = scan(&env, "dent=20mm@EL-214/60°/300mm", 600.0, 31);
    let i = inspected(&env, points, 1.5);
    let dents: Vec<&Finding> = local(&i.checks.findings)
        .into_iter()
        .filter(|f| f.part == "H1")
        .collect();
    assert_eq!(dents.len(), 1, "{dents:#?}");
    let head = dents[0];
    assert_eq!(head.kind, "dent", "{head:?}");
    assert!((head.size - 20.0).abs() <= 2.0, "{head:?}");
    assert!((head.elevation + 214.0).abs() <= 100.0, "{head:?}");
    assert!(arc(914.0, head.orientation, 60.0) <= 100.0, "{head:?}");
    // The merged extent spans both patches' parts of the dent (each alone is
    // under 300 mm along the meridian).
    assert!(
        head.extent.is_some_and(|e| e > 250.0 && e < 700.0),
        "{head:?}"
    );
}

#[test]
fn a_dent_on_an_eccentric_cone_is_found_in_depth_and_place() {
    let env = envelope(TORI_ECCENTRIC);
    // R1 runs from EL3000 (D 2000) to EL3900 (D 1400), flat side at 90°: at
    // EL3450 its section (radius 850) is centred 150 mm towards 90°, so at
    // 270°, on the steep side, it lies 700 mm from the vessel's axis.
    let points = scan(&env, "dent=20mm@EL3450/270°/500mm", 600.0, 32);
    let i = inspected(&env, points, 1.5);
    let f = &i.checks.findings;
    let cone = dent(f, "R1");
    assert!((cone.size - 20.0).abs() <= 2.0, "{cone:?}");
    assert!((cone.elevation - 3450.0).abs() <= 100.0, "{cone:?}");
    assert!(arc(850.0, cone.orientation, 270.0) <= 100.0, "{cone:?}");
    assert!(
        cone.extent.is_some_and(|e| e > 200.0 && e < 900.0),
        "{cone:?}"
    );
    // Nothing else on the vessel, the cone's other side included.
    let others: Vec<&Finding> = local(f)
        .into_iter()
        .filter(|x| !std::ptr::eq(*x, cone))
        .collect();
    assert!(others.is_empty(), "{others:#?}");
    // The courses stand on axes 300 mm apart by design: the vessel is plumb.
    assert!(
        i.checks.plumbness.is_some_and(|p| p < 0.0005),
        "{:?}",
        i.checks.plumbness
    );
}
