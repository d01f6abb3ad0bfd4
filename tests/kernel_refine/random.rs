//! Random rational curves and surfaces for the property tests, and the sampled
//! shape comparisons they are checked with.

use glam::DVec3;
use proptest::prelude::*;
use proptest::test_runner::RngSeed;
use vesselcad::nurbs::{KnotVector, NurbsCurve, NurbsSurface, homogeneous};

/// Side of the box the random control points lie in.
pub const BOX: f64 = 1000.0;
/// Largest allowed deviation between shapes that should be equal.
pub const TOL: f64 = 1e-9 * BOX;
/// Samples per direction for shape comparisons.
pub const SAMPLES: usize = 48;

pub fn config() -> ProptestConfig {
    ProptestConfig {
        cases: 96,
        rng_seed: RngSeed::Fixed(0x7e55e1),
        failure_persistence: None,
        ..ProptestConfig::default()
    }
}

/// Random ingredients of one knot vector: degree, domain, distinct interior knots on
/// a grid of twentieths of the domain, and their multiplicities.
#[derive(Clone, Debug)]
pub struct KnotSpec {
    degree: usize,
    start: f64,
    length: f64,
    interior: Vec<(u32, usize)>,
}

impl KnotSpec {
    fn knot(&self, twentieths: f64) -> f64 {
        self.start + self.length * (twentieths / 20.0)
    }

    fn knots(&self) -> Vec<f64> {
        let mut k = vec![self.start; self.degree + 1];
        for &(pos, mult) in &self.interior {
            k.extend(std::iter::repeat_n(self.knot(pos as f64), mult));
        }
        k.extend(std::iter::repeat_n(
            self.start + self.length,
            self.degree + 1,
        ));
        k
    }
}

pub fn knot_spec(max_interior: usize) -> impl Strategy<Value = KnotSpec> {
    (
        1usize..=4,
        -10.0..10.0f64,
        0.5..20.0f64,
        prop::collection::btree_set(1u32..20, 0..=max_interior),
        prop::collection::vec(0usize..4, max_interior),
    )
        .prop_map(|(degree, start, length, positions, mults)| KnotSpec {
            degree,
            start,
            length,
            interior: positions
                .into_iter()
                .zip(mults)
                .map(|(p, m)| (p, m % degree + 1))
                .collect(),
        })
}

pub fn weighted_point() -> impl Strategy<Value = (DVec3, f64)> {
    let c = -BOX / 2.0..BOX / 2.0;
    ((c.clone(), c.clone(), c), 0.2..5.0f64).prop_map(|((x, y, z), w)| (DVec3::new(x, y, z), w))
}

pub fn curve() -> impl Strategy<Value = NurbsCurve> {
    (
        knot_spec(5),
        prop::collection::vec(weighted_point(), 5 + 5 * 4),
    )
        .prop_map(|(spec, pts)| {
            let knots = KnotVector::try_new(spec.degree, spec.knots()).unwrap();
            let n = knots.basis_count();
            let hom = pts[..n].iter().map(|&(p, w)| homogeneous(p, w)).collect();
            NurbsCurve::try_new(knots, hom).unwrap()
        })
}

pub fn surface() -> impl Strategy<Value = NurbsSurface> {
    (
        knot_spec(3),
        knot_spec(3),
        prop::collection::vec(weighted_point(), (5 + 3 * 4) * (5 + 3 * 4)),
    )
        .prop_map(|(su, sv, pts)| {
            let u = KnotVector::try_new(su.degree, su.knots()).unwrap();
            let v = KnotVector::try_new(sv.degree, sv.knots()).unwrap();
            let n = u.basis_count() * v.basis_count();
            let hom = pts[..n].iter().map(|&(p, w)| homogeneous(p, w)).collect();
            NurbsSurface::try_new(u, v, hom).unwrap()
        })
}

/// `SAMPLES + 1` uniform parameters over `[a, b]` plus the distinct knots inside.
pub fn params(a: f64, b: f64, knots: &KnotVector) -> Vec<f64> {
    let mut t: Vec<f64> = (0..=SAMPLES)
        .map(|i| a + (b - a) * i as f64 / SAMPLES as f64)
        .collect();
    t.extend(knots.distinct().into_iter().filter(|&k| k >= a && k <= b));
    t
}

/// Largest distance between `a(t)` and `b(t)` over samples of `b`'s domain.
pub fn curve_deviation(a: &NurbsCurve, b: &NurbsCurve) -> f64 {
    let (t0, t1) = b.domain();
    params(t0, t1, b.knots())
        .into_iter()
        .map(|t| (a.point(t) - b.point(t)).length())
        .fold(0.0, f64::max)
}

/// Largest distance between `a(u, v)` and `b(u, v)` over a grid on `b`'s domain.
pub fn surface_deviation(a: &NurbsSurface, b: &NurbsSurface) -> f64 {
    let ((u0, u1), (v0, v1)) = b.domain();
    let us = params(u0, u1, b.u_knots());
    let vs = params(v0, v1, b.v_knots());
    let mut worst: f64 = 0.0;
    for &u in us.iter().step_by(3) {
        for &v in vs.iter().step_by(3) {
            worst = worst.max((a.point(u, v) - b.point(u, v)).length());
        }
    }
    worst
}

/// A parameter strictly inside the domain: an existing interior knot when `on_knot`
/// and there is one, else the fraction `f` of the domain.
pub fn pick_parameter(knots: &KnotVector, f: f64, on_knot: bool) -> f64 {
    let (a, b) = knots.domain();
    let interior: Vec<f64> = knots
        .distinct()
        .into_iter()
        .filter(|&k| k > a && k < b)
        .collect();
    if on_knot && !interior.is_empty() {
        interior[(f * interior.len() as f64) as usize % interior.len()]
    } else {
        a + (b - a) * f
    }
}
