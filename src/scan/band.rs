//! A symmetric positive definite banded matrix and its Cholesky factorization:
//! the normal equations of a tensor-product least-squares fit, whose unknowns
//! ordered v-major couple only within `q·n_u + p` of each other.

/// Lower band of a symmetric matrix: `rows[i * (width + 1) + k]` is entry
/// (i, i − k).
#[derive(Clone, Debug)]
pub struct Band {
    size: usize,
    width: usize,
    values: Vec<f64>,
}

impl Band {
    /// A zero matrix of `size` with `width` sub-diagonals.
    pub fn zeros(size: usize, width: usize) -> Self {
        let width = width.min(size.saturating_sub(1));
        Self {
            size,
            width,
            values: vec![0.0; size * (width + 1)],
        }
    }

    /// Adds `value` to entries (i, j) and (j, i); `|i − j|` must be within the band.
    #[inline]
    pub fn add(&mut self, i: usize, j: usize, value: f64) {
        let (i, j) = if i >= j { (i, j) } else { (j, i) };
        debug_assert!(i - j <= self.width);
        self.values[i * (self.width + 1) + (i - j)] += value;
    }

    /// Entry (i, i).
    pub fn diagonal(&self, i: usize) -> f64 {
        self.values[i * (self.width + 1)]
    }

    /// Entry (i, j) of the symmetric matrix; zero outside the band.
    #[cfg(test)]
    pub fn entry(&self, i: usize, j: usize) -> f64 {
        let (i, j) = if i >= j { (i, j) } else { (j, i) };
        if i - j > self.width {
            0.0
        } else {
            self.values[i * (self.width + 1) + (i - j)]
        }
    }

    /// Factors in place (L Lᵀ) and solves for each right-hand side; the index of
    /// the first pivot that is not positive on failure.
    #[expect(
        clippy::needless_range_loop,
        reason = "index arithmetic over matrix rows and columns reads as the algorithm"
    )]
    pub fn solve(mut self, rhs: &mut [Vec<f64>]) -> Result<(), usize> {
        let w = self.width;
        let stride = w + 1;
        let at = |i: usize, j: usize| i * stride + (i - j);
        for i in 0..self.size {
            let j0 = i.saturating_sub(w);
            for j in j0..=i {
                let k0 = j0.max(j.saturating_sub(w));
                // Entries (i, k) and (j, k) for k from j − 1 down to k0 lie
                // side by side in rows i and j.
                let n = j - k0;
                let sum = self.values[at(i, j)]
                    - dot(
                        &self.values[at(i, j) + 1..at(i, j) + 1 + n],
                        &self.values[at(j, j) + 1..at(j, j) + 1 + n],
                    );
                if i == j {
                    if sum <= 0.0 || !sum.is_finite() {
                        return Err(i);
                    }
                    self.values[at(i, i)] = sum.sqrt();
                } else {
                    self.values[at(i, j)] = sum / self.values[at(j, j)];
                }
            }
        }
        for b in rhs.iter_mut() {
            for i in 0..self.size {
                let mut sum = b[i];
                for k in i.saturating_sub(w)..i {
                    sum -= self.values[at(i, k)] * b[k];
                }
                b[i] = sum / self.values[at(i, i)];
            }
            for i in (0..self.size).rev() {
                let mut sum = b[i];
                for k in i + 1..(i + w + 1).min(self.size) {
                    sum -= self.values[at(k, i)] * b[k];
                }
                b[i] = sum / self.values[at(i, i)];
            }
        }
        Ok(())
    }
}

/// Σ aᵢ·bᵢ over four running sums (the band's inner loop, vectorized).
#[inline]
fn dot(a: &[f64], b: &[f64]) -> f64 {
    let (ca, cb) = (a.chunks_exact(4), b.chunks_exact(4));
    let tail: f64 = ca
        .remainder()
        .iter()
        .zip(cb.remainder())
        .map(|(x, y)| x * y)
        .sum();
    let mut sums = [0.0; 4];
    for (x, y) in ca.zip(cb) {
        for k in 0..4 {
            sums[k] += x[k] * y[k];
        }
    }
    (sums[0] + sums[1]) + (sums[2] + sums[3]) + tail
}

/// Solves the small dense system `a x = b` (Gaussian elimination with partial
/// pivoting); `None` when singular.
#[expect(
    clippy::needless_range_loop,
    reason = "index arithmetic over matrix rows and columns reads as the algorithm"
)]
pub fn solve_dense(mut a: Vec<Vec<f64>>, mut b: Vec<f64>) -> Option<Vec<f64>> {
    let n = b.len();
    for c in 0..n {
        let pivot = (c..n).max_by(|&i, &j| a[i][c].abs().total_cmp(&a[j][c].abs()))?;
        if a[pivot][c].abs() < 1e-300 {
            return None;
        }
        a.swap(c, pivot);
        b.swap(c, pivot);
        for r in 0..n {
            if r != c {
                let f = a[r][c] / a[c][c];
                if f != 0.0 {
                    for k in c..n {
                        a[r][k] -= f * a[c][k];
                    }
                    b[r] -= f * b[c];
                }
            }
        }
    }
    Some((0..n).map(|i| b[i] / a[i][i]).collect())
}

/// Weighted least squares of `values` on the first `n` entries of each of
/// `rows`, with weights: the small dense fits of the checks.
pub fn least_squares(
    rows: &[[f64; 5]],
    values: &[f64],
    weights: &[f64],
    n: usize,
) -> Option<Vec<f64>> {
    let mut a = vec![vec![0.0; n]; n];
    let mut b = vec![0.0; n];
    for ((row, &y), &w) in rows.iter().zip(values).zip(weights) {
        if w == 0.0 {
            continue;
        }
        for i in 0..n {
            for j in 0..n {
                a[i][j] += w * row[i] * row[j];
            }
            b[i] += w * row[i] * y;
        }
    }
    solve_dense(a, b)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    #[expect(
        clippy::needless_range_loop,
        reason = "index arithmetic over matrix rows and columns reads as the algorithm"
    )]
    fn solves_a_banded_system() {
        // Tridiagonal 2, -1 plus a small shift: exact solution of ones.
        let n = 50;
        let mut m = Band::zeros(n, 3);
        for i in 0..n {
            m.add(i, i, 2.5);
            if i > 0 {
                m.add(i, i - 1, -1.0);
            }
            if i > 2 {
                m.add(i, i - 3, 0.2);
            }
        }
        let mut b = vec![0.0; n];
        for i in 0..n {
            b[i] += 2.5;
            if i > 0 {
                b[i] -= 1.0;
            }
            if i + 1 < n {
                b[i] -= 1.0;
            }
            if i > 2 {
                b[i] += 0.2;
            }
            if i + 3 < n {
                b[i] += 0.2;
            }
        }
        let mut rhs = vec![b];
        m.solve(&mut rhs).unwrap();
        for x in &rhs[0] {
            assert!((x - 1.0).abs() < 1e-12, "{x}");
        }
    }
}
