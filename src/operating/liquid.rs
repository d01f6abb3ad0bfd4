//! Liquid in a vessel: the exact volume of its interior below a level, and the
//! first moments of that volume (for the centre of gravity).
//!
//! Second step of the operating figures, after [`super::profile`]. A vertical
//! vessel's cross-section at height z is a disk of the profile's radius r(z), so
//! V(h) = ∫ π r² dz up to h. A horizontal vessel's cross-section at axial position
//! z is a disk of radius r(z) cut by the liquid surface at height y above the axis:
//! a circular segment of area A(r, y) = r² acos(−y/r) + y √(r² − y²), so
//! V(y) = ∫ A(r(z), y) dz. Each profile piece is a line or a conic arc, smooth and
//! monotone; its integral is Gauss–Legendre quadrature in the piece's own
//! parameter (trigonometric polynomials for arcs: exact to rounding). Where a
//! disk's edge crosses the liquid surface (r = |y|) the integrand has a
//! (r − |y|)^{3/2} corner: the piece is split there and the variable changed to
//! s = s_c ± w², which makes the integrand smooth again. The result is exact to
//! about 1e-12 relative (tests compare with closed forms).

use std::f64::consts::PI;
use std::sync::OnceLock;

use glam::DVec2;

use super::profile::{Piece, Profile};
use crate::nurbs::GaussLegendre;

/// Gauss–Legendre order per integration interval.
const ORDER: usize = 40;

/// The shared quadrature rule.
fn rule() -> &'static GaussLegendre {
    static RULE: OnceLock<GaussLegendre> = OnceLock::new();
    RULE.get_or_init(|| GaussLegendre::new(ORDER))
}

/// Volume and first moments of a body, mm³ and mm⁴.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Moments {
    /// Volume, mm³.
    pub volume: f64,
    /// ∫ z dV: axial first moment, mm⁴.
    pub axial: f64,
    /// ∫ y dV: first moment above the axis (horizontal vessels), mm⁴.
    pub vertical: f64,
    /// ∫ (x, y) dV of the cross-sections' centres in the vessel frame (vertical
    /// vessels with parts off the axis, above an eccentric reducer), mm⁴.
    pub lateral: DVec2,
}

impl Moments {
    fn add(&mut self, other: Moments, sign: f64) {
        self.volume += sign * other.volume;
        self.axial += sign * other.axial;
        self.vertical += sign * other.vertical;
        self.lateral += sign * other.lateral;
    }
}

/// Liquid below axial position `h` in a vertical vessel whose inside is `profile`.
pub fn vertical(profile: &Profile, h: f64) -> Moments {
    let mut total = Moments::default();
    for (k, (piece, _)) in profile.pieces.iter().enumerate() {
        let (s0, s1) = piece.range();
        let (z0, z1) = (piece.point(s0).1, piece.point(s1).1);
        if z0 == z1 {
            continue;
        }
        let centre = profile.centre(k);
        // The part of the piece below h.
        let sh = piece.at_z(h);
        let (a, b) = if z1 > z0 { (s0, sh) } else { (sh, s1) };
        if a == b {
            continue;
        }
        let mut moments = Moments::default();
        for (s, w) in rule().points_on(a, b) {
            let (r, z) = piece.point(s);
            let dz = piece.derivative(s).1;
            let area = PI * r * r * dz * w;
            moments.volume += area;
            moments.axial += area * z;
            moments.lateral += area * centre.at(z);
        }
        total.add(moments, (z1 - z0).signum());
    }
    total
}

/// Liquid below height `y` above the axis in a horizontal vessel whose inside is
/// `profile`.
pub fn horizontal(profile: &Profile, y: f64) -> Moments {
    let mut total = Moments::default();
    for (piece, _) in &profile.pieces {
        let (s0, s1) = piece.range();
        let (z0, z1) = (piece.point(s0).1, piece.point(s1).1);
        if z0 == z1 {
            continue;
        }
        let sign = (z1 - z0).signum();
        let (r0, r1) = (piece.point(s0).0, piece.point(s1).0);
        let level = y.abs();
        if (r0 - level) * (r1 - level) < 0.0 {
            // The disk edge crosses the surface inside the piece: split there.
            let sc = piece.at_r(level);
            total.add(segment(piece, y, s0, sc, End::High), sign);
            total.add(segment(piece, y, sc, s1, End::Low), sign);
        } else {
            total.add(segment(piece, y, s0, s1, End::None), sign);
        }
    }
    total
}

/// Which end of an interval has the (r − |y|)^{3/2} corner.
#[derive(Clone, Copy, PartialEq, Eq)]
enum End {
    None,
    Low,
    High,
}

/// ∫ (A, A z, M) z' ds over [a, b] of a piece, with the change of variable
/// s = corner ± (b − a) w² towards a corner end.
fn segment(piece: &Piece, y: f64, a: f64, b: f64, corner: End) -> Moments {
    let mut m = Moments::default();
    if a == b {
        return m;
    }
    let mut add = |s: f64, weight: f64| {
        let (r, z) = piece.point(s);
        let dz = piece.derivative(s).1;
        let (area, moment) = circular_segment(r, y);
        let f = dz * weight;
        m.volume += area * f;
        m.axial += area * z * f;
        m.vertical += moment * f;
    };
    match corner {
        End::None => {
            for (s, w) in rule().points_on(a, b) {
                add(s, w);
            }
        }
        End::Low => {
            for (t, w) in rule().points_on(0.0, 1.0) {
                add(a + (b - a) * t * t, w * 2.0 * (b - a) * t);
            }
        }
        End::High => {
            for (t, w) in rule().points_on(0.0, 1.0) {
                add(b - (b - a) * t * t, w * 2.0 * (b - a) * t);
            }
        }
    }
    m
}

/// Area (mm²) of the part of a disk of radius `r` below the line at height `y`
/// above its centre, and its first moment about the centre's horizontal (mm³).
pub fn circular_segment(r: f64, y: f64) -> (f64, f64) {
    if y <= -r {
        return (0.0, 0.0);
    }
    if y >= r {
        return (PI * r * r, 0.0);
    }
    let root = (r * r - y * y).max(0.0).sqrt();
    let area = r * r * (-y / r).clamp(-1.0, 1.0).acos() + y * root;
    (area, -2.0 / 3.0 * root * root * root)
}
