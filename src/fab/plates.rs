//! Plates: each course cut by its longitudinal seams, with the openings that
//! fall in it developed into the plate's own coordinates and the marking
//! lines a fitter needs.
//!
//! A cylinder's plate has `x = r·(θ − θ₀)` from its first seam and `y = z −
//! z₀` from its lower joint (seen from outside, x runs counter-clockwise
//! about the part's axis). A cone's plate is an annular sector laid with its
//! bisector along +y about the apex; it carries no openings (they are cut
//! after forming).

use std::f64::consts::{PI, TAU};

use glam::DVec2;

use super::develop::{Developments, Outline};
use super::openings::Openings;
use super::seams::SeamLayout;

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
) -> Vec<Plate> {
    let mut plates = Vec::new();
    let mut numbers: Vec<usize> = vec![0; developments.rolled.len()];
    for (ci, course) in seams.courses.iter().enumerate() {
        let rolled = &developments.rolled[course.rolled];
        let pitch = course.pitch();
        for k in 0..course.plates {
            numbers[course.rolled] += 1;
            let theta0 = course.seam(k);
            let r = rolled.radius_at(course.z.0);
            let mut holes = Vec::new();
            if rolled.is_cylinder() {
                for cut in openings.cuts.iter().filter(|c| c.rolled == course.rolled) {
                    let rel = (cut.centre.x - theta0).rem_euclid(TAU);
                    let within_z = cut.centre.y >= course.z.0 && cut.centre.y < course.z.1;
                    if rel >= pitch || !within_z {
                        continue;
                    }
                    let map = |p: DVec2| {
                        let t = theta0 + rel + (p.x - cut.centre.x + PI).rem_euclid(TAU) - PI;
                        DVec2::new(r * (t - theta0), p.y - course.z.0)
                    };
                    let reach = cut.pad.as_ref().map_or(cut.cut_radius, |p| 0.5 * p.od) + 50.0;
                    holes.push(PlateOpening {
                        mark: cut.mark.clone(),
                        contour: cut.hole.iter().map(|&p| map(p)).collect(),
                        centre: map(cut.centre),
                        reach: DVec2::splat(reach),
                    });
                }
            }
            plates.push(Plate {
                id: format!("{tag}-{}-P{}", rolled.id, numbers[course.rolled]),
                part: rolled.id.clone(),
                course: course.id.clone(),
                course_index: ci,
                seam: k,
                thickness: rolled.thickness,
                outline: rolled.outline(pitch, course.z.0, course.z.1),
                openings: holes,
                mid_area: rolled.area(pitch, course.z.0, course.z.1),
            });
        }
    }
    plates
}
