//! The neck an opening is cut with: a nozzle's straight neck replaced by one whose
//! length is fixed by the host, so that the opening does not depend on the
//! nozzle's projection.
//!
//! Part of cutting an opening (`opening`), between the Geometry stage's nozzle
//! patches and the host regions laid out from the cut. A nozzle's neck runs from
//! its axis origin (z = 0) up to its hub, so its length follows the projection;
//! the loop where it meets the host does not. Marched on the neck itself, the
//! loop's samples would still differ in their last bits with the neck's length
//! (its v is z over that length), every host region it trims would get a new
//! fingerprint, and a projection edit would re-mesh the whole host course and
//! the pad. Marched on a neck of the same radius reaching just past the host
//! (the top of the host's control net in the nozzle's frame, which bounds the
//! surface), the host side of the cut is a function of the host and the
//! nozzle's placement alone, bit for bit, and only the neck's own v is rescaled
//! to the real neck afterwards.

use std::borrow::Cow;
use std::f64::consts::TAU;
use std::sync::Arc;

use glam::{DAffine3, DVec3};

use super::outcome::{Cut, PadCut};
use crate::nurbs::NurbsSurface;
use crate::nurbs::builders::{line, revolve};
use crate::nurbs::intersect::IntersectionLoop;
use crate::parts::Patch;

/// The neck to cut with.
pub(super) struct Reach<'a> {
    /// The neck itself.
    own: &'a NurbsSurface,
    /// The canonical neck's radius and height, when the neck is replaced by one
    /// (built only when a loop is marched: see [`Reach::surface`]).
    canonical: Option<(f64, f64)>,
    /// The height the pad's outside cylinder spans (in the nozzle frame).
    pub top: f64,
    /// v on the real neck per v on `surface` (1 for the neck itself).
    scale: f64,
    /// The canonical neck's radius and height, bit for bit; `None` for the
    /// neck itself.
    key: Option<(u64, u64)>,
}

impl<'a> Reach<'a> {
    /// The neck to cut `neck` with, placed by `relative` (nozzle frame → host
    /// frame) among `host_patches` (in the host frame).
    ///
    /// Where a cut may be kept and placed again along a straight course's axis
    /// (`axial_hosts`: some host patch is one), the reach must not change with
    /// that move: it does not when the neck's axis is square to the course's
    /// (every radial nozzle), and otherwise the neck is cut as it is.
    pub fn of(
        neck: &'a Patch,
        relative: &DAffine3,
        host_patches: &[&Patch],
        axial_hosts: bool,
    ) -> Self {
        let top = neck
            .surface
            .control_points()
            .iter()
            .fold(0.0f64, |m, p| m.max(p.z))
            .max(1.0);
        let own = Self {
            own: &neck.surface,
            canonical: None,
            top,
            scale: 1.0,
            key: None,
        };
        if axial_hosts && relative.transform_vector3(DVec3::Z).z != 0.0 {
            return own;
        }
        let Some(radius) = straight_radius(&neck.surface, top) else {
            return own;
        };
        // The top of the host's control net in the nozzle frame bounds the host
        // surface, hence the loop; a margin keeps the marcher's steps inside.
        let to_nozzle = relative.inverse();
        let height = host_patches
            .iter()
            .flat_map(|p| p.surface.control_points())
            .map(|p| to_nozzle.transform_point3(p).z)
            .fold(f64::NEG_INFINITY, f64::max);
        let reach = height + 0.05 * height.abs() + 1.0;
        if !(reach.is_finite() && reach > 0.0) {
            return own;
        }
        Self {
            canonical: Some((radius, reach)),
            top: reach,
            scale: reach / top,
            key: Some((radius.to_bits(), reach.to_bits())),
            ..own
        }
    }

    /// The surface the loops are marched on: the canonical neck, or the neck
    /// itself when it is not a plain cylinder from z = 0.
    pub fn surface(&self) -> Cow<'a, NurbsSurface> {
        // A radius > 0 and a finite height > 0 always make a cylinder.
        match self
            .canonical
            .and_then(|(radius, height)| cylinder(radius, height))
        {
            Some(surface) => Cow::Owned(surface),
            None => Cow::Borrowed(self.own),
        }
    }

    /// What the canonical neck is made from (its radius and height, bit for
    /// bit), when the neck was replaced by one: two necks with the same key are
    /// the same surface, whatever the real necks' lengths. `None` when the neck
    /// is cut as it is.
    pub fn key(&self) -> Option<(u64, u64)> {
        self.key
    }

    /// `cut`, marched on [`Reach::surface`], with its neck (u, v) on the real neck.
    pub fn on_neck(&self, mut cut: Cut) -> Cut {
        self.rescale(&mut cut.neck);
        cut
    }

    /// A pad's trim with its inner loop (the neck's) on the real neck.
    pub fn on_pad(&self, pad: Option<PadCut>) -> Option<PadCut> {
        pad.map(|mut p| {
            if self.scale != 1.0 {
                let mut inner = (*p.inner).clone();
                self.rescale(&mut inner);
                p.inner = Arc::new(inner);
            }
            p
        })
    }

    /// A loop's neck (u, v) moved from [`Reach::surface`] to the real neck.
    fn rescale(&self, curve: &mut IntersectionLoop) {
        if self.scale != 1.0 {
            for uv in &mut curve.neck_uv {
                uv.y *= self.scale;
            }
        }
    }
}

/// The radius of `neck` when it is exactly the nozzle's plain neck: the cylinder
/// revolved from the line (r, 0, 0)–(r, 0, `top`) about Z.
fn straight_radius(neck: &NurbsSurface, top: f64) -> Option<f64> {
    let first = *neck.control_points().first()?;
    let rebuilt = cylinder(first.x, top)?;
    (first.x > 0.0 && rebuilt == *neck).then_some(first.x)
}

/// The cylinder of `radius` about Z from z = 0 to `height`, built as the nozzle
/// profile builds its neck.
fn cylinder(radius: f64, height: f64) -> Option<NurbsSurface> {
    let generator = line(
        DVec3::new(radius, 0.0, 0.0),
        DVec3::new(radius, 0.0, height),
    )
    .ok()?;
    revolve(&generator, DVec3::ZERO, DVec3::Z, TAU).ok()
}

#[cfg(test)]
mod tests {
    use glam::{DAffine3, DVec3};

    use super::Reach;
    use crate::mesh::cut::opening::cut_opening;
    use crate::mesh::test_parts::{OD, course, frame, neck, nozzle};
    use crate::parts::Patch;
    use crate::parts::heads::{Head, HeadKind};

    #[test]
    fn a_radial_opening_is_the_same_on_the_host_for_any_projection() {
        let host = course();
        // Radial, on the axis at mid-height; and off the axis (a hillside nozzle).
        for origin in [
            DVec3::new(0.0, 0.0, 1500.0),
            DVec3::new(-150.0, 0.0, 1200.0),
        ] {
            let at = frame(origin, DVec3::new(0.6, 0.8, 0.0));
            let cuts: Vec<_> = [1300.0, 1400.0, 1750.0]
                .into_iter()
                .map(|projection| {
                    let neck = neck(projection);
                    let cut =
                        cut_opening(&neck, Some(450.0), &at, &DAffine3::IDENTITY, &[&host], 1.0)
                            .unwrap();
                    (neck, cut)
                })
                .collect();
            let (_, first) = &cuts[0];
            for (neck, cut) in &cuts {
                // The host side and the pad's loop, bit for bit.
                assert_eq!(cut.neck.host_uv, first.neck.host_uv);
                assert_eq!(cut.neck.points, first.neck.points);
                assert_eq!(cut.pad, first.pad);
                // The neck's (u, v) are on this neck, whatever its length.
                let placed = neck.surface.transformed(&at).unwrap();
                for (p, uv) in cut.neck.points.iter().zip(&cut.neck.neck_uv) {
                    let on = placed.point(uv.x, uv.y);
                    assert!(
                        on.distance(*p) <= 1e-9 * OD,
                        "off the neck by {}",
                        on.distance(*p)
                    );
                    assert!((0.0..=1.0).contains(&uv.y), "v {} off the neck", uv.y);
                }
            }
        }
    }

    #[test]
    fn only_a_plain_neck_square_to_a_course_is_replaced() {
        let host = course();
        let plain = neck(1400.0);
        let radial = frame(DVec3::new(0.0, 0.0, 1500.0), DVec3::X);
        let reach = Reach::of(&plain, &radial, &[&host], true);
        assert!(reach.surface().as_ref() != &plain.surface);
        // A leaning neck in a course: moved along the axis, its reach would
        // change, so it is cut as it is.
        let leaning = frame(DVec3::new(0.0, 0.0, 1500.0), DVec3::new(0.8, 0.0, 0.6));
        let reach = Reach::of(&plain, &leaning, &[&host], true);
        assert!(reach.surface().as_ref() == &plain.surface);
        // On a head (no straight course), any neck of the nozzle's form is.
        let head = Head::new(OD, HeadKind::TWO_TO_ONE).patches().unwrap();
        let hosts: Vec<&Patch> = head.iter().collect();
        let up = DAffine3::from_translation(DVec3::new(300.0, 0.0, 0.0));
        let reach = Reach::of(&plain, &up, &hosts, false);
        assert!(reach.surface().as_ref() != &plain.surface);
        // Another patch of the nozzle (the hub, a cone) is not a plain neck.
        let hub = nozzle(1400.0).patches().unwrap().remove(1);
        let reach = Reach::of(&hub, &radial, &[&host], true);
        assert!(reach.surface().as_ref() == &hub.surface);
    }
}
