//! Plates: each course cut by its longitudinal seams, with the openings that
//! fall in it developed into the plate's own coordinates and the marking
//! lines a fitter needs.
//!
//! A cylinder's plate has `x = r·(θ − θ₀)` from its first seam and `y = z −
//! z₀` from its lower joint (seen from outside, x runs counter-clockwise
//! about the part's axis). A cone's plate is an annular sector laid with its
//! bisector along +y about the apex (an eccentric reducer's, the region
//! between its developed curves, laid alike); a concentric cone's plate
//! carries its openings developed by [`super::cone_openings::develop_point`],
//! an eccentric reducer's by its own development
//! ([`super::oblique_openings::develop_loop`]).

use std::collections::BTreeMap;
use std::f64::consts::{PI, TAU};
use std::sync::Arc;

use glam::DVec2;

use super::cone_openings::{ConeSurface, develop_point};
use super::develop::{Developments, Outline, Rolled};
use super::oblique_openings::develop_loop;
use super::openings::{NozzleCut, Openings};
use super::seams::{Course, Prior, SeamLayout};

/// An opening developed onto a plate.
#[derive(Clone, Debug, PartialEq)]
pub struct PlateOpening {
    /// Nozzle mark.
    pub mark: String,
    /// The cutting contour, plate coordinates, mm.
    pub contour: Vec<DVec2>,
    /// Where the nozzle axis meets the plate's mid-surface, mm.
    pub centre: DVec2,
    /// Half-lengths of the centreline marks `(along x, along y)`, mm.
    pub reach: DVec2,
}

/// One plate of a course.
#[derive(Clone, Debug, PartialEq)]
pub struct Plate {
    /// Plate id, `C-201-S1-P2` (vessel tag, part id, number within the part).
    pub id: String,
    /// Part id.
    pub part: String,
    /// Course id, `S1-C1`.
    pub course: String,
    /// Index into [`SeamLayout::courses`].
    pub course_index: usize,
    /// Seam index in its course (the plate runs from seam `k` to `k + 1`).
    pub seam: usize,
    /// Thickness, mm.
    pub thickness: f64,
    /// The developed outline.
    pub outline: Outline,
    /// Openings in it.
    pub openings: Vec<PlateOpening>,
    /// Exact mid-surface area of its region (openings not taken off), mm².
    pub mid_area: f64,
}

impl Plate {
    /// The DXF file name, `C-201-S1-P2.dxf`.
    pub fn file_name(&self) -> String {
        format!("{}.dxf", self.id)
    }
}

/// Cuts every course into its plates.
pub fn cut_plates(
    tag: &str,
    developments: &Developments,
    openings: &Openings,
    seams: &SeamLayout,
) -> Vec<Arc<Plate>> {
    cut_plates_reusing(tag, developments, openings, seams, None).0
}

/// The cuts whose nozzle axis falls in plate `k` of `course` (cylinders
/// only: a cone's openings are cut after forming).
pub fn cuts_in<'a>(
    course: &Course,
    k: usize,
    developments: &Developments,
    openings: &'a Openings,
) -> Vec<&'a NozzleCut> {
    if !developments.rolled[course.rolled].is_cylinder() {
        return Vec::new();
    }
    let theta0 = course.seam(k);
    openings
        .all()
        .filter(|c| c.rolled == course.rolled)
        .filter(|c| axis_in_plate(c, course, theta0))
        .collect()
}

/// Whether `cut`'s nozzle axis falls in the plate of `course` that starts at
/// seam angle `theta0`.
fn axis_in_plate(cut: &NozzleCut, course: &Course, theta0: f64) -> bool {
    let rel = (cut.centre.x - theta0).rem_euclid(TAU);
    rel < course.pitch() && cut.centre.y >= course.z.0 && cut.centre.y < course.z.1
}

/// The cone openings whose nozzle axis falls in plate `k` of `course`.
pub fn cone_cuts_in<'a>(course: &Course, k: usize, openings: &'a Openings) -> Vec<&'a NozzleCut> {
    let theta0 = course.seam(k);
    openings
        .cones
        .iter()
        .filter(|c| c.rolled == course.rolled)
        .filter(|c| axis_in_plate(c, course, theta0))
        .collect()
}

/// Cone opening `cut` developed onto the plate of `course` from seam angle
/// `theta0`.
fn cone_opening(cut: &NozzleCut, rolled: &Rolled, course: &Course, theta0: f64) -> PlateOpening {
    let reach = cut.pad.as_ref().map_or(cut.cut_radius, |p| 0.5 * p.od) + 50.0;
    if let Outline::Oblique(plate) = rolled.outline(theta0, course.pitch(), course.z.0, course.z.1)
    {
        let (centre, contour) = develop_loop(&plate, cut.centre, &cut.hole);
        return PlateOpening {
            mark: cut.mark.clone(),
            contour,
            centre,
            reach: DVec2::splat(reach),
        };
    }
    let surface = ConeSurface::mid(rolled);
    let mid = theta0 + 0.5 * course.pitch();
    // θ of the centre within the plate, the loop unwrapped about it.
    let centre_theta = theta0 + (cut.centre.x - theta0).rem_euclid(TAU);
    let map = |p: DVec2| {
        let t = centre_theta + (p.x - cut.centre.x + PI).rem_euclid(TAU) - PI;
        develop_point(&surface, mid, DVec2::new(t, p.y))
    };
    PlateOpening {
        mark: cut.mark.clone(),
        contour: cut.hole.iter().map(|&p| map(p)).collect(),
        centre: map(cut.centre),
        reach: DVec2::splat(reach),
    }
}

/// Cuts every course into its plates, keeping from `prior` (a plan made with
/// the same shop data, and its plates) every plate of the same id whose
/// course, part and openings are unchanged. Returns the plates and the
/// number cut again.
pub fn cut_plates_reusing(
    tag: &str,
    developments: &Developments,
    openings: &Openings,
    seams: &SeamLayout,
    prior: Option<(Prior, &[Arc<Plate>])>,
) -> (Vec<Arc<Plate>>, usize) {
    let mut plates = Vec::new();
    let mut cut = 0;
    let mut numbers: Vec<usize> = vec![0; developments.rolled.len()];
    let old: BTreeMap<&str, &Arc<Plate>> = prior
        .map(|(_, p)| p.iter().map(|p| (p.id.as_str(), p)).collect())
        .unwrap_or_default();
    for (ci, course) in seams.courses.iter().enumerate() {
        let rolled = &developments.rolled[course.rolled];
        let pitch = course.pitch();
        for k in 0..course.plates {
            numbers[course.rolled] += 1;
            let id = format!("{tag}-{}-P{}", rolled.id, numbers[course.rolled]);
            let cuts = cuts_in(course, k, developments, openings);
            let cones = cone_cuts_in(course, k, openings);
            let kept = prior.and_then(|(p, _)| {
                let plate = old.get(id.as_str())?;
                let old_course = p.seams.courses.get(plate.course_index)?;
                let same = plate.course_index == ci
                    && plate.seam == k
                    && old_course == course
                    && p.developments.rolled.get(course.rolled) == Some(rolled)
                    && cuts_in(old_course, k, p.developments, p.openings) == cuts
                    && cone_cuts_in(old_course, k, p.openings) == cones;
                same.then(|| Arc::clone(plate))
            });
            if let Some(plate) = kept {
                plates.push(plate);
                continue;
            }
            cut += 1;
            let theta0 = course.seam(k);
            let r = rolled.radius_at(course.z.0);
            let mut holes: Vec<PlateOpening> = cuts
                .iter()
                .map(|cut| {
                    let rel = (cut.centre.x - theta0).rem_euclid(TAU);
                    let map = |p: DVec2| {
                        let t = theta0 + rel + (p.x - cut.centre.x + PI).rem_euclid(TAU) - PI;
                        DVec2::new(r * (t - theta0), p.y - course.z.0)
                    };
                    let reach = cut.pad.as_ref().map_or(cut.cut_radius, |p| 0.5 * p.od) + 50.0;
                    PlateOpening {
                        mark: cut.mark.clone(),
                        contour: cut.hole.iter().map(|&p| map(p)).collect(),
                        centre: map(cut.centre),
                        reach: DVec2::splat(reach),
                    }
                })
                .collect();
            holes.extend(
                cones
                    .iter()
                    .map(|c| cone_opening(c, rolled, course, theta0)),
            );
            plates.push(Arc::new(Plate {
                id,
                part: rolled.id.clone(),
                course: course.id.clone(),
                course_index: ci,
                seam: k,
                thickness: rolled.thickness,
                outline: rolled.outline(theta0, pitch, course.z.0, course.z.1),
                openings: holes,
                mid_area: rolled.area(theta0, pitch, course.z.0, course.z.1),
            }));
        }
    }
    (plates, cut)
}
