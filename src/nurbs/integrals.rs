//! Surface integrals of a patch: its area and the flux of x/3 through it.
//!
//! Both are ∫∫ f(S, S_u, S_v) du dv over the parameter rectangle, taken by a tensor
//! Gauss–Legendre rule on each pair of Bézier spans (where the integrand is smooth)
//! with adaptive quadrisection until two levels agree to [`RELATIVE_TOLERANCE`] of
//! ∫∫|f|. Part measures (`crate::parts::surface_area`, `enclosed_volume`) sum these
//! over a part's patches; nothing in the meshing path depends on them.
//!
//! Quadrature nodes are interior, so the integrands are never evaluated on a
//! degenerate edge (a pole), where they vanish anyway.

use std::sync::OnceLock;

use super::{GaussLegendre, NurbsSurface, SurfaceDerivatives};

/// Nodes per direction of the tensor rule applied to every rectangle.
const ORDER: usize = 12;

/// A rectangle is accepted when its estimate and the sum of its four quarters'
/// estimates differ by at most this fraction of ∫∫|f| over it.
const RELATIVE_TOLERANCE: f64 = 1e-13;

/// Deepest quadrisection of a span pair: a bound on the work for integrands that are
/// not smooth inside a span (|S_u × S_v| of a patch with a cusp).
const MAX_DEPTH: u32 = 8;

/// The rule shared by every surface integral, computed on first use.
fn rule() -> &'static GaussLegendre {
    static RULE: OnceLock<GaussLegendre> = OnceLock::new();
    RULE.get_or_init(|| GaussLegendre::new(ORDER))
}

/// A parameter rectangle `[u0, u1] × [v0, v1]`.
#[derive(Clone, Copy)]
struct Rectangle {
    u0: f64,
    u1: f64,
    v0: f64,
    v1: f64,
}

/// A rule's estimate over one rectangle: `∫∫ f` and `∫∫ |f|`.
#[derive(Clone, Copy)]
struct Estimate {
    value: f64,
    magnitude: f64,
}

impl Rectangle {
    /// The four quarters.
    fn quarters(self) -> [Rectangle; 4] {
        let um = 0.5 * (self.u0 + self.u1);
        let vm = 0.5 * (self.v0 + self.v1);
        [
            Rectangle {
                u1: um,
                v1: vm,
                ..self
            },
            Rectangle {
                u0: um,
                v1: vm,
                ..self
            },
            Rectangle {
                u1: um,
                v0: vm,
                ..self
            },
            Rectangle {
                u0: um,
                v0: vm,
                ..self
            },
        ]
    }
}

impl NurbsSurface {
    /// Area ∫∫|S_u × S_v| du dv, to about 1e-13 relative.
    pub fn area(&self) -> f64 {
        self.integrate(|d| d.du.cross(d.dv).length())
    }

    /// The flux of the field x/3 through the patch along its normal `S_u × S_v`:
    /// (1/3) ∫∫ S · (S_u × S_v) du dv, to about 1e-13 relative (of the flux of |x/3·n|).
    ///
    /// By the divergence theorem (div x/3 = 1) the sum of this over a closed set of
    /// patches with outward normals is the enclosed volume; a patch on a plane through
    /// the origin contributes zero.
    pub fn volume_integral(&self) -> f64 {
        self.integrate(|d| d.point.dot(d.du.cross(d.dv))) / 3.0
    }

    /// ∫∫ f(derivatives) du dv over the domain, span pair by span pair.
    fn integrate(&self, f: impl Fn(&SurfaceDerivatives) -> f64) -> f64 {
        let v_spans = self.v_knots().spans();
        let mut total = 0.0;
        for (u0, u1) in self.u_knots().spans() {
            for &(v0, v1) in &v_spans {
                let rect = Rectangle { u0, u1, v0, v1 };
                let whole = self.estimate(rect, &f);
                total += self.refine(rect, whole, &f, 0);
            }
        }
        total
    }

    /// The tensor rule over one rectangle.
    fn estimate(&self, r: Rectangle, f: &impl Fn(&SurfaceDerivatives) -> f64) -> Estimate {
        let mut value = 0.0;
        let mut magnitude = 0.0;
        for (u, wu) in rule().points_on(r.u0, r.u1) {
            for (v, wv) in rule().points_on(r.v0, r.v1) {
                let x = f(&self.derivatives(u, v)) * wu * wv;
                value += x;
                magnitude += x.abs();
            }
        }
        Estimate { value, magnitude }
    }

    /// Adaptive quadrisection of a rectangle whose estimate is `whole`.
    fn refine(
        &self,
        r: Rectangle,
        whole: Estimate,
        f: &impl Fn(&SurfaceDerivatives) -> f64,
        depth: u32,
    ) -> f64 {
        let quarters = r.quarters().map(|q| (q, self.estimate(q, f)));
        let value: f64 = quarters.iter().map(|(_, e)| e.value).sum();
        let magnitude: f64 = quarters.iter().map(|(_, e)| e.magnitude).sum();
        if depth >= MAX_DEPTH || (value - whole.value).abs() <= RELATIVE_TOLERANCE * magnitude {
            return value;
        }
        quarters
            .iter()
            .map(|&(q, e)| self.refine(q, e, f, depth + 1))
            .sum()
    }
}

#[cfg(test)]
mod tests {
    use glam::DVec3;

    use crate::nurbs::builders::{disk, planar_quad};

    #[test]
    fn planar_patches() {
        let q = planar_quad(
            DVec3::ZERO,
            DVec3::new(2.0, 0.0, 0.0),
            DVec3::new(0.0, 3.0, 0.0),
            DVec3::new(2.0, 3.0, 0.0),
        )
        .unwrap();
        assert!((q.area() - 6.0).abs() < 1e-14);
        assert_eq!(q.volume_integral(), 0.0);
        // A disk at height h, normal +Z: flux of x/3 is h · area / 3.
        let d = disk(DVec3::new(0.0, 0.0, 3.0), DVec3::Z, 2.0).unwrap();
        let area = std::f64::consts::PI * 4.0;
        assert!((d.area() - area).abs() < 1e-13 * area);
        assert!((d.volume_integral() - area).abs() < 1e-13 * area);
    }
}
