//! Vessel heads: hemispherical, ellipsoidal, torispherical, toriconical, conical and
//! flat, each with an optional straight flange, as exact surfaces of revolution.
//!
//! Local frame: the axis is +Z and the origin is on the axis in the plane of the open
//! end (the seam with the shell). The straight flange runs from z = 0 to
//! z = `straight_flange`, the tangent line; the dished part rises from there towards
//! +Z. A bottom head is placed by turning this frame over.
//!
//! Each head is built as a meridian profile in the XZ half-plane (x = radius), one
//! segment per smooth piece, each revolved into its own patch. Where the real head
//! is smooth (flange–knuckle, knuckle–crown) the segments join with equal tangents,
//! so the patches meet G1.

mod conical;
mod ellipsoidal;
mod flat;
mod hemispherical;
mod profile;
mod toriconical;
mod torispherical;

use std::f64::consts::TAU;

use glam::DVec3;

use super::check::{non_negative, positive};
use super::{Analytic, PartError, Patch};
use crate::nurbs::builders::{line, revolve};
use profile::Segment;

/// The kind of a head and its shape parameters (mm, degrees).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum HeadKind {
    /// Half a sphere of the head's outside radius.
    Hemispherical,
    /// Half an ellipsoid of revolution; `ratio` = D / (2 h), 2 for the common 2:1 head.
    Ellipsoidal {
        /// Major-to-minor axis ratio D / (2 h), > 0.
        ratio: f64,
    },
    /// Torispherical (flanged and dished): a spherical crown of `crown_radius` L joined
    /// to the straight flange by a toroidal knuckle of `knuckle_radius` r.
    Torispherical {
        /// Crown radius L (outside), mm; must exceed D/2.
        crown_radius: f64,
        /// Knuckle radius r (outside), mm; 0 < r < D/2 and r < L.
        knuckle_radius: f64,
    },
    /// A cone closing to an apex, joined to the flange by a toroidal knuckle.
    Toriconical {
        /// Half-angle between axis and cone, degrees, 1 ≤ α ≤ 89.
        half_angle: f64,
        /// Knuckle radius, mm; 0 < r < D/2.
        knuckle_radius: f64,
    },
    /// A cone without knuckle, closing to an apex (`small_diameter` = 0) or truncated
    /// at `small_diameter` and closed there by a flat plate.
    Conical {
        /// Half-angle between axis and cone, degrees, 1 ≤ α ≤ 89.
        half_angle: f64,
        /// Diameter of the small end, mm; 0 for an apex, else < D.
        small_diameter: f64,
    },
    /// A flat plate; with `knuckle_radius` > 0 a flanged flat head whose knuckle turns
    /// the flange into the plate.
    Flat {
        /// Knuckle radius, mm; 0 for a plain flat plate, else < D/2.
        knuckle_radius: f64,
    },
}

impl HeadKind {
    /// The 2:1 semi-ellipsoidal head.
    pub const TWO_TO_ONE: HeadKind = HeadKind::Ellipsoidal { ratio: 2.0 };

    /// ASME flanged and dished head for an outside diameter: L = D, r = 0.06 L.
    pub fn asme_fd(outside_diameter: f64) -> HeadKind {
        HeadKind::Torispherical {
            crown_radius: outside_diameter,
            knuckle_radius: 0.06 * outside_diameter,
        }
    }

    /// The 80:10 torispherical head: L = 0.8 D, r = 0.1 D.
    pub fn eighty_ten(outside_diameter: f64) -> HeadKind {
        HeadKind::Torispherical {
            crown_radius: 0.8 * outside_diameter,
            knuckle_radius: 0.1 * outside_diameter,
        }
    }

    /// A short lowercase name, e.g. `"torispherical"`.
    pub fn name(&self) -> &'static str {
        match self {
            HeadKind::Hemispherical => "hemispherical",
            HeadKind::Ellipsoidal { .. } => "ellipsoidal",
            HeadKind::Torispherical { .. } => "torispherical",
            HeadKind::Toriconical { .. } => "toriconical",
            HeadKind::Conical { .. } => "conical",
            HeadKind::Flat { .. } => "flat",
        }
    }
}

/// A head: outside diameter, straight flange length and kind.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Head {
    /// Outside diameter D of the open end, mm (the OD of the shell it closes).
    pub outside_diameter: f64,
    /// Length of the cylindrical straight flange, mm; 0 for none.
    pub straight_flange: f64,
    /// Kind and shape parameters.
    pub kind: HeadKind,
}

impl Head {
    /// A head of `kind` on an outside diameter, without straight flange.
    pub fn new(outside_diameter: f64, kind: HeadKind) -> Self {
        Self {
            outside_diameter,
            straight_flange: 0.0,
            kind,
        }
    }

    /// The same head with a straight flange of `length` mm.
    pub fn with_straight_flange(mut self, length: f64) -> Self {
        self.straight_flange = length;
        self
    }

    /// Checks every parameter; the error names the field, its value and the rule.
    pub fn validate(&self) -> Result<(), PartError> {
        self.profile().map(|_| ())
    }

    /// The dished depth from the tangent line to the top of the head (the pole, or
    /// the small-end plate of a truncated cone), mm.
    pub fn depth(&self) -> Result<f64, PartError> {
        let segments = self.profile()?;
        let top = segments
            .iter()
            .map(|s| s.curve.end().z.max(s.curve.start().z))
            .fold(f64::NEG_INFINITY, f64::max);
        Ok(top - self.straight_flange)
    }

    /// Overall height from the open end to the top: straight flange + depth, mm.
    pub fn height(&self) -> Result<f64, PartError> {
        Ok(self.depth()? + self.straight_flange)
    }

    /// Height above the open end (z = 0) of the head's outside surface at distance
    /// `radius` from the axis (0 ≤ radius ≤ D/2): the top of the head at that
    /// radius. The meridian's radius never increases away from the open end, so
    /// this is one bisection per call.
    pub fn height_at_radius(&self, radius: f64) -> Result<f64, PartError> {
        let segments = self.profile()?;
        let radius = radius.max(0.0);
        let mut best = 0.0f64;
        for s in &segments {
            let (a, b) = s.curve.domain();
            let (ra, rb) = (s.curve.point(a).x, s.curve.point(b).x);
            let (lo_r, hi_r) = (ra.min(rb), ra.max(rb));
            if radius < lo_r - 1e-12 || radius > hi_r + 1e-12 {
                continue;
            }
            if (hi_r - lo_r).abs() <= 1e-12 {
                // A cylinder piece at this radius: its top.
                best = best.max(s.curve.point(a).z.max(s.curve.point(b).z));
                continue;
            }
            // Bisection on the parameter: radius decreases from a to b.
            let (mut lo, mut hi) = (a, b);
            for _ in 0..200 {
                let mid = 0.5 * (lo + hi);
                if s.curve.point(mid).x > radius {
                    lo = mid;
                } else {
                    hi = mid;
                }
                if hi - lo <= f64::EPSILON * (b - a) {
                    break;
                }
            }
            best = best.max(s.curve.point(0.5 * (lo + hi)).z);
        }
        Ok(best)
    }

    /// The exact patches, outward normals, from the open end (z = 0) upwards.
    pub fn patches(&self) -> Result<Vec<Patch>, PartError> {
        self.profile()?
            .into_iter()
            .map(|s| {
                let surface = revolve(&s.curve, DVec3::ZERO, DVec3::Z, TAU)?;
                Ok(Patch::new(s.name, surface, s.analytic))
            })
            .collect()
    }

    /// The meridian profile, validated: straight flange first, then the dished part.
    fn profile(&self) -> Result<Vec<Segment>, PartError> {
        let part = self.part_name();
        let d = positive(part, "outside_diameter", self.outside_diameter)?;
        let sf = non_negative(part, "straight_flange", self.straight_flange)?;
        let r = d / 2.0;
        let mut out = Vec::new();
        if sf > 0.0 {
            out.push(Segment {
                name: "straight flange",
                curve: line(DVec3::new(r, 0.0, 0.0), DVec3::new(r, 0.0, sf))?,
                analytic: Analytic::Cylinder {
                    point: DVec3::ZERO,
                    axis: DVec3::Z,
                    radius: r,
                },
            });
        }
        let dished = match self.kind {
            HeadKind::Hemispherical => hemispherical::profile(r, sf)?,
            HeadKind::Ellipsoidal { ratio } => ellipsoidal::profile(part, r, sf, ratio)?,
            HeadKind::Torispherical {
                crown_radius,
                knuckle_radius,
            } => torispherical::profile(part, r, sf, crown_radius, knuckle_radius)?,
            HeadKind::Toriconical {
                half_angle,
                knuckle_radius,
            } => toriconical::profile(part, r, sf, half_angle, knuckle_radius)?,
            HeadKind::Conical {
                half_angle,
                small_diameter,
            } => conical::profile(part, r, sf, half_angle, small_diameter)?,
            HeadKind::Flat { knuckle_radius } => flat::profile(part, r, sf, knuckle_radius)?,
        };
        out.extend(dished);
        Ok(out)
    }

    fn part_name(&self) -> &'static str {
        match self.kind {
            HeadKind::Hemispherical => "hemispherical head",
            HeadKind::Ellipsoidal { .. } => "ellipsoidal head",
            HeadKind::Torispherical { .. } => "torispherical head",
            HeadKind::Toriconical { .. } => "toriconical head",
            HeadKind::Conical { .. } => "conical head",
            HeadKind::Flat { .. } => "flat head",
        }
    }
}
