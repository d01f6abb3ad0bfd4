//! Axis-aligned bounding boxes of curves and surfaces from their control points.
//!
//! A rational B-spline with positive weights lies in the convex hull of its control
//! points, so the box of the control points contains the geometry. That box may be
//! loose (a circle's box from its 9-point polygon is the circumscribed square, exact
//! here; a strongly curved spline's control polygon can stand far off the curve) but
//! it is cheap and never too small. Broad-phase checks (nozzle clashes, view culling,
//! plant-level queries) use it before any exact geometry.

use glam::DVec3;

use super::{NurbsCurve, NurbsSurface, euclidean};

/// An axis-aligned box `[min, max]` (inclusive). [`Aabb::EMPTY`] (min = +∞,
/// max = −∞) is the box of no points and the identity of [`union`](Aabb::union).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Aabb {
    /// Smallest x, y and z.
    pub min: DVec3,
    /// Largest x, y and z.
    pub max: DVec3,
}

impl Aabb {
    /// The box containing nothing.
    pub const EMPTY: Aabb = Aabb {
        min: DVec3::INFINITY,
        max: DVec3::NEG_INFINITY,
    };

    /// The degenerate box of one point.
    #[inline]
    pub fn from_point(p: DVec3) -> Aabb {
        Aabb { min: p, max: p }
    }

    /// The smallest box containing all `points`; [`Aabb::EMPTY`] for none.
    pub fn from_points(points: impl IntoIterator<Item = DVec3>) -> Aabb {
        points.into_iter().fold(Aabb::EMPTY, Aabb::including)
    }

    /// True for a box that contains no point (such as [`Aabb::EMPTY`]).
    #[inline]
    pub fn is_empty(&self) -> bool {
        !self.min.cmple(self.max).all()
    }

    /// The smallest box containing this one and `p`.
    #[inline]
    pub fn including(self, p: DVec3) -> Aabb {
        Aabb {
            min: self.min.min(p),
            max: self.max.max(p),
        }
    }

    /// The smallest box containing both boxes.
    #[inline]
    pub fn union(&self, other: &Aabb) -> Aabb {
        Aabb {
            min: self.min.min(other.min),
            max: self.max.max(other.max),
        }
    }

    /// True if `p` lies in the box, boundary included.
    #[inline]
    pub fn contains(&self, p: DVec3) -> bool {
        self.min.cmple(p).all() && p.cmple(self.max).all()
    }

    /// True if the two boxes share at least one point.
    #[inline]
    pub fn intersects(&self, other: &Aabb) -> bool {
        self.min.cmple(other.max).all() && other.min.cmple(self.max).all()
    }

    /// Side lengths `max − min`; zero for an empty box.
    #[inline]
    pub fn extent(&self) -> DVec3 {
        if self.is_empty() {
            DVec3::ZERO
        } else {
            self.max - self.min
        }
    }

    /// Length of the diagonal; zero for an empty box.
    #[inline]
    pub fn diagonal(&self) -> f64 {
        self.extent().length()
    }

    /// Centre of the box (NaN components for an empty box).
    #[inline]
    pub fn center(&self) -> DVec3 {
        0.5 * (self.min + self.max)
    }

    /// The box grown by `margin` on every side (shrunk for a negative margin). An
    /// empty box stays empty.
    #[inline]
    pub fn expanded(&self, margin: f64) -> Aabb {
        if self.is_empty() {
            return *self;
        }
        Aabb {
            min: self.min - DVec3::splat(margin),
            max: self.max + DVec3::splat(margin),
        }
    }
}

impl NurbsCurve {
    /// Box of the Euclidean control points: contains the whole curve (convex hull
    /// property), but may be loose. Evaluated points can stand outside it by
    /// floating-point rounding (~1e-15 relative); pad with [`Aabb::expanded`] for
    /// containment tests.
    pub fn bounding_box(&self) -> Aabb {
        Aabb::from_points(self.homogeneous_points().iter().map(|&p| euclidean(p)))
    }
}

impl NurbsSurface {
    /// Box of the Euclidean control points: contains the whole surface (convex hull
    /// property), but may be loose. Evaluated points can stand outside it by
    /// floating-point rounding (~1e-15 relative); pad with [`Aabb::expanded`] for
    /// containment tests.
    pub fn bounding_box(&self) -> Aabb {
        Aabb::from_points(self.homogeneous_points().iter().map(|&p| euclidean(p)))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn empty_is_the_identity_of_union() {
        let b = Aabb::from_points([DVec3::ZERO, DVec3::new(1.0, -2.0, 3.0)]);
        assert_eq!(Aabb::EMPTY.union(&b), b);
        assert!(Aabb::EMPTY.is_empty());
        assert!(!b.is_empty());
        assert_eq!(b.extent(), DVec3::new(1.0, 2.0, 3.0));
        assert!(b.contains(DVec3::new(0.5, -1.0, 3.0)));
        assert!(!b.contains(DVec3::new(0.5, 0.5, 3.0)));
        assert!(!Aabb::EMPTY.contains(DVec3::ZERO));
        assert_eq!(Aabb::EMPTY.extent(), DVec3::ZERO);
    }
}
