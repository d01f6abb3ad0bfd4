//! Registration of a tank: a body of revolution whose turn only two nozzles
//! fix, whose heads (a fifth of the points) alone fix its elevation. Seed 15
//! used to register 127° (plumb) and 137° (settled) wrong, and 140–196 mm low.

mod common;

use common::scan::{TANK, envelope};
use glam::DVec3;
use vesselcad::scan::defects::parse_defects;
use vesselcad::scan::register::{RegisterOptions, register};
use vesselcad::scan::simulate::{SimulateOptions, SiteTransform, simulate};

/// Yaw error (degrees) and shift error (mm, at the point `at` of the plant)
/// of registering `defects` drawn with `seed` from its site frame.
fn registered(defects: &str, density: f64, seed: u64, at: DVec3) -> (f64, f64) {
    let env = envelope(TANK);
    let site = SiteTransform::from_seed(seed);
    let points = simulate(
        &env,
        &SimulateOptions {
            density,
            noise: 1.5,
            occlusion: 0.2,
            seed,
            site: Some(site),
            defects: parse_defects(defects, &env).unwrap(),
        },
    )
    .unwrap()
    .points;
    let r = register(&env, &points, &RegisterOptions::DEFAULT).unwrap();
    // site → plant after plant → site is the identity.
    let back = env.frame * r.to_vessel * site.affine();
    let x = back.matrix3 * DVec3::X;
    let yaw = x.y.atan2(x.x).to_degrees();
    let shift = (back.transform_point3(at) - at).length();
    eprintln!(
        "{defects} seed {seed}: yaw error {yaw:.4}°, shift {shift:.3} mm, rms {:.2}, kept {} of {}",
        r.rms, r.kept, r.used
    );
    (yaw, shift)
}

#[test]
fn a_settled_tank_registers_from_its_site_frame() {
    // The settlement turns the tank 0.57° about a level axis through its
    // bottom centre (30 mm down at 200°): no levelled motion fits that, and
    // the tilt itself carries nozzle N1 (EL 5200, 30°) some 9 mm sideways, so
    // the turn about plant up is good to a few tenths of a degree (0.32° at
    // seed 15), no better; it used to be 137° off, the tank 140 mm low.
    for seed in [15, 14] {
        let (yaw, _) = registered(
            "settlement=cosine:30mm@200°,sag=25mm@45°/3000mm",
            1000.0,
            seed,
            DVec3::ZERO,
        );
        assert!(yaw.abs() <= 0.5, "seed {seed}: yaw error {yaw}°");
    }
}

#[test]
fn a_plumb_tank_registers_to_the_tolerance() {
    // Seed 15 used to register 196 mm low and 127° wrong: the start (centroids)
    // was that far off vertically, and the ICP, trimmed to its robust sigma
    // from the first iteration, had dropped the roof for good.
    for seed in [15, 3] {
        let (yaw, shift) = registered("", 200.0, seed, DVec3::new(0.0, 0.0, 3000.0));
        assert!(yaw.abs() <= 0.05, "seed {seed}: yaw error {yaw}°");
        assert!(shift <= 1.0, "seed {seed}: shift error {shift} mm");
    }
}
