//! The development of an eccentric reducer: an oblique circular cone.
//!
//! The mid-surface is taken as the oblique cone through the two end circles
//! of mid radius (`r = D/2 − t/2` in each end plane, the small end's centre
//! offset by `r₁ − r₂` towards the flat side, as the part builder places
//! it): points of equal angle φ on the two circles lie on one generator
//! through the apex `A = c·r₁/(r₁ − r₂)` (`c` the small end's centre). A cone
//! is developable: a generator keeps its length from the apex, and the
//! developed angle grows by `dψ = |(P − A) × P′| / |P − A|² dφ` along the
//! large end circle `P(φ)`. A point at fraction `λ = r₂/r₁` of the way from
//! the apex lies on the small end, so the plate is the region between the
//! curves `(ρ(φ), ψ(φ))` and `(λ·ρ(φ), ψ(φ))`, `ρ = |P − A|`, and its area
//! is `½(1 − λ²)·∫|(P − A) × P′| dφ` — the cone's area, exactly. Both
//! integrals are taken by Gauss–Legendre rules on equal steps of φ, to
//! rounding (the integrands are analytic and periodic).
//!
//! The plate is cut open along the generator of the flat side (φ = the flat
//! side's angle), the one that runs parallel to the axis.

use std::f64::consts::TAU;

use glam::{DVec2, DVec3};

use crate::nurbs::GaussLegendre;

/// An oblique cone frustum between two parallel circles, developed.
#[derive(Clone, Debug, PartialEq)]
pub struct ObliqueCone {
    /// Radius of the large end (in the plane z = 0, centred on the axis), mm.
    pub large: f64,
    /// Radius of the small end, mm.
    pub small: f64,
    /// Axial length, mm.
    pub length: f64,
    /// Angle of the flat side about the axis, radians.
    pub flat_side: f64,
}

/// Steps of φ the integrals are taken on (each by an 8-point rule).
const STEPS: usize = 256;

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

    /// The apex.
    pub fn apex(&self) -> DVec3 {
        let d = self.large - self.small;
        let c = DVec3::new(
            d * self.flat_side.cos(),
            d * self.flat_side.sin(),
            self.length,
        );
        c * (self.large / d)
    }

    /// The point at angle `phi` of the large end.
    fn base(&self, phi: f64) -> DVec3 {
        DVec3::new(self.large * phi.cos(), self.large * phi.sin(), 0.0)
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

    /// `∫ f` over one turn from the flat side, on [`STEPS`] steps.
    fn integrate(&self, f: impl Fn(f64) -> f64) -> f64 {
        let rule = GaussLegendre::new(8);
        let h = TAU / STEPS as f64;
        (0..STEPS)
            .map(|k| {
                let a = self.flat_side + k as f64 * h;
                rule.integrate(a, a + h, &f)
            })
            .sum()
    }

    /// The developed plate's angle at the apex, radians.
    pub fn angle(&self) -> f64 {
        self.integrate(|phi| self.turn(phi))
    }

    /// The exact area of the frustum (= the developed plate's), mm².
    pub fn area(&self) -> f64 {
        let lambda = self.small / self.large;
        0.5 * (1.0 - lambda * lambda) * self.integrate(|phi| self.sweep(phi))
    }

    /// The developed plate's outline, apex at the origin, cut open along the
    /// flat side's generator (on +x): the large end's curve from φ = flat
    /// side round to it again, then the small end's back, `n` points each
    /// (`n` a multiple of [`STEPS`] is not needed: ψ is integrated on the way).
    pub fn outline(&self, n: usize) -> Vec<DVec2> {
        let n = n.max(8);
        let rule = GaussLegendre::new(8);
        let h = TAU / n as f64;
        let lambda = self.small / self.large;
        let mut psi = 0.0;
        let mut outer = Vec::with_capacity(n + 1);
        for k in 0..=n {
            let phi = self.flat_side + k as f64 * h;
            if k > 0 {
                psi += rule.integrate(phi - h, phi, |x| self.turn(x));
            }
            let rho = (self.base(phi) - self.apex()).length();
            outer.push(DVec2::new(psi.cos(), psi.sin()) * rho);
        }
        let inner: Vec<DVec2> = outer.iter().rev().map(|p| *p * lambda).collect();
        outer.extend(inner);
        outer
    }
}
