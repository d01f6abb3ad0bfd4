//! Clamped knot vectors: validation, span search, multiplicity and Bézier spans.
//!
//! A [`KnotVector`] is the parameter-space half of every curve and surface in the
//! kernel. It is validated once on construction (finite, non-decreasing, clamped,
//! multiplicities ≤ degree + 1) so that evaluation never has to check again.

use super::{MAX_DEGREE, NurbsError};

/// A validated, clamped (open) knot vector together with the degree it is clamped for.
#[derive(Clone, Debug, PartialEq)]
pub struct KnotVector {
    knots: Vec<f64>,
    degree: usize,
}

impl KnotVector {
    /// Validates `knots` as a clamped knot vector of `degree`.
    ///
    /// Knots must be finite and non-decreasing, the first and last knot must appear
    /// exactly `degree + 1` times, no knot more than `degree + 1` times, and the domain
    /// must not be empty. The knots are never sorted or repaired.
    pub fn try_new(degree: usize, knots: Vec<f64>) -> Result<Self, NurbsError> {
        if degree == 0 || degree > MAX_DEGREE {
            return Err(NurbsError::DegreeOutOfRange {
                degree,
                max: MAX_DEGREE,
            });
        }
        for (index, &value) in knots.iter().enumerate() {
            if !value.is_finite() {
                return Err(NurbsError::KnotNotFinite { index, value });
            }
            if index > 0 && value < knots[index - 1] {
                return Err(NurbsError::KnotsDecreasing {
                    index,
                    previous: knots[index - 1],
                    next: value,
                });
            }
        }
        let order = degree + 1;
        if knots.len() < 2 * order {
            return Err(NurbsError::NotClamped {
                end: "first",
                multiplicity: knots.len().min(order),
                expected: order,
            });
        }
        let first = knots[0];
        let last = knots[knots.len() - 1];
        if last <= first {
            return Err(NurbsError::EmptyDomain {
                start: first,
                end: last,
            });
        }
        let head = knots.iter().take_while(|&&k| k == first).count();
        if head != order {
            return Err(NurbsError::NotClamped {
                end: "first",
                multiplicity: head,
                expected: order,
            });
        }
        let tail = knots.iter().rev().take_while(|&&k| k == last).count();
        if tail != order {
            return Err(NurbsError::NotClamped {
                end: "last",
                multiplicity: tail,
                expected: order,
            });
        }
        let mut start = 0;
        while start < knots.len() {
            let value = knots[start];
            let run = knots[start..].iter().take_while(|&&k| k == value).count();
            if run > order {
                return Err(NurbsError::MultiplicityTooHigh {
                    knot: value,
                    multiplicity: run,
                    max: order,
                });
            }
            start += run;
        }
        Ok(Self { knots, degree })
    }

    /// Validates like [`try_new`](Self::try_new).
    ///
    /// # Panics
    /// On invalid knots: for vectors the program itself builds, never for user data.
    pub fn new(degree: usize, knots: Vec<f64>) -> Self {
        match Self::try_new(degree, knots) {
            Ok(k) => k,
            Err(e) => panic!("invalid knot vector: {e}"),
        }
    }

    /// The clamped vector on [0, 1] with `count − degree − 1` uniformly spaced
    /// interior knots: the knot vector of `count` control points.
    pub fn uniform(degree: usize, count: usize) -> Result<Self, NurbsError> {
        if count <= degree {
            return Err(NurbsError::PointCountMismatch {
                direction: "curve",
                expected: degree + 1,
                got: count,
            });
        }
        let interior = count - degree - 1;
        let mut knots = vec![0.0; degree + 1];
        for i in 1..=interior {
            knots.push(i as f64 / (interior + 1) as f64);
        }
        knots.extend(std::iter::repeat_n(1.0, degree + 1));
        Self::try_new(degree, knots)
    }

    /// The degree this vector is clamped for.
    #[inline]
    pub fn degree(&self) -> usize {
        self.degree
    }

    /// All knots, including the repeated end knots.
    #[inline]
    pub fn as_slice(&self) -> &[f64] {
        &self.knots
    }

    /// Number of knots.
    #[inline]
    pub fn len(&self) -> usize {
        self.knots.len()
    }

    /// Always false: a valid vector has at least `2 (degree + 1)` knots.
    #[inline]
    pub fn is_empty(&self) -> bool {
        self.knots.is_empty()
    }

    /// Number of basis functions (= control points) this vector defines.
    #[inline]
    pub fn basis_count(&self) -> usize {
        self.knots.len() - self.degree - 1
    }

    /// The parameter domain `[first knot, last knot]`.
    #[inline]
    pub fn domain(&self) -> (f64, f64) {
        (self.knots[0], self.knots[self.knots.len() - 1])
    }

    /// Clamps `u` into the domain.
    #[inline]
    pub fn clamp(&self, u: f64) -> f64 {
        let (a, b) = self.domain();
        if u.is_nan() { a } else { u.clamp(a, b) }
    }

    /// Index `i` of the knot span `[U_i, U_{i+1})` holding `u` (Piegl & Tiller A2.1);
    /// the last non-empty span for `u` at the end of the domain. `u` is clamped.
    #[inline]
    pub fn find_span(&self, u: f64) -> usize {
        let u = self.clamp(u);
        let n = self.basis_count() - 1;
        let k = &self.knots;
        if u >= k[n + 1] {
            return n;
        }
        if u <= k[self.degree] {
            return self.degree;
        }
        let (mut low, mut high) = (self.degree, n + 1);
        let mut mid = (low + high) / 2;
        while u < k[mid] || u >= k[mid + 1] {
            if u < k[mid] {
                high = mid;
            } else {
                low = mid;
            }
            mid = (low + high) / 2;
        }
        mid
    }

    /// How many times `u` appears in the vector (exact comparison).
    pub fn multiplicity(&self, u: f64) -> usize {
        self.knots.iter().filter(|&&k| k == u).count()
    }

    /// Distinct knot values in increasing order.
    pub fn distinct(&self) -> Vec<f64> {
        let mut out: Vec<f64> = Vec::new();
        for &k in &self.knots {
            if out.last() != Some(&k) {
                out.push(k);
            }
        }
        out
    }

    /// The non-empty knot intervals `[a, b)`: the Bézier spans of the B-spline.
    pub fn spans(&self) -> Vec<(f64, f64)> {
        self.distinct().windows(2).map(|w| (w[0], w[1])).collect()
    }

    /// The vector mapped affinely onto `[start, end]`.
    pub fn reparametrized(&self, start: f64, end: f64) -> Result<Self, NurbsError> {
        let (a, b) = self.domain();
        let scale = (end - start) / (b - a);
        let knots = self
            .knots
            .iter()
            .map(|&k| if k == b { end } else { start + (k - a) * scale })
            .collect();
        Self::try_new(self.degree, knots)
    }

    /// The vector with every knot `u` mapped to `a + b − u` (the parameter reversal).
    pub fn reversed(&self) -> Self {
        let (a, b) = self.domain();
        let knots = self.knots.iter().rev().map(|&k| a + b - k).collect();
        Self {
            knots,
            degree: self.degree,
        }
    }

    /// Builds without validation; for kernel algorithms that preserve validity.
    pub(crate) fn from_raw(degree: usize, knots: Vec<f64>) -> Self {
        debug_assert!(Self::try_new(degree, knots.clone()).is_ok());
        Self { knots, degree }
    }
}
