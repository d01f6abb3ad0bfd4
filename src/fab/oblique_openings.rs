//! Openings on eccentric reducers, developed by the oblique cone's own
//! development ([`super::oblique`]).
//!
//! A point of an oblique cone is named by `(φ, z)`: φ the angle about the
//! centre of its circle at height `z` (points of equal φ lie on one
//! generator), as the cut's loops are sampled
//! ([`super::cone_openings::ConeSurface::crossing`] on the leaning cone).
//! [`develop_loop`] lays such a loop on a plate by [`ObliquePlate::develop`]
//! (apex at the origin, the plate's bisector along +y), so an opening lands
//! on its plate exactly where the plate's outline puts the cone's surface;
//! [`develop_about`] lays a pad on its own oblique mid-surface, centred on
//! the nozzle axis with the generator through it along +y, for nesting and
//! its template. The development is an isometry: the developed loops are the
//! exact curves unrolled.

use std::f64::consts::{FRAC_PI_2, PI, TAU};

use glam::DVec2;

use super::oblique::{ObliqueCone, ObliquePlate};

/// The loop `points` about `centre` (surface coordinates `(φ, z)`, φ
/// continuous about the centre's) developed onto `plate`: the centre's φ is
/// moved by whole turns to the plate's first turn from its first
/// generator, each point's to within π of it. Returns the developed centre
/// and loop.
pub fn develop_loop(plate: &ObliquePlate, centre: DVec2, points: &[DVec2]) -> (DVec2, Vec<DVec2>) {
    let phi = plate.from + (centre.x - plate.from).rem_euclid(TAU);
    let at = |p: DVec2| {
        let t = phi + (p.x - centre.x + PI).rem_euclid(TAU) - PI;
        plate.develop(t, p.y)
    };
    (at(centre), points.iter().map(|&p| at(p)).collect())
}

/// The loop `points` about `centre` developed on `cone` (a whole turn cut
/// open opposite the centre), moved so that the centre is at the origin and
/// the generator through it runs along +y (away from the apex). Returns the
/// developed apex and loop.
pub fn develop_about(cone: &ObliqueCone, centre: DVec2, points: &[DVec2]) -> (DVec2, Vec<DVec2>) {
    let plate = ObliquePlate {
        cone: *cone,
        from: centre.x - PI,
        angle: TAU,
        z: (0.0, cone.length),
    };
    let (c, developed) = develop_loop(&plate, centre, points);
    let turn = DVec2::from_angle(FRAC_PI_2 - c.y.atan2(c.x));
    let apex = turn.rotate(-c);
    (
        apex,
        developed.iter().map(|&p| turn.rotate(p - c)).collect(),
    )
}
