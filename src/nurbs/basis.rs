//! B-spline basis functions and their derivatives (Piegl & Tiller A2.2 and A2.3).
//!
//! These are the innermost loops of every evaluation in the kernel. They work on
//! fixed-size stack arrays of length [`MAX_ORDER`] so that evaluation allocates
//! nothing. The thesis's listing of A2.2 has two bugs (its right-hand term uses
//! `U[i+1-j]` instead of `U[i+j]`, and it omits the final `N[j] = saved`); this is the
//! corrected algorithm.

use super::MAX_DEGREE;

/// Largest number of non-zero basis functions at a parameter: `MAX_DEGREE + 1`.
pub const MAX_ORDER: usize = MAX_DEGREE + 1;

/// Values of the `p + 1` non-zero basis functions `N_{span−p..=span, p}(u)`
/// (A2.2). Only the first `p + 1` entries of the result are meaningful.
#[inline]
pub fn basis_functions(knots: &[f64], span: usize, u: f64, p: usize) -> [f64; MAX_ORDER] {
    basis_functions_in::<MAX_ORDER>(knots, span, u, p)
}

/// [`basis_functions`] in arrays of `N > p` entries: the same values, with less
/// stack to clear for a low degree (row evaluation uses [`SMALL_ORDER`]).
#[inline]
pub fn basis_functions_in<const N: usize>(
    knots: &[f64],
    span: usize,
    u: f64,
    p: usize,
) -> [f64; N] {
    let mut n = [0.0; N];
    if p == 2 && N > 2 {
        // Unrolled: the same operations as the loop below, without it.
        let t = Quadratic::at(knots, span, u);
        n[0] = t.n[0];
        n[1] = t.n[1];
        n[2] = t.n[2];
        return n;
    }
    let mut left = [0.0; N];
    let mut right = [0.0; N];
    n[0] = 1.0;
    for j in 1..=p {
        left[j] = u - knots[span + 1 - j];
        right[j] = knots[span + j] - u;
        let mut saved = 0.0;
        for r in 0..j {
            let temp = n[r] / (right[r + 1] + left[j - r]);
            n[r] = saved + right[r + 1] * temp;
            saved = left[j - r] * temp;
        }
        n[j] = saved;
    }
    n
}

/// Order of the small-array evaluation path: degrees up to 3.
pub const SMALL_ORDER: usize = 4;

/// Values and derivatives up to order `d` of the non-zero basis functions at `u`
/// (A2.3): `result[k][j]` is the k-th derivative of `N_{span−p+j, p}(u)`.
/// Derivatives above the degree are zero.
pub fn basis_derivatives<const D: usize>(
    knots: &[f64],
    span: usize,
    u: f64,
    p: usize,
) -> [[f64; MAX_ORDER]; D] {
    if p < SMALL_ORDER {
        let small = basis_derivatives_in::<D, SMALL_ORDER>(knots, span, u, p);
        let mut out = [[0.0; MAX_ORDER]; D];
        for (o, s) in out.iter_mut().zip(&small) {
            o[..SMALL_ORDER].copy_from_slice(s);
        }
        return out;
    }
    basis_derivatives_in::<D, MAX_ORDER>(knots, span, u, p)
}

/// Values and derivatives up to order `d` of the non-zero basis functions at `u`
/// (A2.3): `result[k][j]` is the k-th derivative of `N_{span−p+j, p}(u)`.
/// Derivatives above the degree are zero. Works in arrays of `N > p` entries: the
/// kernel's quadratics and cubics use `N = 4` ([`SMALL_ORDER`]), which keeps the
/// scratch arrays (zeroed on every call) a tenth of the general size.
#[inline]
pub fn basis_derivatives_in<const D: usize, const N: usize>(
    knots: &[f64],
    span: usize,
    u: f64,
    p: usize,
) -> [[f64; N]; D] {
    debug_assert!(p < N, "degree {p} needs arrays of more than {N}");
    match p {
        1 => linear_derivatives(knots, span, u),
        2 => quadratic_derivatives(knots, span, u),
        _ => general_derivatives(knots, span, u, p),
    }
}

/// [`basis_derivatives_in`] for any degree: A2.3 as published (corrected).
#[inline]
fn general_derivatives<const D: usize, const N: usize>(
    knots: &[f64],
    span: usize,
    u: f64,
    p: usize,
) -> [[f64; N]; D] {
    let mut ders = [[0.0; N]; D];
    let mut ndu = [[0.0; N]; N];
    let mut left = [0.0; N];
    let mut right = [0.0; N];
    ndu[0][0] = 1.0;
    for j in 1..=p {
        left[j] = u - knots[span + 1 - j];
        right[j] = knots[span + j] - u;
        let mut saved = 0.0;
        for r in 0..j {
            // Lower triangle: knot differences; upper triangle: basis values.
            ndu[j][r] = right[r + 1] + left[j - r];
            let temp = ndu[r][j - 1] / ndu[j][r];
            ndu[r][j] = saved + right[r + 1] * temp;
            saved = left[j - r] * temp;
        }
        ndu[j][j] = saved;
    }
    if D == 0 {
        return ders;
    }
    for j in 0..=p {
        ders[0][j] = ndu[j][p];
    }
    let order = D - 1; // highest derivative requested
    let mut a = [[0.0; N]; 2];
    for r in 0..=p {
        let (mut s1, mut s2) = (0usize, 1usize);
        a[0][0] = 1.0;
        for k in 1..=order.min(p) {
            let mut d = 0.0;
            let rk = r as isize - k as isize;
            let pk = p - k;
            if r >= k {
                a[s2][0] = a[s1][0] / ndu[pk + 1][r - k];
                d = a[s2][0] * ndu[r - k][pk];
            }
            let j1 = if rk >= -1 { 1 } else { (-rk) as usize };
            let j2 = if (r as isize - 1) <= pk as isize {
                k - 1
            } else {
                p - r
            };
            for j in j1..=j2 {
                let idx = (rk + j as isize) as usize;
                a[s2][j] = (a[s1][j] - a[s1][j - 1]) / ndu[pk + 1][idx];
                d += a[s2][j] * ndu[idx][pk];
            }
            if r <= pk {
                a[s2][k] = -a[s1][k - 1] / ndu[pk + 1][r];
                d += a[s2][k] * ndu[r][pk];
            }
            ders[k][r] = d;
            std::mem::swap(&mut s1, &mut s2);
        }
    }
    let mut factor = p as f64;
    for (k, row) in ders.iter_mut().enumerate().skip(1).take(order.min(p)) {
        for value in row.iter_mut().take(p + 1) {
            *value *= factor;
        }
        factor *= (p - k) as f64;
    }
    ders
}

/// A2.2's triangle for degree 1 at `u` in knot span `span`: the knot difference
/// `ndu[1][0]` and the two basis values, by the general algorithm's operations.
struct Linear {
    left1: f64,
    right1: f64,
    ndu10: f64,
    n: [f64; 2],
}

impl Linear {
    #[inline]
    fn at(knots: &[f64], span: usize, u: f64) -> Self {
        let left1 = u - knots[span];
        let right1 = knots[span + 1] - u;
        let ndu10 = right1 + left1;
        let temp = 1.0 / ndu10;
        Self {
            left1,
            right1,
            ndu10,
            n: [0.0 + right1 * temp, left1 * temp],
        }
    }
}

/// A2.2's triangle for degree 2: the knot differences below the diagonal, the
/// degree-1 values (`first`) and the three basis values, by the general
/// algorithm's operations in its order.
struct Quadratic {
    ndu10: f64,
    ndu20: f64,
    ndu21: f64,
    first: [f64; 2],
    n: [f64; 3],
}

impl Quadratic {
    #[inline]
    fn at(knots: &[f64], span: usize, u: f64) -> Self {
        let Linear {
            left1,
            right1,
            ndu10,
            n: first,
        } = Linear::at(knots, span, u);
        let left2 = u - knots[span - 1];
        let right2 = knots[span + 2] - u;
        let ndu20 = right1 + left2;
        let temp = first[0] / ndu20;
        let n0 = 0.0 + right1 * temp;
        let saved = left2 * temp;
        let ndu21 = right2 + left1;
        let temp = first[1] / ndu21;
        Self {
            ndu10,
            ndu20,
            ndu21,
            first,
            n: [n0, saved + right2 * temp, left1 * temp],
        }
    }
}

/// [`basis_derivatives_in`] for degree 1, unrolled: the same floating-point
/// operations in the same order as the general algorithm (so the same bits),
/// without its loops, scratch arrays and index arithmetic. Lines and the linear
/// direction of courses and cones are degree 1.
#[inline]
fn linear_derivatives<const D: usize, const N: usize>(
    knots: &[f64],
    span: usize,
    u: f64,
) -> [[f64; N]; D] {
    let mut ders = [[0.0; N]; D];
    if D == 0 {
        return ders;
    }
    let Linear { ndu10, n, .. } = Linear::at(knots, span, u);
    ders[0][0] = n[0];
    ders[0][1] = n[1];
    if D > 1 {
        // r = 0: a = −1/ndu10, d = 0 + a·ndu00; r = 1: a = 1/ndu10, d = a·ndu00;
        // then both times the degree, 1.
        ders[1][0] = (0.0 + (-1.0 / ndu10) * 1.0) * 1.0;
        ders[1][1] = ((1.0 / ndu10) * 1.0) * 1.0;
    }
    ders
}

/// [`basis_derivatives_in`] for degree 2, unrolled like [`linear_derivatives`]
/// (the same operations, so the same bits). Every circle and conic of the kernel
/// is a rational quadratic, so this is the most evaluated basis.
#[inline]
fn quadratic_derivatives<const D: usize, const N: usize>(
    knots: &[f64],
    span: usize,
    u: f64,
) -> [[f64; N]; D] {
    let mut ders = [[0.0; N]; D];
    if D == 0 {
        return ders;
    }
    let Quadratic {
        ndu10,
        ndu20,
        ndu21,
        first,
        n,
    } = Quadratic::at(knots, span, u);
    let [ndu01, ndu11] = first;
    ders[0][0] = n[0];
    ders[0][1] = n[1];
    ders[0][2] = n[2];
    if D == 1 {
        return ders;
    }
    // A2.3 with p = 2: first derivatives (k = 1, pk = 1) of each function r, and
    // the a-coefficients the second derivatives (k = 2, pk = 0) go on from.
    // r = 0
    let a1_1 = -1.0 / ndu20;
    let d1_0 = 0.0 + a1_1 * ndu01;
    // r = 1
    let b1_0 = 1.0 / ndu20;
    let b1_1 = -1.0 / ndu21;
    let d1_1 = b1_0 * ndu01 + b1_1 * ndu11;
    // r = 2
    let c1_0 = 1.0 / ndu21;
    let d1_2 = c1_0 * ndu11;
    ders[1][0] = d1_0 * 2.0;
    ders[1][1] = d1_1 * 2.0;
    ders[1][2] = d1_2 * 2.0;
    if D > 2 {
        // r = 0: a₂[2] = −a₁[1]/ndu10.
        let d2_0 = 0.0 + (-a1_1 / ndu10) * 1.0;
        // r = 1: a₂[1] = (a₁[1] − a₁[0])/ndu10.
        let d2_1 = 0.0 + ((b1_1 - b1_0) / ndu10) * 1.0;
        // r = 2: a₂[0] = a₁[0]/ndu10.
        let d2_2 = (c1_0 / ndu10) * 1.0;
        ders[2][0] = d2_0 * 2.0;
        ders[2][1] = d2_1 * 2.0;
        ders[2][2] = d2_2 * 2.0;
    }
    ders
}

#[cfg(test)]
mod tests {
    use super::*;

    const U: [f64; 11] = [0.0, 0.0, 0.0, 1.0, 2.0, 3.0, 4.0, 4.0, 5.0, 5.0, 5.0];

    #[test]
    fn thesis_example_values() {
        // Piegl & Tiller Ex. 2.3 / thesis Ch. 2.2.5: span 4 at u = 5/2.
        let n = basis_functions(&U, 4, 2.5, 2);
        assert_eq!(&n[..3], &[0.125, 0.75, 0.125]);
    }

    #[test]
    fn derivatives_match_finite_differences() {
        let h = 1e-6;
        for &u in &[0.3, 1.7, 2.5, 3.2, 4.6] {
            let span = 2 + U[3..9].iter().take_while(|&&k| k <= u).count();
            let ders = basis_derivatives::<3>(&U, span, u, 2);
            let plus = basis_functions(&U, span, u + h, 2);
            let minus = basis_functions(&U, span, u - h, 2);
            for j in 0..3 {
                let fd = (plus[j] - minus[j]) / (2.0 * h);
                assert!((fd - ders[1][j]).abs() < 1e-6, "u={u} j={j}");
                let fd2 = (plus[j] - 2.0 * ders[0][j] + minus[j]) / (h * h);
                assert!((fd2 - ders[2][j]).abs() < 1e-3, "u={u} j={j}");
            }
        }
    }
}

#[cfg(test)]
mod properties {
    use super::*;
    use proptest::prelude::*;

    /// A clamped knot vector of `degree` with random interior knots.
    fn knots() -> impl Strategy<Value = (usize, Vec<f64>)> {
        knots_of(1..=5)
    }

    /// [`knots`] of a degree in `degrees`.
    fn knots_of(
        degrees: std::ops::RangeInclusive<usize>,
    ) -> impl Strategy<Value = (usize, Vec<f64>)> {
        degrees.prop_flat_map(|p| {
            proptest::collection::vec(0.0..1.0f64, 0..12).prop_map(move |mut interior| {
                interior.sort_by(f64::total_cmp);
                let mut k = vec![0.0; p + 1];
                k.extend(interior);
                k.extend(std::iter::repeat_n(1.0, p + 1));
                (p, k)
            })
        })
    }

    proptest! {
        #![proptest_config(ProptestConfig { cases: 512, failure_persistence: None, ..ProptestConfig::default() })]

        /// The unrolled degree-1 and degree-2 paths give the general algorithm's
        /// values and derivatives bit for bit (values from A2.2 too), so no
        /// evaluation changes with the path taken.
        #[test]
        fn unrolled_degrees_are_bit_identical((p, k) in knots_of(1..=2), t in 0.0..=1.0f64) {
            let kv = crate::nurbs::KnotVector::new(p, k);
            let span = kv.find_span(t);
            let knots = kv.as_slice();
            let bits = |rows: &[[f64; SMALL_ORDER]]| -> Vec<u64> {
                rows.iter().flat_map(|r| r[..=p].iter().map(|x| x.to_bits())).collect()
            };
            let fast = basis_derivatives_in::<3, SMALL_ORDER>(knots, span, t, p);
            let slow = general_derivatives::<3, SMALL_ORDER>(knots, span, t, p);
            prop_assert_eq!(bits(&fast), bits(&slow));
            let first = basis_derivatives_in::<2, SMALL_ORDER>(knots, span, t, p);
            prop_assert_eq!(bits(&first), bits(&slow[..2]));
            let values = basis_functions_in::<SMALL_ORDER>(knots, span, t, p);
            prop_assert_eq!(bits(&[values]), bits(&slow[..1]));
        }

        /// Partition of unity and non-negativity at any parameter, for the values
        /// of A2.2 and the zeroth row of A2.3; derivatives of the sum vanish.
        #[test]
        fn partition_of_unity((p, k) in knots(), t in 0.0..=1.0f64) {
            let kv = crate::nurbs::KnotVector::new(p, k);
            let span = kv.find_span(t);
            let n = basis_functions(kv.as_slice(), span, t, p);
            let d = basis_derivatives::<3>(kv.as_slice(), span, t, p);
            let sum: f64 = n[..=p].iter().sum();
            prop_assert!((sum - 1.0).abs() < 1e-12, "sum {sum}");
            prop_assert!(n[..=p].iter().all(|&v| v >= -1e-15));
            for j in 0..=p {
                prop_assert!((n[j] - d[0][j]).abs() < 1e-12);
            }
            let s1: f64 = d[1][..=p].iter().sum();
            let s2: f64 = d[2][..=p].iter().sum();
            let scale = d[1][..=p].iter().chain(&d[2][..=p]).fold(1.0f64, |m, v| m.max(v.abs()));
            prop_assert!(s1.abs() < 1e-9 * scale && s2.abs() < 1e-9 * scale, "{s1} {s2}");
        }
    }
}
