//! Clearances between nozzle bodies: the neck from where it meets its host to
//! the back of its flange, and the flange from there to the gasket face, each
//! a solid cylinder along the nozzle's axis. Two nozzles whose openings are
//! apart can still collide outside the vessel — a flange reaching over a
//! neighbour's neck or flange (the storage tank's N2 and N4, 8″ and 3″ at one
//! orientation 250 mm apart in elevation, overlapped by 17 mm) — which
//! `footprints` cannot see.
//!
//! Two finite solid cylinders are convex, so whether they meet is decided by
//! alternating projections (projecting onto a finite solid cylinder is a clamp
//! of the axial coordinate and of the radius, exact): the iterates approach a
//! common point when the solids meet, and a pair of closest points otherwise,
//! each gap found an upper bound of the true distance. The same test holds for
//! any two closed convex solids known by their nearest-point projection
//! ([`Convex`]): boxes ([`Block`], a support's plate or lug) and balls ([`Ball`],
//! an opening's footprint) too.

use glam::DVec3;

/// A solid cylinder: the points within `radius` of the axis through `origin`
/// along `axis` (unit), between `from` and `to` along it, mm (vessel frame).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Body {
    /// What it is, for messages: `"flange"`, `"neck"`.
    pub name: &'static str,
    /// A point of the axis.
    pub origin: DVec3,
    /// The unit axis.
    pub axis: DVec3,
    /// Start along the axis from `origin`.
    pub from: f64,
    /// End along the axis from `origin`.
    pub to: f64,
    /// Radius.
    pub radius: f64,
}

/// Alternating projections made at most.
const STEPS: usize = 400;
/// A gap below this (mm) is contact.
const CONTACT: f64 = 1e-6;

/// A closed convex solid, known by its nearest-point projection.
pub(crate) trait Convex {
    /// A point of the solid and the radius of a ball round it holding the solid.
    fn bound(&self) -> (DVec3, f64);

    /// The point of the solid nearest `p`.
    fn project(&self, p: DVec3) -> DVec3;
}

/// Whether two convex solids share a point (within [`CONTACT`]), by
/// alternating projections from the middle of their bounding balls' centres.
pub(crate) fn meet(a: &dyn Convex, b: &dyn Convex) -> bool {
    let ((ca, ra), (cb, rb)) = (a.bound(), b.bound());
    if (ca - cb).length() >= ra + rb {
        return false;
    }
    let mut p = 0.5 * (ca + cb);
    for _ in 0..STEPS {
        let q = a.project(p);
        let r = b.project(q);
        if (q - r).length() <= CONTACT {
            return true;
        }
        if (r - p).length() <= 1e-12 * (1.0 + p.length()) {
            // A fixed point with a gap: the closest points, apart.
            return false;
        }
        p = r;
    }
    false
}

/// A box: the points within `half[k]` of `centre` along each of the
/// orthonormal `axes[k]`, mm (vessel frame).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Block {
    /// Its centre.
    pub centre: DVec3,
    /// Three orthonormal directions.
    pub axes: [DVec3; 3],
    /// Half its size along each axis.
    pub half: [f64; 3],
}

impl Convex for Block {
    fn bound(&self) -> (DVec3, f64) {
        let [a, b, c] = self.half;
        (self.centre, (a * a + b * b + c * c).sqrt())
    }

    fn project(&self, p: DVec3) -> DVec3 {
        let d = p - self.centre;
        self.axes
            .iter()
            .zip(self.half)
            .fold(self.centre, |q, (axis, h)| {
                q + *axis * d.dot(*axis).clamp(-h, h)
            })
    }
}

/// A ball (an opening's footprint).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Ball {
    /// Its centre.
    pub centre: DVec3,
    /// Its radius.
    pub radius: f64,
}

impl Convex for Ball {
    fn bound(&self) -> (DVec3, f64) {
        (self.centre, self.radius)
    }

    fn project(&self, p: DVec3) -> DVec3 {
        let d = p - self.centre;
        let l = d.length();
        if l > self.radius {
            self.centre + d * (self.radius / l)
        } else {
            p
        }
    }
}

impl Convex for Body {
    fn bound(&self) -> (DVec3, f64) {
        (self.centre(), self.reach())
    }

    fn project(&self, p: DVec3) -> DVec3 {
        Body::project(self, p)
    }
}

impl Body {
    /// The centre of the cylinder.
    fn centre(&self) -> DVec3 {
        self.origin + self.axis * (0.5 * (self.from + self.to))
    }

    /// Radius of the ball round [`centre`](Self::centre) holding the cylinder.
    fn reach(&self) -> f64 {
        (0.5 * (self.to - self.from)).hypot(self.radius)
    }

    /// The point of the cylinder nearest `p`.
    fn project(&self, p: DVec3) -> DVec3 {
        let d = p - self.origin;
        let t = d.dot(self.axis);
        let radial = d - self.axis * t;
        let rho = radial.length();
        let radial = if rho > self.radius {
            radial * (self.radius / rho)
        } else {
            radial
        };
        self.origin + self.axis * t.clamp(self.from, self.to) + radial
    }

    /// Whether the two solids share a point (within [`CONTACT`]).
    pub fn meets(&self, other: &Body) -> bool {
        meet(self, other)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn along(origin: DVec3, axis: DVec3, from: f64, to: f64, radius: f64) -> Body {
        Body {
            name: "neck",
            origin,
            axis,
            from,
            to,
            radius,
        }
    }

    #[test]
    fn parallel_flanges_meet_only_when_they_overlap() {
        // Two radial nozzles at one orientation, 250 mm apart along the vessel.
        let a = along(DVec3::ZERO, DVec3::X, 4200.0, 4300.0, 171.5);
        let b = along(DVec3::new(0.0, 0.0, 250.0), DVec3::X, 4150.0, 4250.0, 95.25);
        assert!(a.meets(&b));
        let c = along(DVec3::new(0.0, 0.0, 300.0), DVec3::X, 4150.0, 4250.0, 95.25);
        assert!(!c.meets(&a));
        // Apart along the axis: no overlap however close radially.
        let d = along(DVec3::new(0.0, 0.0, 250.0), DVec3::X, 4310.0, 4400.0, 95.25);
        assert!(!a.meets(&d));
    }

    #[test]
    fn boxes_and_balls_meet_cylinders_only_when_they_overlap() {
        let plate = Block {
            centre: DVec3::new(0.0, -1100.0, 0.0),
            axes: [DVec3::X, DVec3::Y, DVec3::Z],
            half: [800.0, 100.0, 6.0],
        };
        // A drain straight down through the web's plane, and one beside it.
        let through = along(DVec3::new(0.0, 0.0, 50.0), -DVec3::Y, 1000.0, 1200.0, 60.0);
        assert!(meet(&plate, &through));
        let beside = along(DVec3::new(0.0, 0.0, 70.0), -DVec3::Y, 1000.0, 1200.0, 60.0);
        assert!(!meet(&plate, &beside));
        let ball = Ball {
            centre: DVec3::new(810.0, -1100.0, 0.0),
            radius: 10.5,
        };
        assert!(meet(&plate, &ball));
        let apart = Ball {
            radius: 9.5,
            ..ball
        };
        assert!(!meet(&apart, &plate));
    }

    #[test]
    fn crossing_and_skew_cylinders() {
        let a = along(DVec3::ZERO, DVec3::X, -100.0, 100.0, 10.0);
        let b = along(DVec3::new(0.0, 0.0, 15.0), DVec3::Y, -100.0, 100.0, 10.0);
        assert!(a.meets(&b));
        let c = along(DVec3::new(0.0, 0.0, 25.0), DVec3::Y, -100.0, 100.0, 10.0);
        assert!(!a.meets(&c));
    }
}
