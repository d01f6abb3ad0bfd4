//! Scans against their design end to end: registration recovers the site pose,
//! a scan without defects reports nothing, and each injected defect is found
//! within 10 % of its size and 100 mm of its place.

mod common;

use common::scan::{DRUM, TANK, envelope};
use glam::DVec3;
use vesselcad::scan::checks::Finding;
use vesselcad::scan::defects::parse_defects;
use vesselcad::scan::inspect::{InspectOptions, Inspection, inspect};
use vesselcad::scan::register::{RegisterOptions, register};
use vesselcad::scan::simulate::{SimulateOptions, SiteTransform, simulate};
use vesselcad::scan::{Envelope, fit::FitOptions};

fn scan(env: &Envelope, defects: &str, density: f64, seed: u64) -> (Vec<DVec3>, SiteTransform) {
    let site = SiteTransform::from_seed(seed);
    let s = simulate(
        env,
        &SimulateOptions {
            density,
            noise: 1.5,
            occlusion: 0.2,
            seed,
            site: Some(site),
            defects: parse_defects(defects, env).unwrap(),
        },
    )
    .unwrap();
    (s.points, site)
}

fn inspected(env: &Envelope, points: Vec<DVec3>) -> Inspection {
    let options = InspectOptions {
        fit: FitOptions {
            noise: 1.5,
            ..FitOptions::DEFAULT
        },
        ..InspectOptions::DEFAULT
    };
    inspect(env, points, &options).unwrap()
}

/// Angle (degrees) of the turn of a rigid motion.
fn turn_degrees(m: glam::DMat3) -> f64 {
    (((m.x_axis.x + m.y_axis.y + m.z_axis.z) - 1.0) / 2.0)
        .clamp(-1.0, 1.0)
        .acos()
        .to_degrees()
}

#[test]
fn registration_recovers_the_site_pose() {
    let env = envelope(DRUM);
    let (points, site) = scan(&env, "", 150.0, 11);
    let r = register(&env, &points, &RegisterOptions::DEFAULT).unwrap();
    // site → plant after plant → site is the identity.
    let back = env.frame * r.to_vessel * site.affine();
    let angle = turn_degrees(back.matrix3);
    assert!(angle <= 0.05, "turn error {angle}°");
    let centre = env.frame.transform_point3(DVec3::new(0.0, 0.0, 3000.0));
    let shift = (back.transform_point3(centre) - centre).length();
    assert!(shift <= 1.0, "shift error {shift} mm");
    assert!(r.rms < 2.5, "{}", r.rms);
}

#[test]
fn a_scan_without_defects_reports_nothing() {
    let env = envelope(DRUM);
    let (points, _) = scan(&env, "", 150.0, 12);
    let i = inspected(&env, points);
    assert!(i.checks.findings.is_empty(), "{:#?}", i.checks.findings);
    let v = i.volume;
    assert!((v.as_built / v.design - 1.0).abs() < 2e-3, "{v:?}");
}

/// The largest finding of a kind on a part.
fn find<'a>(findings: &'a [Finding], kind: &str, part: &str) -> &'a Finding {
    findings
        .iter()
        .filter(|f| f.kind == kind && f.part == part)
        .max_by(|a, b| a.size.total_cmp(&b.size))
        .unwrap_or_else(|| panic!("no {kind} on {part}: {findings:#?}"))
}

/// Distance along a course of radius `r` between two orientations, mm.
fn arc(r: f64, a: f64, b: f64) -> f64 {
    let d = (a - b).rem_euclid(360.0);
    r * d.min(360.0 - d).to_radians()
}

#[test]
fn each_injected_defect_is_found_in_size_and_place() {
    let env = envelope(DRUM);
    let (points, _) = scan(
        &env,
        "ovality=0.8%@course:S1/0,dent=25mm@EL4500/90°,peaking=8mm@seam:S2/200°,tilt=0.3°/45°",
        400.0,
        13,
    );
    let i = inspected(&env, points);
    let f = &i.checks.findings;
    let ovality = find(f, "out_of_roundness", "S1");
    assert!((ovality.size - 0.8).abs() <= 0.08, "{ovality:?}");
    let dent = find(f, "dent", "S2");
    assert!((dent.size - 25.0).abs() <= 2.5, "{dent:?}");
    assert!((dent.elevation - 4500.0).abs() <= 100.0, "{dent:?}");
    assert!(arc(1000.0, dent.orientation, 90.0) <= 100.0, "{dent:?}");
    let peaking = find(f, "peaking", "S2");
    // Within 10 %: the board reads the points, not the fit (which rounds the
    // crest within the noise and read 6.7 mm).
    assert!((peaking.size - 8.0).abs() <= 0.8, "{peaking:?}");
    assert!(
        arc(1000.0, peaking.orientation, 200.0) <= 100.0,
        "{peaking:?}"
    );
    let plumb = find(f, "plumbness", "V-1");
    let tilt = 0.3f64.to_radians().tan();
    assert!((plumb.size - tilt).abs() <= 0.1 * tilt, "{plumb:?}");
    assert!(plumb.exceeds);
    assert!((plumb.orientation - 45.0).abs() <= 5.0, "{plumb:?}");
    assert!(!ovality.exceeds && !dent.exceeds);
    // Nothing else of a defect's size: smaller local readings remain near the
    // course ends and around the dent (see the commit notes).
    let others: Vec<&Finding> = f
        .iter()
        .filter(|x| x.unit == "mm" && x.size > 10.0 && !std::ptr::eq(*x, dent))
        .collect();
    assert!(others.is_empty(), "{others:#?}");
}

/// Scan density of the settlement tests, points/m². A cosine's lowest point is
/// where it is flattest: with 8 stations read to u, its orientation is good to
/// u / (A·√4) radians. At 200 points/m² (1.5 mm noise, 20 % of 1 m cells
/// hidden) the stations are read to about 3 mm and the lowest point of a 40 mm
/// settlement to 95–140 mm of arc RMS on this 6 m tank (27–41 % of seeds past
/// 100 mm, by a simulation of the bottom edge alone); at 1000 points/m²,
/// still sparse for a laser scanner, to about 40 mm.
const SETTLEMENT_DENSITY: f64 = 1000.0;

#[test]
fn tank_settlement_is_fitted_by_a_cosine() {
    let env = envelope(TANK);
    let (points, _) = scan(&env, "settlement=cosine:40mm@120°", SETTLEMENT_DENSITY, 14);
    let i = inspected(&env, points);
    let s = i
        .checks
        .settlement
        .as_ref()
        .expect("a tank has a settlement fit");
    assert!((s.amplitude - 40.0).abs() <= 4.0, "{s:?}");
    assert!(arc(3000.0, s.lowest, 120.0) <= 100.0, "{s:?}");
    assert!(s.r_squared > 0.9 && s.cosine_valid, "{s:?}");
    find(&i.checks.findings, "settlement", "TK-1");
    // API 653 12.5.1.2: stations at most 32 ft (9754 mm) apart, at least 8.
    assert_eq!(s.stations.len(), 8, "{s:?}");
    // B.3.2.1 for SA-283-C (Y 205 MPa, E 200 000 MPa), L = π·6000/8, H = 6000:
    // S_max = 11·L²·Y / (2·E·H) = 5.22 mm.
    let l = std::f64::consts::PI * 6000.0 / 8.0;
    let expected = 11.0 * l * l * 205.0 / (2.0 * 200_000.0 * 6000.0);
    let allowable = s.allowable.expect("the tank's material is in the table");
    assert!(
        (allowable - expected).abs() < 1e-9,
        "{allowable} vs {expected}"
    );
    assert!((expected - 5.22).abs() < 0.01, "{expected}");
    // A planar tilt leaves no out-of-plane settlement past the stations'
    // uncertainty (at 1000 points/m² a station's edge is good to about 1 mm).
    assert!(s.uncertainty < 4.0, "{s:?}");
    assert!(s.out_of_plane < 3.0 * s.uncertainty, "{s:?}");
    assert!(
        !i.checks
            .findings
            .iter()
            .any(|f| f.kind == "out_of_plane_settlement"),
        "{:#?}",
        i.checks.findings
    );
}

#[test]
fn out_of_plane_settlement_past_the_api_653_allowable_is_flagged() {
    // A local sag of the shell's bottom edge at a station (45°: the stations
    // are every 45° from 0) pulls it down out of the cosine's plane.
    // Registered from its site frame: this scan (seed 15) used to register
    // 140 mm low and 132–137° wrong about the axis (tests/scan_register).
    let env = envelope(TANK);
    let station = 45.0;
    let points = simulate(
        &env,
        &SimulateOptions {
            density: SETTLEMENT_DENSITY,
            noise: 1.5,
            occlusion: 0.2,
            seed: 15,
            site: Some(SiteTransform::from_seed(15)),
            defects: parse_defects(
                &format!("settlement=cosine:30mm@200°,sag=25mm@{station}°/3000mm"),
                &env,
            )
            .unwrap(),
        },
    )
    .unwrap()
    .points;
    let i = inspected(&env, points);
    let s = i.checks.settlement.as_ref().expect("a settlement fit");
    let f = find(&i.checks.findings, "out_of_plane_settlement", "TK-1");
    assert!(f.exceeds, "{f:?}");
    assert_eq!(f.limit, s.allowable);
    assert!(arc(3000.0, f.orientation, station) <= 100.0, "{f:?}\n{s:?}");
}

/// Root mean square of the errors of edges read by `edge_by_likelihood` from
/// `count` points (uniform above an edge at 0, 1.5 mm noise) and of the
/// uncertainty `station_uncertainty` gives them, over `trials` draws.
fn edge_errors(count: usize, trials: usize) -> (f64, f64) {
    use vesselcad::scan::Random;
    use vesselcad::scan::settlement::{EDGE_WINDOW, edge_by_likelihood, station_uncertainty};
    let sigma = 1.5;
    let mut random = Random::new(count as u64);
    let (mut errors, mut uncertainties) = (0.0, 0.0);
    for _ in 0..trials {
        // Points up to 1.5 windows above the edge, `count` of them in one.
        let mut z: Vec<f64> = (0..count * 3 / 2)
            .map(|_| 1.5 * EDGE_WINDOW * random.uniform() + sigma * random.normal())
            .collect();
        z.sort_by(f64::total_cmp);
        let guess = z[0] - (z[7] - z[0]) / 7.0;
        let edge = edge_by_likelihood(&z, guess, sigma);
        let n = z
            .iter()
            .filter(|&&v| v >= edge && v < edge + EDGE_WINDOW)
            .count();
        errors += edge * edge;
        uncertainties += station_uncertainty(n, sigma).powi(2);
    }
    (
        (errors / trials as f64).sqrt(),
        (uncertainties / trials as f64).sqrt(),
    )
}

#[test]
fn a_stations_uncertainty_is_the_spread_of_its_edge() {
    // Sparse (the gap between points rules) and dense (the noise rules): the
    // error was twice the stated uncertainty at 400 points when it left the
    // noise over √n.
    for (count, trials) in [(40, 300), (400, 150)] {
        let (error, uncertainty) = edge_errors(count, trials);
        let ratio = error / uncertainty;
        assert!(
            (0.75..1.33).contains(&ratio),
            "{count} points: RMS error {error:.3} mm, uncertainty {uncertainty:.3} mm"
        );
    }
}
