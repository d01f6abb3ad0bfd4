//! A row of a sphere patch's layout: a parallel at a colatitude with a uniform
//! spacing of vertices round it, and those vertices' longitudes with their
//! cosines and sines. Shared by `layout` (which chooses the rows) and `bound`
//! (which checks the triangles zipped between two of them).

use std::f64::consts::TAU;

use glam::DVec3;

/// A spacing's cosines and sines are turned on from an exact one over this
/// many vertices at most (each turn adds a rounding of about 1e-16).
const EXACT_EVERY: usize = 16;

/// A parallel of the sphere: its colatitude from the pole and its uniform
/// spacing.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct Row {
    pub phi: f64,
    /// Vertices of the uniform spacing (the seam's extra vertex of a shifted
    /// row not counted).
    pub count: usize,
    /// Whether the uniform spacing is shifted by half a step from the seam.
    pub shifted: bool,
}

/// A row's longitudes from the seam, 0 and 2π included, with their cosines and
/// sines.
pub(super) struct Spacing {
    pub lams: Vec<f64>,
    cs: Vec<(f64, f64)>,
}

impl Spacing {
    pub fn new(count: usize, shifted: bool) -> Self {
        let step = TAU / count as f64;
        let shift = if shifted { 0.5 } else { 0.0 };
        let mut lams = Vec::with_capacity(count + 2);
        if shifted {
            lams.push(0.0);
        }
        lams.extend((0..count).map(|k| (k as f64 + shift) * step));
        lams.push(TAU);
        let (turn_s, turn_c) = step.sin_cos();
        let mut cs: Vec<(f64, f64)> = Vec::with_capacity(lams.len());
        for (k, &l) in lams.iter().enumerate() {
            // Exact at the seam's ends, the first of a shifted row and every
            // few; turned by one step from the last otherwise.
            let exact = k % EXACT_EVERY == 0 || k + 1 == lams.len() || (shifted && k == 1);
            let next = match cs.last() {
                Some(&(c, s)) if !exact => (c * turn_c - s * turn_s, s * turn_c + c * turn_s),
                _ => {
                    let (s, c) = l.sin_cos();
                    (c, s)
                }
            };
            cs.push(next);
        }
        Self { lams, cs }
    }

    /// Segments seam to seam.
    pub fn segments(&self) -> usize {
        self.lams.len() - 1
    }

    /// (r sin φ, r cos φ): what [`Spacing::vertex`] takes for a row at `phi`.
    pub fn at(&self, r: f64, phi: f64) -> (f64, f64) {
        let (s, c) = phi.sin_cos();
        (r * s, r * c)
    }

    /// Vertex `i` of the row at `at` ([`Spacing::at`]).
    #[inline]
    pub fn vertex(&self, (s, z): (f64, f64), i: usize) -> DVec3 {
        let (c, sn) = self.cs[i];
        DVec3::new(s * c, s * sn, z)
    }
}
