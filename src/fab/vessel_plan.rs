//! The fabrication plan of one vessel ([`FabPlan`]): developments, openings,
//! seams and plates, made from nothing ([`plan`]) or from a previous plan of
//! the same vessel keeping what an edit left unchanged ([`plan_vessel`]),
//! which is how the live model keeps flat patterns current: moving a nozzle
//! develops its opening and its plate(s) again (on a course or a cone, or
//! maps it onto its head's blank again) and lays out the seams of its part (and of the parts above,
//! only if those seams moved).

use glam::DVec2;

use std::sync::Arc;

use super::boot::{self, BootPlate};
use super::cone_openings;
use super::develop::{self, Developments};
use super::error::FabError;
use super::head_map;
use super::nest::{self, Nesting, Piece};
use super::openings::{self, Openings};
use super::plates::{self, Plate};
use super::seams::{self, Prior, SeamLayout};
use super::shop::Shop;
use crate::constraints::{ResolvedVessel, resolve_vessel};
use crate::format::{Design, RuleViolation, VesselDesign};

/// The fabrication plan of one vessel.
#[derive(Clone, Debug, PartialEq)]
pub struct FabPlan {
    /// The vessel's tag.
    pub tag: String,
    /// The material grade of its plates (the design's material, or
    /// `"unspecified"`).
    pub grade: String,
    /// The vessel as resolved.
    pub resolved: ResolvedVessel,
    /// The developments of its parts.
    pub developments: Developments,
    /// Its openings, pads and neck ends.
    pub openings: Openings,
    /// Its courses and seams, with the deficiencies found.
    pub seams: SeamLayout,
    /// Its plates.
    pub plates: Vec<Arc<Plate>>,
    /// The shop data it was planned with.
    pub shop: Shop,
    /// The vessel's design it was planned from, and its index in the design.
    pub vessel: VesselDesign,
    /// The vessel's index in its design.
    pub index: usize,
}

/// What [`plan_vessel`] did again rather than keep from the previous plan.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct FabWork {
    /// Rolled parts and heads developed.
    pub parts: usize,
    /// Nozzles whose opening, pad and neck end were developed (or mapped onto
    /// a head's blank), and boots cut into their course.
    pub openings: usize,
    /// Courses whose seams were laid out and checked.
    pub courses: usize,
    /// Plates cut.
    pub plates: usize,
}

impl FabPlan {
    /// The plates of every boot, in part order.
    pub fn boot_plates(&self) -> Vec<BootPlate> {
        let mut out = Vec::new();
        for b in &self.developments.boots {
            let Some(cut) = self.openings.boots.iter().find(|c| c.nozzle == b.part) else {
                continue;
            };
            let course = &self.developments.rolled[cut.rolled];
            out.extend(boot::boot_plates(&self.tag, b, cut, course, &self.shop));
        }
        out
    }

    /// Every head blank: the heads', then the boots' heads'.
    pub fn blanks(&self) -> impl Iterator<Item = &develop::HeadBlank> {
        let boots = self
            .developments
            .boots
            .iter()
            .filter_map(|b| b.head.as_ref());
        self.developments.heads.iter().chain(boots)
    }

    /// The pieces to nest: plates (net of openings), boot plates, pads (on
    /// courses and cones), head blanks.
    pub fn pieces(&self) -> Vec<Piece> {
        let mut out: Vec<Piece> = self
            .plates
            .iter()
            .map(|p| {
                let (w, h) = p.outline.extent();
                let holes: f64 = p
                    .openings
                    .iter()
                    .map(|o| openings::polygon_area(&o.contour).abs())
                    .sum();
                Piece {
                    id: p.id.clone(),
                    thickness: p.thickness,
                    size: DVec2::new(w, h),
                    area: p.outline.area() - holes,
                }
            })
            .collect();
        for p in self.boot_plates() {
            let (w, h) = p.extent();
            out.push(Piece {
                id: p.id.clone(),
                thickness: p.thickness,
                size: DVec2::new(w, h),
                area: openings::polygon_area(&p.outline).abs(),
            });
        }
        for cut in self.openings.cuts.iter().chain(&self.openings.cones) {
            if let Some(pad) = &cut.pad {
                let (lo, hi) = pad.outline.iter().fold(
                    (DVec2::splat(f64::INFINITY), DVec2::splat(f64::NEG_INFINITY)),
                    |(lo, hi), p| (lo.min(*p), hi.max(*p)),
                );
                out.push(Piece {
                    id: format!("{}-{}-PAD", self.tag, cut.mark),
                    thickness: pad.thickness,
                    size: hi - lo,
                    area: pad.area(),
                });
            }
        }
        for h in self.blanks() {
            out.push(Piece {
                id: format!("{}-{}-BLANK", self.tag, h.id),
                thickness: h.thickness,
                size: DVec2::splat(h.diameter),
                area: 0.25 * std::f64::consts::PI * h.diameter * h.diameter,
            });
        }
        out
    }

    /// Nests [`pieces`](Self::pieces) on the shop's stock sheets.
    pub fn nesting(&self, shop: &Shop) -> Nesting {
        nest::nest(
            &self.pieces(),
            shop.sheet_length,
            shop.sheet_width,
            shop.nest_gap,
        )
    }
}

/// Plans the fabrication of vessel `tag` of `design` with `shop` data.
///
/// # Errors
///
/// [`FabError::UnknownVessel`], or [`FabError::Rules`] with every broken
/// design or fabrication rule (a part without thickness, a neck that does
/// not lie on its course, loop validity). Seams that cannot keep their
/// clearance or stagger are not errors: they are the plan's
/// [`SeamLayout::deficiencies`].
pub fn plan(design: &Design, tag: &str, shop: &Shop) -> Result<FabPlan, FabError> {
    let (index, vessel) = design
        .vessels
        .iter()
        .enumerate()
        .find(|(_, v)| v.tag == tag)
        .ok_or_else(|| FabError::UnknownVessel { tag: tag.into() })?;
    let resolved = resolve_vessel(vessel, index).map_err(FabError::Rules)?;
    plan_vessel(vessel, index, &resolved, shop, None).map(|(p, _)| p)
}

/// Plans the fabrication of `vessel` (index `index` of its design) resolved as
/// `resolved`, keeping from `previous` (a plan of the same vessel) whatever
/// its inputs leave unchanged: a part's development when the part is the
/// same, a nozzle's cuts when the nozzle and its course are, a part's seams
/// when its development, openings and the course below are, a plate when
/// its course, part and openings are. The result equals a plan made from
/// nothing; [`FabWork`] counts what was done again.
///
/// # Errors
///
/// As [`plan`].
pub fn plan_vessel(
    vessel: &VesselDesign,
    index: usize,
    resolved: &ResolvedVessel,
    shop: &Shop,
    previous: Option<&FabPlan>,
) -> Result<(FabPlan, FabWork), FabError> {
    let previous = previous.filter(|p| p.shop == *shop && p.index == index);
    let mut work = FabWork::default();
    let mut developments = Developments::default();
    let mut errors = Vec::new();
    for (i, part) in resolved.parts.iter().enumerate() {
        let same_design = |p: &FabPlan| {
            let same = |id: &str| {
                let at = |v: &VesselDesign| v.parts.iter().position(|d| d.id() == id);
                let (old, new) = (at(&p.vessel), at(vessel));
                old == new && new.is_none_or(|k| p.vessel.parts[k] == vessel.parts[k])
            };
            // A boot takes its host course's thickness.
            let host = part.host.and_then(|h| resolved.parts.get(h));
            same(&part.id) && host.is_none_or(|h| same(&h.id))
        };
        let kept = previous
            .filter(|p| p.resolved.parts.get(i) == Some(part) && same_design(p))
            .map(|p| p.developments.of_part(i, &part.id));
        let d = match kept {
            Some(d) => d,
            None => match develop::develop_one(vessel, index, resolved, i) {
                Ok(d) => {
                    work.parts += usize::from(d.is_some());
                    d
                }
                Err(e) => {
                    errors.push(e);
                    continue;
                }
            },
        };
        if let Some(d) = d {
            developments.push(d);
        }
    }
    if !errors.is_empty() {
        return Err(FabError::Rules(errors));
    }
    let mut openings = Openings::default();
    for (i, nozzle) in resolved.nozzles.iter().enumerate() {
        let course = openings::host_course(resolved, &developments, i);
        let cone = cone_openings::host_cone(resolved, &developments, i);
        let kept = previous.and_then(|p| {
            let same = p.resolved.nozzles.get(i) == Some(nozzle)
                && openings::host_course(&p.resolved, &p.developments, i) == course
                && cone_openings::host_cone(&p.resolved, &p.developments, i) == cone
                && course
                    .or(cone)
                    .is_none_or(|c| p.developments.rolled.get(c) == developments.rolled.get(c));
            if !same {
                return None;
            }
            if cone.is_some() {
                return p
                    .openings
                    .cones
                    .iter()
                    .find(|c| c.nozzle == i)
                    .map(|c| openings::NozzleOutcome::Cone(Box::new(c.clone())));
            }
            match course {
                Some(_) => p
                    .openings
                    .cuts
                    .iter()
                    .find(|c| c.nozzle == i)
                    .map(|c| openings::NozzleOutcome::Cut(Box::new(c.clone()))),
                // On a head: kept with the host and its blank.
                None => {
                    let host = nozzle.host;
                    let blank = |d: &Developments| d.heads.iter().find(|h| h.part == host).cloned();
                    let same_host = p.resolved.parts.get(host) == resolved.parts.get(host)
                        && blank(&p.developments) == blank(&developments);
                    same_host
                        .then(|| p.openings.formed.iter().find(|f| f.mark == nozzle.mark))
                        .flatten()
                        .map(|f| openings::NozzleOutcome::Formed(f.clone()))
                }
            }
        });
        let outcome = match kept {
            Some(o) => o,
            None => match openings::cut_nozzle(index, resolved, &developments, shop, i) {
                Ok(mut o) => {
                    if let openings::NozzleOutcome::Formed(f) = &mut o {
                        f.blank = head_map::blank_mark(resolved, &developments, shop, i);
                    }
                    // Developed on a course, or mapped onto a head's blank.
                    work.openings += usize::from(match &o {
                        openings::NozzleOutcome::Cut(_) | openings::NozzleOutcome::Cone(_) => true,
                        openings::NozzleOutcome::Formed(f) => f.blank.is_some(),
                    });
                    o
                }
                Err(e) => {
                    errors.push(e);
                    continue;
                }
            },
        };
        openings.push(outcome);
    }
    if !errors.is_empty() {
        return Err(FabError::Rules(errors));
    }
    for b in &developments.boots {
        let kept = previous.and_then(|p| {
            let c = p.openings.boots.iter().find(|c| c.nozzle == b.part)?;
            let same = p.developments.boots.iter().any(|old| old == b)
                && p.resolved.parts.get(b.host) == resolved.parts.get(b.host)
                && p.developments.rolled.get(c.rolled) == developments.rolled.get(c.rolled);
            same.then(|| c.clone())
        });
        let cut = match kept {
            Some(c) => c,
            None => {
                work.openings += 1;
                match openings::cut_boot(resolved, &developments, shop, b) {
                    Ok(c) => c,
                    Err(e) => {
                        errors.push(e);
                        continue;
                    }
                }
            }
        };
        openings.boots.push(cut);
    }
    if !errors.is_empty() {
        return Err(FabError::Rules(errors));
    }
    let prior = previous.map(|p| Prior {
        developments: &p.developments,
        openings: &p.openings,
        seams: &p.seams,
    });
    let tag = &resolved.tag;
    let (mut seams, courses) = seams::lay_out_reusing(tag, &developments, &openings, shop, prior);
    work.courses = courses;
    seams
        .deficiencies
        .extend(tall_boots(tag, &developments, &openings, shop));
    if !seams.errors.is_empty() {
        return Err(FabError::Rules(seams.errors));
    }
    let old_plates = previous.map(|p| p.plates.as_slice());
    let (plates, cut) =
        plates::cut_plates_reusing(tag, &developments, &openings, &seams, prior.zip(old_plates));
    work.plates = cut;
    let grade = vessel
        .design
        .material
        .clone()
        .unwrap_or_else(|| "unspecified".into());
    Ok((
        FabPlan {
            tag: tag.clone(),
            grade,
            resolved: resolved.clone(),
            developments,
            openings,
            seams,
            plates,
            shop: shop.clone(),
            vessel: vessel.clone(),
            index,
        },
        work,
    ))
}

/// A boot is rolled as one course: a boot whose plate is higher than the
/// shop's widest plate is a deficiency naming its length.
fn tall_boots(
    tag: &str,
    developments: &Developments,
    openings: &Openings,
    shop: &Shop,
) -> Vec<RuleViolation> {
    developments
        .boots
        .iter()
        .filter_map(|b| {
            let cut = openings.boots.iter().find(|c| c.nozzle == b.part)?;
            let high = cut.saddle.iter().fold(0.0f64, |m, p| m.max(p.y));
            (high > shop.max_plate_width).then(|| RuleViolation {
                path: format!("{}.length", b.path),
                entity: format!("{tag}/{}", b.id),
                field: "length".into(),
                value: format!("{high:.1}"),
                rule: format!(
                    "the boot's plate is {high:.1} mm high, more than the shop's max_plate_width \
                     of {} mm; a boot is rolled as one course, not split along its axis: \
                     shorten the boot or give a wider max_plate_width",
                    shop.max_plate_width
                ),
            })
        })
        .collect()
}
