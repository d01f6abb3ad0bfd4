//! Metal of the pressure envelope: volume and axial first moment of the walls,
//! as the wall thickness times the area of the wall's mid-surface (Pappus: exact
//! for courses and cones, within O(t³/R²) for spheres and tori).
//!
//! Third step of the operating figures, beside [`super::liquid`]; reads the
//! mid-surface profile from [`super::profile`]. Nozzles, supports and internals
//! are not weighed.

use std::f64::consts::TAU;
use std::sync::OnceLock;

use super::liquid::Moments;
use super::profile::Profile;
use crate::nurbs::GaussLegendre;

/// Gauss–Legendre order per piece.
const ORDER: usize = 24;

/// Volume (mm³), axial and lateral first moments (mm⁴) of the walls whose mid-surface is
/// `profile` (each piece carrying its wall thickness).
pub fn walls(profile: &Profile) -> Moments {
    static RULE: OnceLock<GaussLegendre> = OnceLock::new();
    let rule = RULE.get_or_init(|| GaussLegendre::new(ORDER));
    let mut total = Moments::default();
    for (k, (piece, thickness)) in profile.pieces.iter().enumerate() {
        if *thickness <= 0.0 {
            continue;
        }
        let centre = profile.centre(k);
        let (s0, s1) = piece.range();
        for (s, w) in rule.points_on(s0, s1) {
            let (r, z) = piece.point(s);
            let (dr, dz) = piece.derivative(s);
            let dv = TAU * r * dr.hypot(dz) * thickness * w;
            total.volume += dv;
            total.axial += dv * z;
            total.lateral += dv * centre.at(z);
        }
    }
    total
}
