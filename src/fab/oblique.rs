//! The development of an eccentric reducer: an oblique circular cone.
//!
//! The mid-surface is taken as the oblique cone through the two end circles
//! of mid radius (`r = D/2 − t/2` in each end plane, the wall measured in the
//! end planes: the normal offset of an oblique cone is not a cone), the small
//! end's centre offset by `r₁ − r₂` towards the flat side, as the part
//! builder places it; along the flat side's generator the wall is measured
//! normally and the rule is exact. Points of equal angle φ on the two circles
//! lie on one generator through the apex `A = c·r₁/(r₁ − r₂)` (`c` the small
//! end's centre). A cone is developable: a generator keeps its length from
//! the apex, and the developed angle grows by `dψ = |(P − A) × P′| / |P −
//! A|² dφ` along the large end circle `P(φ)`. The point at height `z` of the
//! generator at φ is `A + s(z)·(P(φ) − A)`, `s(z) = 1 − z/z_A`, so the band
//! `z₀..z₁` between the generators at `φa` and `φb` develops to the region
//! between the curves `s(z₀)·ρ(φ)·(cos ψ, sin ψ)` and `s(z₁)·ρ(φ)·(cos ψ,
//! sin ψ)`, `ρ = |P − A|`, and its area is `½(s₀² − s₁²)·∫|(P − A) × P′|
//! dφ` — the cone's area, exactly. Both integrals are taken by 8-point
//! Gauss–Legendre rules on steps of at most 2π/256, to rounding (the
//! integrands are analytic).
//!
//! A developed plate ([`ObliquePlate`]) is laid like a concentric cone's
//! sector: the apex at the origin, the bisector of its developed angle along
//! +y. Its outline is a polygon whose vertices lie on the developed curves
//! and whose chords stay within [`OUTLINE_SAG`] of them; its generator edges
//! are straight, exactly. [`ObliquePlate::roll_back`] maps a developed point
//! back onto the cone.

use std::f64::consts::{FRAC_PI_2, TAU};

use glam::{DVec2, DVec3};

use crate::nurbs::GaussLegendre;

/// The largest distance between a developed outline's chord and the curve
/// it stands for, mm.
pub const OUTLINE_SAG: f64 = 0.01;

/// An oblique cone frustum between two parallel circles: the large end in
/// the plane z = 0 centred on the axis, the small end at z = `length`, its
/// centre offset by `large − small` towards `flat_side`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ObliqueCone {
    /// Radius of the large end, mm.
    pub large: f64,
    /// Radius of the small end, mm.
    pub small: f64,
    /// Axial length, mm.
    pub length: f64,
    /// Angle of the flat side about the axis, counter-clockwise from +x,
    /// radians.
    pub flat_side: f64,
}

/// Steps of φ per turn the integrals are taken on (each by an 8-point rule).
const STEPS: usize = 256;

/// `∫ₐᵇ f` on steps of at most 2π/[`STEPS`], 8 points each.
fn integrate(a: f64, b: f64, f: impl Fn(f64) -> f64) -> f64 {
    let rule = GaussLegendre::new(8);
    let n = (((b - a).abs() / (TAU / STEPS as f64)).ceil() as usize).max(1);
    let h = (b - a) / n as f64;
    (0..n)
        .map(|k| {
            let x = a + k as f64 * h;
            rule.integrate(x, x + h, &f)
        })
        .sum()
}

impl ObliqueCone {
    /// The mid-surface of an eccentric reducer of outside diameters `large`,
    /// `small`, `length` and flat side at `flat_side` degrees, `t` thick.
    pub fn mid_surface(large: f64, small: f64, length: f64, flat_side: f64, t: f64) -> Self {
        ObliqueCone {
            large: 0.5 * (large - t),
            small: 0.5 * (small - t),
            length,
            flat_side: flat_side.to_radians(),
        }
    }

    /// The oblique cone `d` mm outside this one, measured in the planes of
    /// its circles (its circles' centres stay where they are).
    pub fn offset(&self, d: f64) -> Self {
        ObliqueCone {
            large: self.large + d,
            small: self.small + d,
            ..*self
        }
    }

    /// The flat side's unit direction.
    fn flat(&self) -> DVec3 {
        DVec3::new(self.flat_side.cos(), self.flat_side.sin(), 0.0)
    }

    /// The apex.
    pub fn apex(&self) -> DVec3 {
        let d = self.large - self.small;
        let c = self.flat() * d + DVec3::Z * self.length;
        c * (self.large / d)
    }

    /// The fraction `s(z)` of the way from the apex at which height `z` lies.
    pub fn fraction(&self, z: f64) -> f64 {
        1.0 - z * (self.large - self.small) / (self.length * self.large)
    }

    /// The point at angle `phi` of the large end.
    fn base(&self, phi: f64) -> DVec3 {
        DVec3::new(self.large * phi.cos(), self.large * phi.sin(), 0.0)
    }

    /// The point of the cone at angle `phi` (about its circles' centres) and
    /// height `z`.
    pub fn point(&self, phi: f64, z: f64) -> DVec3 {
        let a = self.apex();
        a + (self.base(phi) - a) * self.fraction(z)
    }

    /// The centre of the circle at height `z`.
    pub fn centre(&self, z: f64) -> DVec3 {
        let a = self.apex();
        a - a * self.fraction(z)
    }

    /// `|P − A|` at `phi`: the large end's distance from the apex.
    fn reach(&self, phi: f64) -> f64 {
        (self.base(phi) - self.apex()).length()
    }

    /// `|(P − A) × P′|` at `phi`: twice the area swept per radian.
    fn sweep(&self, phi: f64) -> f64 {
        let p = self.base(phi) - self.apex();
        let dp = DVec3::new(-self.large * phi.sin(), self.large * phi.cos(), 0.0);
        p.cross(dp).length()
    }

    /// The developed angle's rate `dψ/dφ` at `phi`.
    fn turn(&self, phi: f64) -> f64 {
        let p = self.base(phi) - self.apex();
        self.sweep(phi) / p.length_squared()
    }

    /// The developed angle between the generators at `a` and `b`, radians.
    pub fn developed_angle(&self, a: f64, b: f64) -> f64 {
        integrate(a, b, |phi| self.turn(phi))
    }

    /// The developed angle of the whole cone, radians (less than 2π).
    pub fn angle(&self) -> f64 {
        self.developed_angle(self.flat_side, self.flat_side + TAU)
    }

    /// The exact area of the band `z0..z1` between the generators at `a` and
    /// `b`, mm².
    pub fn band_area(&self, a: f64, b: f64, z0: f64, z1: f64) -> f64 {
        let (s0, s1) = (self.fraction(z0), self.fraction(z1));
        0.5 * (s0 * s0 - s1 * s1).abs() * integrate(a, b, |phi| self.sweep(phi))
    }

    /// The exact area of the frustum (= the developed plate's), mm².
    pub fn area(&self) -> f64 {
        self.band_area(self.flat_side, self.flat_side + TAU, 0.0, self.length)
    }

    /// The length of the generator at `phi` between heights `z0` and `z1`, mm.
    pub fn generator(&self, phi: f64, z0: f64, z1: f64) -> f64 {
        (self.fraction(z0) - self.fraction(z1)).abs() * self.reach(phi)
    }

    /// The longest generator's length per unit of height (on the side
    /// opposite the flat one).
    pub fn slope(&self) -> f64 {
        (2.0 * (self.large - self.small) / self.length).hypot(1.0)
    }

    /// The whole cone developed as one plate, cut open along the flat side.
    pub fn whole(&self) -> ObliquePlate {
        ObliquePlate {
            cone: *self,
            from: self.flat_side,
            angle: TAU,
            z: (0.0, self.length),
        }
    }
}

/// A plate of an oblique cone: the band `z.0..z.1` between the generators at
/// `from` and `from + angle`, developed.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ObliquePlate {
    /// The cone.
    pub cone: ObliqueCone,
    /// The first generator's angle, radians.
    pub from: f64,
    /// The angle it spans about the cone's circles, radians.
    pub angle: f64,
    /// Its heights, mm.
    pub z: (f64, f64),
}

impl ObliquePlate {
    /// The exact area, mm².
    pub fn area(&self) -> f64 {
        self.cone
            .band_area(self.from, self.from + self.angle, self.z.0, self.z.1)
    }

    /// The developed angle, radians.
    pub fn developed_angle(&self) -> f64 {
        self.cone.developed_angle(self.from, self.from + self.angle)
    }

    /// The rotation that lays the plate's bisector along +y.
    fn lay(&self) -> f64 {
        FRAC_PI_2 - 0.5 * self.developed_angle()
    }

    /// The developed point of the cone's point at angle `phi` (within the
    /// plate) and height `z`.
    pub fn develop(&self, phi: f64, z: f64) -> DVec2 {
        let psi = self.cone.developed_angle(self.from, phi) + self.lay();
        DVec2::new(psi.cos(), psi.sin()) * (self.cone.fraction(z) * self.cone.reach(phi))
    }

    /// The cone's point (part-local) at developed point `q`: the inverse of
    /// [`develop`](Self::develop).
    pub fn roll_back(&self, q: DVec2) -> DVec3 {
        // The developed angle from the first generator, in [0, Ψ] (points
        // just outside by rounding are kept on their side).
        let total = self.developed_angle();
        let mut want = (q.y.atan2(q.x) - self.lay()).rem_euclid(TAU);
        if want > 0.5 * (total + TAU) {
            want -= TAU;
        }
        // ψ(φ) is increasing (dψ/dφ > 0): Newton from the linear guess,
        // ψ integrated from the plate's first generator each step.
        let mut phi = self.from + self.angle * (want / total);
        for _ in 0..50 {
            let f = self.cone.developed_angle(self.from, phi) - want;
            let step = f / self.cone.turn(phi);
            phi -= step;
            if step.abs() < 1e-15 {
                break;
            }
        }
        let a = self.cone.apex();
        a + (self.cone.base(phi) - a) * (q.length() / self.cone.reach(phi))
    }

    /// Points of the developed curve at height `z` from `from` to the end,
    /// spaced so that their chords stay within [`OUTLINE_SAG`] of the curve
    /// (the development is an isometry, so the curve's geodesic curvature is
    /// at most the circle's, 1/r, and a step of `dφ` sags at most `r·dφ²/8`).
    pub fn edge(&self, z: f64) -> Vec<DVec2> {
        let c = &self.cone;
        let r = c.fraction(z) * c.large;
        let step = (8.0 * OUTLINE_SAG / r).sqrt();
        let n = ((self.angle / step).ceil() as usize).max(2);
        let h = self.angle / n as f64;
        let lay = self.lay();
        let mut psi = lay;
        let mut out = Vec::with_capacity(n + 1);
        for k in 0..=n {
            let phi = self.from + k as f64 * h;
            if k > 0 {
                psi += c.developed_angle(phi - h, phi);
            }
            out.push(DVec2::new(psi.cos(), psi.sin()) * (c.fraction(z) * c.reach(phi)));
        }
        out
    }

    /// The closed outline: the edge at `z.0` from the first generator to the
    /// last, then the edge at `z.1` back.
    pub fn outline(&self) -> Vec<DVec2> {
        let mut out = self.edge(self.z.0);
        out.extend(self.edge(self.z.1).into_iter().rev());
        out
    }

    /// The bounding box of the laid outline, `(min, max)`, mm.
    pub fn bounds(&self) -> (DVec2, DVec2) {
        self.outline().iter().fold(
            (DVec2::splat(f64::INFINITY), DVec2::splat(f64::NEG_INFINITY)),
            |(lo, hi), p| (lo.min(*p), hi.max(*p)),
        )
    }
}
