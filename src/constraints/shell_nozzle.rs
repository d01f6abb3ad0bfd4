//! Non-radial nozzles on cylindrical shell courses: hillside (offset), tangential
//! and inclined nozzles.
//!
//! A shell nozzle's axis is parallel to its orientation direction `n` (the
//! radial direction of the orientation angle), moved `offset` mm sideways along
//! the course's tangent `a` at that angle (towards larger orientation angles) and
//! turned `inclination` degrees towards the vessel's +Z (up on a vertical
//! vessel, towards the right end on a horizontal one): its direction is
//! `d = cos i · n + sin i · Z` and it passes through `axis(elevation) + offset · a`,
//! where its projection is measured from. A radial nozzle is the case
//! offset = inclination = 0. This is how COMPRESS and PV Elite describe them:
//! a hillside nozzle by its offset from the radial plane (tangential when the
//! offset brings the neck's outer wall to the shell's surface), an inclined
//! (lateral) one by its angle.
//!
//! The opening on the course is where the neck (or pad) cylinder of radius ρ
//! meets the course's cylinder of radius R, worked out here in closed form along
//! each of the neck's generators (a quadratic), so that the rules see the
//! opening's true shape: its axial extent must lie within the course, the flange
//! face must be clear of its farthest point, and the ball holding it (for the
//! overlap checks of `footprints`) is measured from it. The geometry is built and
//! tested for |inclination| ≤ [`MAX_INCLINATION`] and for openings whose outer
//! edge stays within [`MAX_HILLSIDE`] of the course radius from the radial
//! plane (the neck then still crosses the course at 11° or more; a truly
//! tangential neck, flush with the surface, would touch it along a line and
//! leave no cut).

use glam::{DAffine3, DMat3, DVec3};

/// Largest inclination of a shell nozzle's axis from the course's cross-section
/// plane, degrees.
pub const MAX_INCLINATION: f64 = 45.0;

/// Largest distance of a shell nozzle opening's outer edge (|offset| plus half
/// the neck or pad OD) from the radial plane, as a fraction of the course's
/// outside radius.
pub const MAX_HILLSIDE: f64 = 0.98;

/// Generators of the neck (or pad) cylinder along which the opening is worked
/// out.
const SAMPLES: usize = 720;

/// Where a non-radial nozzle stands on its course and what its opening covers.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Placement {
    /// Nozzle frame → vessel frame: +Z along the nozzle axis, origin where the
    /// projection is measured from.
    pub frame: DAffine3,
    /// Where the nozzle axis meets the course's surface, vessel frame.
    pub centre: DVec3,
    /// Radius of a ball about `centre` holding the whole opening, mm.
    pub radius: f64,
    /// Lowest and highest axial coordinate of the opening, vessel frame, mm.
    pub axial: (f64, f64),
    /// Farthest point of the opening along the nozzle axis from the origin, mm.
    pub depth: f64,
}

/// A nozzle on a cylindrical course of outside radius `radius` whose axis is
/// `axis_point` + t Z: orientation direction `n` (unit, across the axis),
/// sideways tangent `a` (unit, across the axis and ⟂ `n`), `offset` mm and
/// `inclination` degrees, with an opening (neck or pad) of radius `rho`.
/// `None` when the opening does not lie wholly on the course's face (|offset| +
/// ρ ≥ R: the rules refuse that first).
pub(crate) fn place(
    axis_point: DVec3,
    radius: f64,
    n: DVec3,
    a: DVec3,
    offset: f64,
    inclination: f64,
    rho: f64,
) -> Option<Placement> {
    if offset.abs() + rho >= radius {
        return None;
    }
    let (sin, cos) = inclination.to_radians().sin_cos();
    let d = n * cos + DVec3::Z * sin;
    let origin = axis_point + a * offset;
    let b = d.cross(a);
    // The nozzle frame's +X is the vessel's +Z made orthogonal to the axis, as
    // a radial nozzle's is (never parallel: |i| < 90°).
    let x = (DVec3::Z - d * d.z).normalize();
    let frame = DAffine3::from_mat3_translation(DMat3::from_cols(x, d.cross(x), d), origin);
    // Along the generator at q (relative to the axis point) + t d, the
    // distance from the course axis is R where
    // cos²i t² + 2 (q·n cos i) t + |q_h|² − R² = 0 (q_h: q across the axis).
    let meet = |q: DVec3| -> Option<f64> {
        let qh = q - DVec3::Z * q.z;
        let half_b = qh.dot(n) * cos;
        let c = qh.length_squared() - radius * radius;
        let disc = half_b * half_b - cos * cos * c;
        (disc >= 0.0 && cos > 0.0).then(|| (-half_b + disc.sqrt()) / (cos * cos))
    };
    let centre_t = meet(origin - axis_point)?;
    let centre = origin + d * centre_t;
    let mut points = Vec::with_capacity(SAMPLES);
    for k in 0..SAMPLES {
        let phi = std::f64::consts::TAU * k as f64 / SAMPLES as f64;
        let (s, c) = phi.sin_cos();
        let q = origin - axis_point + (a * c + b * s) * rho;
        let t = meet(q)?;
        points.push((q + d * t + axis_point, t));
    }
    // Between two samples the opening stays within half their chord (with 1 %
    // for the arc's excess over its chord at this spacing) of one of them.
    let step = (0..SAMPLES)
        .map(|k| (points[k].0 - points[(k + 1) % SAMPLES].0).length())
        .fold(0.0, f64::max);
    let margin = 0.505 * step;
    let reach = points
        .iter()
        .map(|(p, _)| (*p - centre).length())
        .fold(0.0, f64::max);
    let (lo, hi) = points
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), (p, _)| {
            (lo.min(p.z), hi.max(p.z))
        });
    let depth = points.iter().map(|&(_, t)| t).fold(0.0, f64::max);
    Some(Placement {
        frame,
        centre,
        radius: reach + margin,
        axial: (lo - margin, hi + margin),
        depth: depth + margin,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A radial nozzle's opening is the classic saddle: its axial extent is ±ρ,
    /// its depth along the axis R, and every sampled point lies on both
    /// cylinders.
    #[test]
    fn a_radial_opening_has_the_classic_extent() {
        let p = place(
            DVec3::new(0.0, 0.0, 1000.0),
            1000.0,
            DVec3::X,
            DVec3::Y,
            0.0,
            0.0,
            100.0,
        )
        .unwrap();
        assert!((p.centre - DVec3::new(1000.0, 0.0, 1000.0)).length() < 1e-9);
        assert!((p.axial.0 - 900.0).abs() < 1.0 && (p.axial.1 - 1100.0).abs() < 1.0);
        assert!((p.depth - 1000.0).abs() < 1.0);
        assert!(p.radius >= 100.0 && p.radius < 110.0);
    }

    /// A hillside nozzle's axis is parallel to the radial direction, offset
    /// sideways; the opening is longer round the course than along it, and the
    /// centre lies on the course.
    #[test]
    fn a_hillside_opening_stretches_round_the_course() {
        let (r, e, rho) = (1000.0, 600.0, 100.0);
        let p = place(DVec3::ZERO, r, DVec3::X, DVec3::Y, e, 0.0, rho).unwrap();
        assert!((p.frame.translation - DVec3::new(0.0, e, 0.0)).length() < 1e-12);
        assert!((p.frame.matrix3 * DVec3::Z - DVec3::X).length() < 1e-12);
        assert!((p.centre.truncate().length() - r).abs() < 1e-9);
        // Round the course the opening spans the arc between y = e ± ρ.
        let x = |y: f64| (r * r - y * y).sqrt();
        let across =
            (DVec3::new(x(e + rho), e + rho, 0.0) - DVec3::new(x(e - rho), e - rho, 0.0)).length();
        assert!(p.radius >= across / 2.0);
        assert!((p.axial.0 + rho).abs() < 1.0 && (p.axial.1 - rho).abs() < 1.0);
    }

    /// An inclined nozzle's opening reaches ρ / cos i along the course.
    #[test]
    fn an_inclined_opening_stretches_along_the_course() {
        let p = place(DVec3::ZERO, 1000.0, DVec3::X, DVec3::Y, 0.0, 30.0, 100.0).unwrap();
        let axis = p.frame.matrix3 * DVec3::Z;
        assert!((axis.z - 0.5).abs() < 1e-12);
        assert!((p.centre.z - 1000.0 * 30f64.to_radians().tan()).abs() < 1e-9);
        let half = 100.0 / 30f64.to_radians().cos();
        assert!(p.axial.1 - p.axial.0 >= 2.0 * half - 1e-6);
    }

    #[test]
    fn an_opening_past_the_course_face_is_none() {
        assert!(place(DVec3::ZERO, 1000.0, DVec3::X, DVec3::Y, 950.0, 0.0, 50.0).is_none());
    }
}
