//! Affine maps and parallel projections of curves and surfaces.
//!
//! Part builders make patches in the part's local frame; placing a part in the
//! vessel or plant frame, and the drawing views' parallel projections onto a sheet
//! plane, map those patches here. Rational B-splines are affinely invariant: mapping
//! the Euclidean control points and keeping the weights maps every point of the
//! geometry, so `transformed(S)(u, v) == T(S(u, v))` exactly up to rounding.
//! Perspective maps (which would change weights) are not offered.

use glam::{DAffine3, DVec3, DVec4};

use super::builders::{direction, finite_vec};
use super::{NurbsCurve, NurbsError, NurbsSurface, euclidean, homogeneous};

/// Smallest |cosine| between a projection direction and the plane normal. Below it
/// the direction counts as parallel to the plane: a point would move more than 10⁹
/// times its distance from the plane.
pub const MIN_PROJECTION_COSINE: f64 = 1e-9;

/// The parallel (oblique or orthographic) projection onto the plane through
/// `plane_point` with normal `plane_normal`, along `direction`:
/// `P′ = P + (N·(Q − P)) / (N·W) · W` (thesis §4.1.3.3).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ParallelProjection {
    plane_point: DVec3,
    plane_normal: DVec3,
    direction: DVec3,
}

impl ParallelProjection {
    /// Validates and builds the projection. Errors if a vector is non-finite, the
    /// normal or direction is zero, or the direction is parallel to the plane
    /// (|cos| below [`MIN_PROJECTION_COSINE`]).
    pub fn try_new(
        plane_point: DVec3,
        plane_normal: DVec3,
        projection_direction: DVec3,
    ) -> Result<Self, NurbsError> {
        let plane_point = finite_vec("projection plane point", plane_point)?;
        let plane_normal = direction("projection plane normal", plane_normal)?;
        let projection_direction = direction("projection direction", projection_direction)?;
        let cosine = plane_normal.dot(projection_direction);
        if cosine.abs() < MIN_PROJECTION_COSINE {
            return Err(NurbsError::ProjectionParallelToPlane { cosine });
        }
        Ok(Self {
            plane_point,
            plane_normal,
            direction: projection_direction,
        })
    }

    /// The orthographic projection onto the plane (direction = normal).
    pub fn orthographic(plane_point: DVec3, plane_normal: DVec3) -> Result<Self, NurbsError> {
        Self::try_new(plane_point, plane_normal, plane_normal)
    }

    /// A point of the target plane.
    #[inline]
    pub fn plane_point(&self) -> DVec3 {
        self.plane_point
    }

    /// Unit normal of the target plane.
    #[inline]
    pub fn plane_normal(&self) -> DVec3 {
        self.plane_normal
    }

    /// Unit projection direction.
    #[inline]
    pub fn direction(&self) -> DVec3 {
        self.direction
    }

    /// The projection of one point: `P + (N·(Q − P)) / (N·W) · W`.
    #[inline]
    pub fn project_point(&self, p: DVec3) -> DVec3 {
        let n = self.plane_normal;
        p + self.direction * (n.dot(self.plane_point - p) / n.dot(self.direction))
    }

    /// The projection as an affine map `(I − W Nᵀ / (N·W)) P + W (N·Q) / (N·W)`.
    pub fn to_affine(&self) -> DAffine3 {
        let (n, w) = (self.plane_normal, self.direction);
        let s = 1.0 / n.dot(w);
        let matrix = glam::DMat3::IDENTITY
            - glam::DMat3::from_cols(w * (n.x * s), w * (n.y * s), w * (n.z * s));
        DAffine3::from_mat3_translation(matrix, w * (n.dot(self.plane_point) * s))
    }
}

/// Errors unless every entry of `transform` is finite.
fn check_affine(transform: &DAffine3) -> Result<(), NurbsError> {
    let entries = transform.to_cols_array();
    match entries.iter().find(|e| !e.is_finite()) {
        None => Ok(()),
        Some(&value) => Err(NurbsError::InvalidGeometry {
            what: "affine transform entry",
            value,
            rule: "must be finite",
        }),
    }
}

/// A homogeneous point mapped by an affine transform, its weight kept:
/// `(M (w p) + w t, w)`.
#[inline]
fn transform_homogeneous(transform: &DAffine3, p: DVec4) -> DVec4 {
    (transform.matrix3 * p.truncate() + transform.translation * p.w).extend(p.w)
}

/// A homogeneous point projected, its weight kept.
#[inline]
fn project_homogeneous(projection: &ParallelProjection, p: DVec4) -> DVec4 {
    homogeneous(projection.project_point(euclidean(p)), p.w)
}

/// What transforms and projections need of a curve or surface: its homogeneous
/// control points, and the same shape over other points.
trait ControlNet: Sized {
    fn net(&self) -> &[DVec4];
    fn with_net(&self, points: Vec<DVec4>) -> Result<Self, NurbsError>;

    /// The shape with every homogeneous control point mapped by `f`.
    fn map_net(&self, f: impl Fn(DVec4) -> DVec4) -> Result<Self, NurbsError> {
        self.with_net(self.net().iter().map(|&p| f(p)).collect())
    }
}

impl ControlNet for NurbsCurve {
    fn net(&self) -> &[DVec4] {
        self.homogeneous_points()
    }

    fn with_net(&self, points: Vec<DVec4>) -> Result<Self, NurbsError> {
        NurbsCurve::try_new(self.knots().clone(), points)
    }
}

impl ControlNet for NurbsSurface {
    fn net(&self) -> &[DVec4] {
        self.homogeneous_points()
    }

    fn with_net(&self, points: Vec<DVec4>) -> Result<Self, NurbsError> {
        NurbsSurface::try_new(self.u_knots().clone(), self.v_knots().clone(), points)
    }
}

impl NurbsCurve {
    /// The curve mapped by `transform` (control points mapped, weights kept).
    /// Errors if the transform has a non-finite entry or a mapped point overflows.
    pub fn transformed(&self, transform: &DAffine3) -> Result<NurbsCurve, NurbsError> {
        check_affine(transform)?;
        self.map_net(|p| transform_homogeneous(transform, p))
    }

    /// The curve projected by `projection` (control points projected, weights
    /// kept). Every point of the result lies on the projection plane. Errors only
    /// if a projected point overflows.
    pub fn projected(&self, projection: &ParallelProjection) -> Result<NurbsCurve, NurbsError> {
        self.map_net(|p| project_homogeneous(projection, p))
    }
}

impl NurbsSurface {
    /// The surface mapped by `transform` (control points mapped, weights kept).
    /// Errors if the transform has a non-finite entry or a mapped point overflows.
    pub fn transformed(&self, transform: &DAffine3) -> Result<NurbsSurface, NurbsError> {
        check_affine(transform)?;
        self.map_net(|p| transform_homogeneous(transform, p))
    }

    /// The surface projected by `projection` (control points projected, weights
    /// kept). Every point of the result lies on the projection plane. Errors only
    /// if a projected point overflows.
    pub fn projected(&self, projection: &ParallelProjection) -> Result<NurbsSurface, NurbsError> {
        self.map_net(|p| project_homogeneous(projection, p))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn affine_form_matches_the_formula() {
        let proj = ParallelProjection::try_new(
            DVec3::new(1.0, 2.0, 3.0),
            DVec3::new(0.2, -0.3, 1.0),
            DVec3::new(1.0, 1.0, 1.0),
        )
        .unwrap();
        let affine = proj.to_affine();
        for p in [DVec3::ZERO, DVec3::new(-40.0, 7.0, 300.0)] {
            let a = affine.transform_point3(p);
            let b = proj.project_point(p);
            assert!((a - b).length() < 1e-12 * (1.0 + p.length()), "{a} vs {b}");
            let on_plane = proj.plane_normal().dot(b - proj.plane_point());
            assert!(on_plane.abs() < 1e-12 * (1.0 + p.length()));
        }
    }
}
