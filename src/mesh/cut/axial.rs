//! Openings in a straight course, marched once per placement across its axis.
//!
//! A course is a cross-section swept straight along its axis (part-frame Z).
//! Moving a nozzle along that axis, to a new elevation or because a course
//! below got longer, moves its neck–host loop by the same translation and
//! changes nothing else. `opening::cut_opening` therefore marches such a loop
//! on a canonical copy of the host: the same cross-section, with the nozzle
//! moved along the axis to 0. It then places the result where the nozzle is
//! ([`AxialCut::place`]):
//! - the points move along the axis;
//! - the host v is read off each point's axial coordinate;
//! - the neck (u, v) and the host u stay as they are.
//!
//! A reinforcing pad's patch is the canonical host itself, moved into the
//! nozzle's frame, trimmed by the canonical loops ([`AxialCut::pad_cut`]). It
//! too is the same wherever the nozzle sits along the axis, so a pad moved along
//! the course keeps its mesh.
//!
//! The canonical march depends only on the cross-section, the nozzle's
//! placement across the axis, its neck (for a plain neck, only the canonical neck
//! of `mesh::reach`, whatever the projection), its pad and the tolerance. So the Geometry stage keeps
//! the [`AxialCut`] and, for an opening that only moved along the axis, places
//! it again without marching. The result has the very bits a fresh cut gives, so
//! the incremental model stays byte-identical to a full build. The neck's region
//! is then unchanged too, and the Tessellate stage shares its old mesh.

use crate::mesh::store::Key;
use std::sync::Arc;

use glam::{DAffine3, DVec2, DVec3, DVec4};

use super::error::{CutError, CutLoop};
use super::outcome::{Cut, PAD_PATCH, PadCut};
use super::seams::HostTrim;
use super::turn::{Turn, is_round, round_u, split_turn};
use crate::mesh::surface::Extrusion;
use crate::nurbs::intersect::IntersectionLoop;
use crate::nurbs::{KnotVector, NurbsSurface};
use crate::parts::Patch;

/// A 128-bit key of everything a canonical cut depends on besides the neck, the
/// pad and the tolerance: the host's cross-section (u knots, x·w, y·w, w of its
/// control points, which way v runs) and the nozzle's placement across the axis,
/// all by their exact bits (a [`Key`], like [`mesh_key`](crate::mesh::mesh_key)):
/// different inputs collide with probability about 2⁻¹²⁸.
fn key(surface: &NurbsSurface, ext: &Extrusion, across: &DAffine3, turned: bool) -> u128 {
    let knots = surface.u_knots();
    let mut key = Key::with_capacity(knots.len() + 3 * surface.homogeneous_points().len() / 2 + 16);
    let mut write = |x: u64| key.write(x);
    write(knots.degree() as u64);
    write(knots.len() as u64);
    knots.as_slice().iter().for_each(|k| write(k.to_bits()));
    for row in surface.homogeneous_points().chunks_exact(2) {
        for x in [row[0].x, row[0].y, row[0].w] {
            write(x.to_bits());
        }
    }
    write(u64::from(ext.z1 > ext.z0));
    write(u64::from(turned));
    for x in across.to_cols_array() {
        write(x.to_bits());
    }
    key.finish()
}

/// The nozzle's placement in the host split into its part along the axis (`t`)
/// and the rest (`across`, the placement with its axial translation zeroed):
/// `relative = translate(t·Z) · across`, exactly.
fn split_placement(relative: &DAffine3) -> (DAffine3, f64) {
    let t = relative.translation.z;
    let mut across = *relative;
    across.translation.z = 0.0;
    (across, t)
}

/// A nozzle's placement in its host part (`host_frame⁻¹ · nozzle_frame`) as a
/// cut in a straight course takes it: a canonical placement across the axis,
/// turned about the axis (in a round course, see `mesh::turn`) and moved `t`
/// along it.
#[derive(Clone, Copy, Debug)]
pub(super) struct Placement {
    /// The placement the loops are marched with: across the axis, turned to
    /// face −X and snapped in a round course.
    pub canonical: DAffine3,
    /// The turn from the canonical placement to the nozzle's, in a round course.
    pub turn: Option<Turn>,
    /// The move along the axis.
    pub t: f64,
}

impl Placement {
    /// The placement `relative` in a host part of `host_patches`: turned when
    /// every one is a round course (a turn about the axis maps the whole host
    /// onto itself) and the nozzle's axis does not run along the course's.
    pub fn of(relative: &DAffine3, host_patches: &[&Patch]) -> Self {
        let (across, t) = split_placement(relative);
        let round = !host_patches.is_empty()
            && host_patches
                .iter()
                .all(|p| Extrusion::of(&p.surface).is_some() && is_round(&p.surface));
        match round.then(|| split_turn(&across)).flatten() {
            Some((canonical, turn)) => Self {
                canonical,
                turn: Some(turn),
                t,
            },
            None => Self {
                canonical: across,
                turn: None,
                t,
            },
        }
    }

    /// The placement the canonical neck's reach is sized at (`mesh::reach`):
    /// the nozzle's own (`relative`), or turned, the canonical one the loops
    /// are marched at (its reach is the same whatever way the nozzle faces).
    pub fn sized_at(&self, relative: &DAffine3) -> DAffine3 {
        if self.turn.is_some() {
            self.canonical
        } else {
            *relative
        }
    }
}

/// The key of the canonical march of an opening at `placement` in the course
/// `surface` (an extrusion `ext`), besides the neck, pad and tolerance.
pub(super) fn cut_key(surface: &NurbsSurface, ext: &Extrusion, placement: &Placement) -> u128 {
    key(surface, ext, &placement.canonical, placement.turn.is_some())
}

/// The canonical host for a nozzle whose placed neck (and pad) span the axial
/// range `zs`: the cross-section of `surface` swept over that range widened by
/// its own length and 1 mm on each side, v over [0, 1] running the same way as in
/// `surface`. The loop lies on the neck, so within the neck's control net and
/// well inside this host.
pub(super) fn canonical_host(
    surface: &NurbsSurface,
    ext: &Extrusion,
    zs: (f64, f64),
) -> Result<NurbsSurface, CutError> {
    let margin = (zs.1 - zs.0) + 1.0;
    let (lo, hi) = (zs.0 - margin, zs.1 + margin);
    let (a, b) = if ext.z1 > ext.z0 { (lo, hi) } else { (hi, lo) };
    let points = surface
        .homogeneous_points()
        .chunks_exact(2)
        .flat_map(|row| {
            let p = row[0];
            [
                DVec4::new(p.x, p.y, a * p.w, p.w),
                DVec4::new(p.x, p.y, b * p.w, p.w),
            ]
        })
        .collect();
    let construction = |source| CutError::Construction {
        what: "the course's canonical copy",
        source,
    };
    let v = KnotVector::try_new(1, vec![0.0, 0.0, 1.0, 1.0]).map_err(construction)?;
    NurbsSurface::try_new(surface.u_knots().clone(), v, points).map_err(construction)
}

/// The axial range of the control nets of `surfaces`.
pub(super) fn axial_range<'a>(surfaces: impl IntoIterator<Item = &'a NurbsSurface>) -> (f64, f64) {
    surfaces
        .into_iter()
        .flat_map(|s| s.homogeneous_points().iter().map(|p| p.z / p.w))
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), z| {
            (lo.min(z), hi.max(z))
        })
}

/// An opening's loops marched on a course's canonical host (see the module
/// documentation), kept to place it again when the nozzle only moves along the
/// course's axis.
#[derive(Clone, Debug, PartialEq)]
pub struct AxialCut {
    /// The host patch it was cut in, by index among the host part's patches.
    host: usize,
    /// See [`key`].
    key: u128,
    /// The axial range of the placed neck's (and pad's) control nets, which sizes
    /// the canonical host.
    zs: (f64, f64),
    /// The neck's loop on the canonical host.
    neck: Arc<IntersectionLoop>,
    /// The pad's outer loop on the canonical host.
    pad: Option<Arc<IntersectionLoop>>,
    /// The key of the canonical neck it was marched on (`mesh::reach`): a
    /// nozzle whose plain neck only changed length is marched on the same one.
    reach: Option<(u64, u64)>,
}

impl AxialCut {
    /// A cut of host patch `host` (an extrusion `ext`) from loops marched on its
    /// canonical host (sized by `zs`) with the nozzle placed at
    /// `placement.canonical`.
    pub(super) fn new(
        host: usize,
        surface: &NurbsSurface,
        ext: &Extrusion,
        placement: &Placement,
        zs: (f64, f64),
        (neck, pad): (IntersectionLoop, Option<IntersectionLoop>),
        reach: Option<(u64, u64)>,
    ) -> Self {
        Self {
            host,
            key: cut_key(surface, ext, placement),
            zs,
            neck: Arc::new(neck),
            pad: pad.map(Arc::new),
            reach,
        }
    }

    /// The key of the neck it was marched on (its radius and height, bit for
    /// bit), when that was a canonical neck (see `mesh::reach`).
    pub fn reach(&self) -> Option<(u64, u64)> {
        self.reach
    }

    /// The reinforcing pad's patch, if the nozzle has a pad: the canonical host
    /// of `host` moved into the nozzle's frame (`canonical⁻¹`), trimmed by the
    /// canonical pad and neck loops, whose host (u, v) are its own. The same
    /// wherever the nozzle sits along the axis (and, in a round course, whatever
    /// way it faces).
    pub(super) fn pad_cut(
        &self,
        host: &Patch,
        placement: &Placement,
    ) -> Result<Option<PadCut>, CutError> {
        let Some(outer) = &self.pad else {
            return Ok(None);
        };
        let ext = Extrusion::of(&host.surface).ok_or(CutError::NotACourse { patch: host.name })?;
        let into_nozzle = placement.canonical.inverse();
        let surface = canonical_host(&host.surface, &ext, self.zs)?
            .transformed(&into_nozzle)
            .map_err(CutError::Placement)?;
        Ok(Some(PadCut {
            patch: Patch::new(PAD_PATCH, surface, host.analytic.transformed(&into_nozzle)),
            outer: outer.clone(),
            inner: self.neck.clone(),
        }))
    }

    /// The host patch index it was cut in.
    pub(super) fn host(&self) -> usize {
        self.host
    }

    /// Whether this cut applies to a nozzle at `placement` in host patch
    /// `surface` (same cross-section, same canonical placement, bit for bit, by
    /// [`key`]).
    pub(super) fn fits(&self, surface: &NurbsSurface, placement: &Placement) -> bool {
        Extrusion::of(surface).is_some_and(|ext| cut_key(surface, &ext, placement) == self.key)
    }

    /// The opening in host patch `host` with the nozzle at `placement`
    /// (turned and moved from the canonical one), or
    /// [`CutError::PastCourseEnd`] when a loop does not lie strictly within the
    /// patch's v-domain (it crosses an end of the course). `host` is a straight
    /// course ([`fits`](Self::fits)).
    pub(super) fn place(&self, host: &Patch, placement: &Placement) -> Result<Cut, CutError> {
        let ext = Extrusion::of(&host.surface).ok_or(CutError::NotACourse { patch: host.name })?;
        let past_end = |which| {
            move |z| CutError::PastCourseEnd {
                which,
                patch: host.name,
                z,
                z0: ext.z0.min(ext.z1),
                z1: ext.z0.max(ext.z1),
            }
        };
        let neck = placed(&self.neck, &ext, placement).map_err(past_end(CutLoop::Neck))?;
        let pad = match self.pad.as_deref() {
            Some(p) => Some(placed(p, &ext, placement).map_err(past_end(CutLoop::Pad))?),
            None => None,
        };
        Ok(Cut {
            hosts: vec![(self.host, HostTrim::Hole)],
            neck,
            pad,
        })
    }

    /// Its loops on the canonical host (shared with the pad's trim, if any), for
    /// counting memory.
    pub fn loops(&self) -> impl Iterator<Item = &Arc<IntersectionLoop>> {
        std::iter::once(&self.neck).chain(&self.pad)
    }
}

/// `canonical` turned and moved along the axis as `placement` says onto the
/// extrusion `ext`, or the axial coordinate of the first point that falls
/// outside its v-domain.
///
/// Turned, a point's host u is its new angle's (the first in the domain, each
/// later one unwrapped next to the one before, as the marcher keeps them).
fn placed(
    canonical: &IntersectionLoop,
    ext: &Extrusion,
    placement: &Placement,
) -> Result<IntersectionLoop, f64> {
    let t = placement.t;
    let points: Vec<DVec3> = match placement.turn {
        Some(turn) => canonical
            .points
            .iter()
            .map(|&p| turn.point(p) + DVec3::new(0.0, 0.0, t))
            .collect(),
        None => canonical
            .points
            .iter()
            .map(|p| DVec3::new(p.x, p.y, p.z + t))
            .collect(),
    };
    let mut host_uv = Vec::with_capacity(points.len());
    let mut last: Option<f64> = None;
    for (uv, p) in canonical.host_uv.iter().zip(&points) {
        let v = ext.v_at(p.z);
        let u = match placement.turn {
            Some(_) => {
                let u = round_u(*p);
                let u = last.map_or(u, |l| u + (l - u).round());
                last = Some(u);
                u
            }
            None => uv.x,
        };
        if !ext.holds(v) {
            return Err(p.z);
        }
        host_uv.push(DVec2::new(u, v));
    }
    Ok(IntersectionLoop {
        points,
        neck_uv: canonical.neck_uv.clone(),
        host_uv,
    })
}

#[cfg(test)]
mod tests {
    use std::sync::Arc;

    use glam::{DAffine3, DVec3};

    use super::Extrusion;
    use crate::mesh::cut::opening::{ReusableCut, cut_opening_reusing};
    use crate::mesh::test_parts::{OD, course, frame};
    use crate::nurbs::intersect::IntersectionLoop;
    use crate::parts::Patch;
    use crate::parts::heads::{Head, HeadKind};

    const TOLERANCE: f64 = 1.0;

    fn neck() -> Patch {
        crate::mesh::test_parts::neck(1400.0)
    }

    fn cut(
        frame: &DAffine3,
        pad: bool,
        kept: Option<&Arc<super::AxialCut>>,
    ) -> Result<ReusableCut, super::CutError> {
        let (neck, course) = (neck(), course());
        cut_opening_reusing(
            &neck,
            pad.then_some(450.0),
            frame,
            &DAffine3::IDENTITY,
            &[&course],
            TOLERANCE,
            kept,
        )
    }

    /// Every point of `l` lies on the course's cylinder, on the host surface at
    /// its host (u, v) and on the placed neck at its neck (u, v).
    fn assert_on_both(l: &IntersectionLoop, neck: &crate::nurbs::NurbsSurface) {
        let host = course();
        let eps = 1e-9 * OD;
        for k in 0..l.points.len() {
            let p = l.points[k];
            let r = DVec3::new(p.x, p.y, 0.0).length();
            assert!(
                (r - OD / 2.0).abs() <= eps,
                "off the cylinder by {}",
                r - OD / 2.0
            );
            let h = host.surface.point(l.host_uv[k].x, l.host_uv[k].y);
            assert!(h.distance(p) <= eps, "host (u, v) off by {}", h.distance(p));
            let n = neck.point(l.neck_uv[k].x, l.neck_uv[k].y);
            assert!(n.distance(p) <= eps, "neck (u, v) off by {}", n.distance(p));
        }
    }

    #[test]
    fn a_course_is_an_extrusion_and_a_head_is_not() {
        let ext = Extrusion::of(&course().surface).expect("a course is swept along Z");
        assert_eq!((ext.z0, ext.z1, ext.v), (0.0, 3000.0, (0.0, 1.0)));
        let head = Head::new(OD, HeadKind::TWO_TO_ONE).with_straight_flange(50.0);
        for p in head.patches().unwrap() {
            // The straight flange is a short cylinder: an extrusion like a course.
            let swept = Extrusion::of(&p.surface).is_some();
            assert_eq!(swept, p.name == "straight flange", "{}", p.name);
        }
    }

    #[test]
    fn a_cut_moved_along_the_axis_is_placed_bit_for_bit() {
        // Radial, and off-centre and inclined (a hillside nozzle leaning up).
        let placements = [
            (DVec3::ZERO, DVec3::new(0.6, 0.8, 0.0)),
            (DVec3::new(-120.0, 90.0, 0.0), DVec3::new(0.8, -0.6, 0.3)),
        ];
        for (offset, axis) in placements {
            for pad in [false, true] {
                let at = |z: f64| frame(offset + DVec3::new(0.0, 0.0, z), axis);
                let first = cut(&at(1500.0), pad, None).unwrap();
                assert!(!first.reused);
                let kept = first
                    .axial
                    .clone()
                    .expect("a course keeps its canonical cut");
                for z in [1100.0, 1500.0, 2345.678] {
                    let fresh = cut(&at(z), pad, None).unwrap();
                    let placed = cut(&at(z), pad, Some(&kept)).unwrap();
                    assert!(placed.reused, "moved along the axis: placed, not marched");
                    assert_eq!(placed.cut, fresh.cut, "pad {pad}, z {z}");
                    let bits = |l: &IntersectionLoop| {
                        l.points
                            .iter()
                            .flat_map(|p| p.to_array().map(f64::to_bits))
                            .collect::<Vec<_>>()
                    };
                    assert_eq!(bits(&placed.cut.neck), bits(&fresh.cut.neck));
                    let neck = neck().surface.transformed(&at(z)).unwrap();
                    assert_on_both(&placed.cut.neck, &neck);
                    assert_eq!(placed.cut.pad.is_some(), pad);
                    // The pad's patch and trim are the same at every elevation,
                    // and its loops, evaluated on it and moved out of the nozzle's
                    // frame, land on the placed loops' points.
                    assert_eq!(placed.pad, first.pad);
                    assert_eq!(placed.pad, fresh.pad);
                    if let Some(p) = &placed.pad {
                        let outer = placed.cut.pad.as_ref().unwrap();
                        for (trim, placed) in [(&p.outer, outer), (&p.inner, &placed.cut.neck)] {
                            for (uv, point) in trim.host_uv.iter().zip(&placed.points) {
                                let on_pad =
                                    at(z).transform_point3(p.patch.surface.point(uv.x, uv.y));
                                assert!(on_pad.distance(*point) <= 1e-9 * OD);
                            }
                        }
                    }
                }
            }
        }
    }

    #[test]
    fn a_moved_loop_is_the_marched_loop_on_the_real_course() {
        // The canonical march agrees with a march on the course itself: every
        // sample of one lies on the other's curve (both within the tolerance of
        // the exact intersection, sampled alike).
        let at = frame(DVec3::new(0.0, 0.0, 900.0), DVec3::new(0.0, -1.0, 0.0));
        let placed = cut(&at, false, None).unwrap().cut.neck;
        let neck = neck().surface.transformed(&at).unwrap();
        let direct =
            crate::nurbs::neck_host_intersection(&neck, &course().surface, TOLERANCE).unwrap();
        assert_on_both(&placed, &neck);
        for p in &placed.points {
            let nearest = direct
                .points
                .windows(2)
                .map(|w| {
                    let (a, b) = (w[0], w[1]);
                    let t = ((*p - a).dot(b - a) / (b - a).length_squared()).clamp(0.0, 1.0);
                    p.distance(a + (b - a) * t)
                })
                .fold(f64::INFINITY, f64::min);
            assert!(nearest <= TOLERANCE, "{nearest} mm from the direct loop");
        }
    }

    #[test]
    fn a_loop_past_the_course_end_is_not_placed() {
        let axis = DVec3::new(1.0, 0.0, 0.0);
        let first = cut(&frame(DVec3::new(0.0, 0.0, 1500.0), axis), true, None).unwrap();
        let kept = first.axial.unwrap();
        // The 8 in neck (pad 450 mm) at 150 mm runs past the course's bottom.
        let low = frame(DVec3::new(0.0, 0.0, 150.0), axis);
        let course = course();
        let placement = super::Placement::of(&low, &[&course]);
        assert!(matches!(
            kept.place(&course, &placement),
            Err(super::CutError::PastCourseEnd { .. })
        ));
        let fresh = cut(&low, true, None);
        let reusing = cut(&low, true, Some(&kept));
        assert!(
            fresh.is_err() && reusing.is_err(),
            "{fresh:?} / {reusing:?}"
        );
        let err = fresh.unwrap_err();
        assert_eq!(err, reusing.unwrap_err());
        // Typed: the pad's loop (radius 225 mm at 150 mm) leaves the course
        // below its start, and the message says what to change.
        let super::CutError::PastCourseEnd {
            which,
            patch,
            z,
            z0,
            z1,
        } = &err
        else {
            panic!("{err}");
        };
        assert_eq!((*which, *patch), (super::CutLoop::Pad, course.name));
        assert!(*z < *z0 && (*z0, *z1) == (0.0, 3000.0), "{err}");
        assert!(err.to_string().contains("move the nozzle"), "{err}");
    }

    #[test]
    fn a_turned_nozzle_is_placed_bit_for_bit() {
        // Radial, and off-centre and inclined (a hillside nozzle leaning up).
        let placements = [
            (DVec3::ZERO, DVec3::new(1.0, 0.0, 0.0)),
            (DVec3::new(-120.0, 90.0, 0.0), DVec3::new(0.8, -0.6, 0.3)),
        ];
        for (offset, axis) in placements {
            for pad in [false, true] {
                let at = |angle: f64, z: f64| {
                    let (s, c) = angle.sin_cos();
                    let turn = |v: DVec3| DVec3::new(c * v.x - s * v.y, s * v.x + c * v.y, v.z);
                    frame(turn(offset) + DVec3::new(0.0, 0.0, z), turn(axis))
                };
                let first = cut(&at(0.0, 1500.0), pad, None).unwrap();
                let kept = first.axial.clone().unwrap();
                // Every way round, the seam's side included.
                for (angle, z) in [(0.3, 1500.0), (2.0, 1200.0), (3.1, 1500.0), (-1.4, 1700.0)] {
                    let fresh = cut(&at(angle, z), pad, None).unwrap();
                    let placed = cut(&at(angle, z), pad, Some(&kept)).unwrap();
                    assert!(placed.reused, "turned {angle}: placed, not marched");
                    assert_eq!(placed.cut, fresh.cut, "turned {angle}, pad {pad}");
                    let neck = neck().surface.transformed(&at(angle, z)).unwrap();
                    assert_on_both(&placed.cut.neck, &neck);
                    // The neck's (u, v) and the pad's patch and trim do not turn.
                    assert_eq!(placed.cut.neck.neck_uv, first.cut.neck.neck_uv);
                    assert_eq!(placed.pad, first.pad);
                    if let Some(p) = &placed.pad {
                        let outer = placed.cut.pad.as_ref().unwrap();
                        for (trim, placed) in [(&p.outer, outer), (&p.inner, &placed.cut.neck)] {
                            for (uv, point) in trim.host_uv.iter().zip(&placed.points) {
                                let on_pad = at(angle, z)
                                    .transform_point3(p.patch.surface.point(uv.x, uv.y));
                                assert!(on_pad.distance(*point) <= 1e-9 * OD);
                            }
                        }
                    }
                }
            }
        }
    }
}
