//! Octahedral unit normals in two snorm16 ([`OctNormal`]), and the rounding
//! packing uses for them and for fixed-point offsets.

use glam::{DVec2, DVec3};

/// Largest value of a signed-normalised 16-bit component.
const SNORM16: f64 = i16::MAX as f64;

/// A unit vector in octahedral encoding: its projection on the octahedron
/// `|x| + |y| + |z| = 1`, the lower half folded over the upper, as two snorm16.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub struct OctNormal(pub [i16; 2]);

impl OctNormal {
    /// What a zero or non-finite vector encodes as (never a unit vector's
    /// code: components are clamped to ±32767); it decodes as NaN, so the
    /// exporters' checks still see it.
    pub const INVALID: Self = Self([i16::MIN, i16::MIN]);

    /// Encodes a unit vector (a zero or non-finite one as [`OctNormal::INVALID`]).
    pub fn encode(n: DVec3) -> Self {
        let l1 = n.x.abs() + n.y.abs() + n.z.abs();
        if !(l1.is_finite() && l1 > 0.0) {
            return Self::INVALID;
        }
        let mut p = DVec2::new(n.x, n.y) / l1;
        if n.z < 0.0 {
            p = (DVec2::ONE - DVec2::new(p.y.abs(), p.x.abs())) * sign(p);
        }
        let q = |x: f64| round_small(x.clamp(-1.0, 1.0) * SNORM16) as i16;
        Self([q(p.x), q(p.y)])
    }

    /// The unit vector it encodes (NaN for [`OctNormal::INVALID`]).
    pub fn decode(self) -> DVec3 {
        if self == Self::INVALID {
            return DVec3::NAN;
        }
        let mut p = DVec2::new(f64::from(self.0[0]), f64::from(self.0[1])) / SNORM16;
        let z = 1.0 - p.x.abs() - p.y.abs();
        if z < 0.0 {
            p = (DVec2::ONE - DVec2::new(p.y.abs(), p.x.abs())) * sign(p);
        }
        DVec3::new(p.x, p.y, z).normalize()
    }
}

/// `x.round()` (half away from zero) for |x| < 2⁶², as packing's offsets and
/// normal components are: the truncation is the hardware's conversion to an
/// integer, where `f64::round` is a library call on CPUs without SSE4.1 — and
/// packing rounds five numbers per vertex. The difference `x − trunc(x)` is
/// exact, so the result is `round`'s value (a zero may lose its sign, which the
/// integer conversion after it drops anyway; tested).
#[inline]
pub(super) fn round_small(x: f64) -> f64 {
    let t = x as i64 as f64;
    let d = x - t;
    // Without branches: which way a coordinate rounds is a coin toss, and
    // mispredicted branches cost more than the library call saved.
    t + f64::from(u8::from(d >= 0.5)) - f64::from(u8::from(d <= -0.5))
}

/// Component-wise sign, with +1 for zero (so the fold is defined on the axes).
fn sign(p: DVec2) -> DVec2 {
    DVec2::new(
        if p.x >= 0.0 { 1.0 } else { -1.0 },
        if p.y >= 0.0 { 1.0 } else { -1.0 },
    )
}
