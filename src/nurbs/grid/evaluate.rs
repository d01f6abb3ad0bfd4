//! Grid evaluation entry points on [`NurbsSurface`].
//!
//! Each u row is handled the same way: contract the `p + 1` control rows its u basis
//! touches into homogeneous isocurve control points (and, for normals, the same with
//! the u-derivative basis), then hand the row to the v kernels. The per-row
//! contraction costs `(p + 1) · v_count` homogeneous multiply-adds, small next to the
//! `(q + 1)`-term contraction of each of the row's grid points.

use glam::{DVec3, DVec4};

use super::GridError;
use super::basis::GridBasis;
use super::kernel::{contract_rows, points_row};
use super::normals::normals_row;
use crate::nurbs::NurbsSurface;

impl NurbsSurface {
    /// Points `S(us[i], vs[j])` of the tensor grid `us × vs`, row-major
    /// (`points[i * vs.len() + j]`, `i` along u).
    ///
    /// `points` is resized to `us.len() * vs.len()` and overwritten, so its
    /// allocation is reused across calls.
    /// Parameters are clamped to the domain as in [`point`](Self::point); any order is
    /// accepted, increasing parameters are fastest. Each point equals
    /// `self.point(u, v)` to rounding.
    pub fn evaluate_grid(&self, us: &[f64], vs: &[f64], points: &mut Vec<DVec3>) {
        let u = GridBasis::new(self.u_knots(), us);
        let v = GridBasis::new(self.v_knots(), vs);
        self.grid_points(&u, &v, points);
    }

    /// Points and unit normals of the tensor grid `us × vs`, both row-major like
    /// [`evaluate_grid`](Self::evaluate_grid).
    ///
    /// Each normal equals `self.normal(u, v)` to rounding; at degenerate edges (the
    /// pole of a head, the apex of a cone) and wherever `|S_u × S_v|` is small next
    /// to the partials it is computed by [`normal`](Self::normal) itself, so the
    /// limit normal there is exactly the pointwise one.
    pub fn evaluate_grid_with_normals(
        &self,
        us: &[f64],
        vs: &[f64],
        points: &mut Vec<DVec3>,
        normals: &mut Vec<DVec3>,
    ) {
        let u = GridBasis::new(self.u_knots(), us);
        let v = GridBasis::new(self.v_knots(), vs);
        self.grid_points_normals(&u, &v, points, normals);
    }

    /// True when `u` and `v` were computed for this surface's knot vectors, so that
    /// [`try_evaluate_grid_on`](Self::try_evaluate_grid_on) succeeds.
    pub fn can_evaluate_grid_on(&self, u: &GridBasis, v: &GridBasis) -> bool {
        u.fits(self.u_knots()) && v.fits(self.v_knots())
    }

    /// [`evaluate_grid`](Self::evaluate_grid) with precomputed bases, e.g. one pair
    /// shared by every patch with the same knot vectors.
    pub fn try_evaluate_grid_on(
        &self,
        u: &GridBasis,
        v: &GridBasis,
        points: &mut Vec<DVec3>,
    ) -> Result<(), GridError> {
        self.check_bases(u, v)?;
        self.grid_points(u, v, points);
        Ok(())
    }

    /// [`evaluate_grid_with_normals`](Self::evaluate_grid_with_normals) with
    /// precomputed bases.
    pub fn try_evaluate_grid_with_normals_on(
        &self,
        u: &GridBasis,
        v: &GridBasis,
        points: &mut Vec<DVec3>,
        normals: &mut Vec<DVec3>,
    ) -> Result<(), GridError> {
        self.check_bases(u, v)?;
        self.grid_points_normals(u, v, points, normals);
        Ok(())
    }

    fn check_bases(&self, u: &GridBasis, v: &GridBasis) -> Result<(), GridError> {
        if !u.fits(self.u_knots()) {
            return Err(GridError::KnotsMismatch { direction: "u" });
        }
        if !v.fits(self.v_knots()) {
            return Err(GridError::KnotsMismatch { direction: "v" });
        }
        Ok(())
    }

    /// Fills `points`; the bases fit this surface.
    fn grid_points(&self, u: &GridBasis, v: &GridBasis, points: &mut Vec<DVec3>) {
        let (rows, cols) = (u.len(), v.len());
        reset(points, rows * cols);
        if cols == 0 {
            return;
        }
        let stride = self.v_count();
        let net = self.homogeneous_points();
        let mut iso = vec![DVec4::ZERO; stride];
        for run in u.runs() {
            for i in run.start..run.end {
                contract_rows(net, stride, run, u.values(), u.order(), i, &mut iso);
                points_row(&iso, v, &mut points[i * cols..][..cols]);
            }
        }
    }

    /// Fills `points` and `normals`; the bases fit this surface.
    fn grid_points_normals(
        &self,
        u: &GridBasis,
        v: &GridBasis,
        points: &mut Vec<DVec3>,
        normals: &mut Vec<DVec3>,
    ) {
        let (rows, cols) = (u.len(), v.len());
        reset(points, rows * cols);
        reset(normals, rows * cols);
        if cols == 0 {
            return;
        }
        let stride = self.v_count();
        let net = self.homogeneous_points();
        let mut iso = vec![DVec4::ZERO; stride];
        let mut iso_du = vec![DVec4::ZERO; stride];
        for run in u.runs() {
            for i in run.start..run.end {
                contract_rows(net, stride, run, u.values(), u.order(), i, &mut iso);
                contract_rows(net, stride, run, u.derivatives(), u.order(), i, &mut iso_du);
                let ui = u.params()[i];
                normals_row(
                    &iso,
                    &iso_du,
                    v,
                    &mut points[i * cols..][..cols],
                    &mut normals[i * cols..][..cols],
                    |j| self.normal(ui, v.params()[j]),
                );
            }
        }
    }
}

/// Gives `buffer` length `len`, keeping its capacity. Existing elements are left as
/// they are (the kernels overwrite every one), so refilling a buffer of the right
/// length costs nothing.
fn reset(buffer: &mut Vec<DVec3>, len: usize) {
    buffer.truncate(len);
    buffer.resize(len, DVec3::ZERO);
}
