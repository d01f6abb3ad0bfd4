//! Seam layout: rolled parts split into courses (circumferential seams) and
//! courses into plates (longitudinal seams), by the shop's plate sizes, with
//! the seams kept clear of openings and pads and the longitudinal seams of
//! adjacent courses staggered.
//!
//! **Courses.** A part of axial height `L` (slant height for a cone) becomes
//! `⌈L / max_plate_width⌉` courses of equal height; a joint inside a part is
//! moved, within the plate width, to the nearest height at least the
//! clearance from every opening and pad footprint. Joints between parts stay
//! where the design puts them.
//!
//! **Plates.** A course of mid radius `r` becomes `n = ⌈2π·r_max /
//! max_plate_length⌉` plates of equal angle, its `n` longitudinal seams at
//! `φ₀ + k·2π/n`. `φ₀` is chosen, from the preferred angle outwards in steps
//! of at most 1 mm of arc, as the first for which every seam is at least the
//! clearance (measured along the developed arc, from the opening's points
//! within the clearance of the course's height) from every opening and pad
//! and the stagger (arc at the joint) from every seam of the course below
//! (the previous course in the stack, across part joints too). The preferred
//! angle is half a plate from the seams below (0 for a stack's first course).
//! Where no `φ₀` satisfies every rule, the one breaking the fewest is taken
//! and each rule broken is a **deficiency** naming both entities.
//!
//! **Loop validity** (the seed's even/odd loop depth: every opening and pad
//! loop must lie at depth one inside exactly one plate): an opening or pad
//! across a seam, two openings or pads that overlap or nest, are **errors**
//! naming both entities.

use std::f64::consts::TAU;

use glam::{DVec2, DVec3};

use super::develop::{Developments, Rolled, RolledKind};
use super::openings::{NozzleCut, Openings};
use super::shop::Shop;
use crate::format::RuleViolation;

/// One course of a rolled part: an axial band rolled from its plates.
#[derive(Clone, Debug, PartialEq)]
pub struct Course {
    /// Index in [`Developments::rolled`].
    pub rolled: usize,
    /// Course id: part id and number from the part's start, `S1-C2`.
    pub id: String,
    /// Axial range in the part's local frame, mm.
    pub z: (f64, f64),
    /// Angle of the first longitudinal seam, part local, radians in [0, 2π).
    pub start: f64,
    /// Number of plates (and of longitudinal seams).
    pub plates: usize,
}

impl Course {
    /// Angle of one plate, radians.
    pub fn pitch(&self) -> f64 {
        TAU / self.plates as f64
    }

    /// Part-local angle of longitudinal seam `k` (0-based).
    pub fn seam(&self, k: usize) -> f64 {
        self.start + k as f64 * self.pitch()
    }

    /// Id of longitudinal seam `k` (0-based): `S1-C2-L1`.
    pub fn seam_id(&self, k: usize) -> String {
        format!("{}-L{}", self.id, k + 1)
    }
}

/// The seams of one vessel and what their rules found.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct SeamLayout {
    /// Courses, by rolled part in design order, then from the part's start.
    pub courses: Vec<Course>,
    /// Rules that could not be met by moving seams.
    pub deficiencies: Vec<RuleViolation>,
    /// Broken loop-validity rules.
    pub errors: Vec<RuleViolation>,
    /// The same, part by part from the bottom of the stack up, with what
    /// each part's seams were laid out from (so a new layout can keep the
    /// parts whose inputs did not change).
    pub parts: Vec<PartSeams>,
}

/// The seams of one rolled part, and the inputs besides the part and its
/// openings they were laid out from.
#[derive(Clone, Debug, PartialEq)]
pub struct PartSeams {
    /// Index in [`Developments::rolled`].
    pub rolled: usize,
    /// The course below the part's first course in the stack and the part it
    /// belongs to: the seams the part's first course is staggered from.
    pub below: Option<(Course, Rolled)>,
    /// Its courses, from the bottom up.
    pub courses: Vec<Course>,
    /// Its deficiencies.
    pub deficiencies: Vec<RuleViolation>,
    /// Its loop-validity errors.
    pub errors: Vec<RuleViolation>,
}

/// A previous plan's layout and what it was laid out from.
#[derive(Clone, Copy)]
pub struct Prior<'a> {
    /// Its developments.
    pub developments: &'a Developments,
    /// Its openings.
    pub openings: &'a Openings,
    /// Its seams.
    pub seams: &'a SeamLayout,
}

/// The angle of part-local `theta` in the vessel frame of `rolled`.
pub fn vessel_angle(rolled: &Rolled, theta: f64) -> f64 {
    let d = rolled.frame.matrix3 * DVec3::new(theta.cos(), theta.sin(), 0.0);
    d.y.atan2(d.x)
}

/// Distance between two angles, radians in [0, π].
pub fn angle_gap(a: f64, b: f64) -> f64 {
    let d = (a - b).rem_euclid(TAU);
    d.min(TAU - d)
}

/// A loop a seam must keep clear of: an opening or a pad footprint.
struct Keep<'a> {
    /// Entity named in reports, `C-201/N1` or `C-201/N1 pad`.
    entity: String,
    /// JSON path of its nozzle (or boot): loops of one path are one cut.
    path: &'a str,
    /// Where its nozzle's axis meets the mid-surface, `(θ, z)`.
    centre: DVec2,
    points: &'a [DVec2],
    z: (f64, f64),
}

fn keeps<'a>(tag: &str, openings: &'a Openings, rolled: usize) -> Vec<Keep<'a>> {
    let mut out = Vec::new();
    let mut push = |entity: String, path: &'a str, centre: DVec2, points: &'a [DVec2]| {
        let z = points
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), p| {
                (lo.min(p.y), hi.max(p.y))
            });
        out.push(Keep {
            entity,
            path,
            centre,
            points,
            z,
        });
    };
    for cut in cuts_on(openings, rolled) {
        push(
            format!("{tag}/{}", cut.mark),
            &cut.path,
            cut.centre,
            &cut.hole,
        );
        if let Some(pad) = &cut.pad {
            push(
                format!("{tag}/{} pad", cut.mark),
                &cut.path,
                cut.centre,
                &pad.footprint,
            );
        }
    }
    out
}

/// Lays out the seams of every rolled part.
pub fn lay_out(
    tag: &str,
    developments: &Developments,
    openings: &Openings,
    shop: &Shop,
) -> SeamLayout {
    lay_out_reusing(tag, developments, openings, shop, None).0
}

/// The cuts on rolled part `rolled` (a course's or a cone's).
fn cuts_on(openings: &Openings, rolled: usize) -> Vec<&NozzleCut> {
    openings
        .all()
        .chain(&openings.cones)
        .filter(|c| c.rolled == rolled)
        .collect()
}

/// Lays out the seams of every rolled part, keeping from `prior` (a layout
/// made with the same shop data) each part whose development, openings and
/// course below are unchanged. Returns the layout and the number of courses
/// laid out again.
pub fn lay_out_reusing(
    tag: &str,
    developments: &Developments,
    openings: &Openings,
    shop: &Shop,
    prior: Option<Prior>,
) -> (SeamLayout, usize) {
    let mut layout = SeamLayout::default();
    let mut laid_out = 0;
    // Rolled parts bottom-up in the vessel frame; skirts are not butt-welded
    // to the stack, so they stagger against nothing but themselves.
    let mut order: Vec<usize> = (0..developments.rolled.len()).collect();
    let low = |r: &Rolled| {
        let a = r.frame.transform_point3(DVec3::new(0.0, 0.0, r.z.0)).z;
        let b = r.frame.transform_point3(DVec3::new(0.0, 0.0, r.z.1)).z;
        a.min(b)
    };
    order.sort_by(|&a, &b| low(&developments.rolled[a]).total_cmp(&low(&developments.rolled[b])));
    // The top course of the stack so far: (course, its part, vessel z of its
    // top, the axis point there).
    let mut below: Option<(Course, usize, f64, DVec3)> = None;
    for &ri in &order {
        let rolled = &developments.rolled[ri];
        let at = |z: f64| rolled.frame.transform_point3(DVec3::new(0.0, 0.0, z));
        let (first, last) = (at(rolled.z.0), at(rolled.z.1));
        let (bottom, top) = if first.z > last.z {
            (last, first)
        } else {
            (first, last)
        };
        let in_stack = rolled.kind != RolledKind::Skirt;
        let lower = match &below {
            Some((c, r, z, axis))
                if in_stack
                    && (z - bottom.z).abs() < 1e-6
                    && (axis.truncate() - bottom.truncate()).length() < 1e-6 =>
            {
                Some((c.clone(), developments.rolled[*r].clone()))
            }
            _ => None,
        };
        let kept = prior.and_then(|p| {
            let old = p.seams.parts.iter().find(|o| o.rolled == ri)?;
            let same = p.developments.rolled.get(ri) == Some(rolled)
                && old.below == lower
                && cuts_on(p.openings, ri) == cuts_on(openings, ri);
            same.then(|| old.clone())
        });
        let part = kept.unwrap_or_else(|| {
            let part = lay_out_part(tag, ri, developments, openings, lower, shop);
            laid_out += part.courses.len();
            part
        });
        if in_stack && let Some(c) = part.courses.last() {
            below = Some((c.clone(), ri, top.z, top));
        }
        layout.parts.push(part);
    }
    for part in &layout.parts {
        layout.courses.extend(part.courses.iter().cloned());
        layout
            .deficiencies
            .extend(part.deficiencies.iter().cloned());
        layout.errors.extend(part.errors.iter().cloned());
    }
    // Courses by part in design order, then from the part's start.
    layout
        .courses
        .sort_by(|a, b| a.rolled.cmp(&b.rolled).then(a.z.0.total_cmp(&b.z.0)));
    (layout, laid_out)
}

/// Lays out the courses and seams of rolled part `ri`, its first course
/// staggered from `lower` (the course below it in the stack, with its part).
fn lay_out_part(
    tag: &str,
    ri: usize,
    developments: &Developments,
    openings: &Openings,
    lower: Option<(Course, Rolled)>,
    shop: &Shop,
) -> PartSeams {
    let rolled = &developments.rolled[ri];
    let mut part = PartSeams {
        rolled: ri,
        below: lower.clone(),
        courses: Vec::new(),
        deficiencies: Vec::new(),
        errors: Vec::new(),
    };
    let keep = keeps(tag, openings, ri);
    let (joints, faults) = course_joints(rolled, &keep, shop);
    // Crossings are loop-validity errors (below); the rest deficiencies.
    for (i, z, crossing) in faults {
        if !crossing {
            part.deficiencies.push(RuleViolation {
                path: keep[i].path.to_string(),
                entity: keep[i].entity.clone(),
                field: "elevation".into(),
                value: format!("{:.3}", keep[i].centre.y),
                rule: format!(
                    "the circumferential seam of {}/{} at z = {z:.1} mm is closer than the clearance {} mm",
                    tag,
                    rolled.id,
                    shop.clearance_for(rolled.thickness)
                ),
            });
        }
    }
    let flipped = {
        let at = |z: f64| rolled.frame.transform_point3(DVec3::new(0.0, 0.0, z)).z;
        at(rolled.z.0) > at(rolled.z.1)
    };
    let mut bands: Vec<(usize, (f64, f64))> = joints
        .windows(2)
        .enumerate()
        .map(|(k, w)| (k + 1, (w[0], w[1])))
        .collect();
    if flipped {
        bands.reverse();
    }
    let mut previous = lower;
    for (number, band) in bands {
        let id = format!("{}-C{number}", rolled.id);
        let below = previous.as_ref().map(|(c, r)| (c, r));
        let course = place_seams(tag, ri, id, band, rolled, &keep, below, shop, &mut part);
        previous = Some((course.clone(), rolled.clone()));
        part.courses.push(course);
    }
    check_loops(rolled, &keep, &mut part);
    part
}

/// A course joint too close to a loop: (loop index in the keep list, joint
/// z, whether it crosses the loop).
type JointFault = (usize, f64, bool);

/// The course joints of `rolled` (part-local z, both ends included): the
/// fewest courses of at most the plate width, each inner joint moved within
/// the plate width to the nearest height clear of every opening and pad;
/// one or two more courses where that is what clears them. Returns the
/// joints and the faults left.
fn course_joints(rolled: &Rolled, keep: &[Keep], shop: &Shop) -> (Vec<f64>, Vec<JointFault>) {
    let (z0, z1) = rolled.z;
    let slope = rolled.slant(0.0, 1.0);
    let width = shop.max_plate_width / slope;
    let fewest = (((z1 - z0) / width) - 1e-9).ceil().max(1.0) as usize;
    let clearance = shop.clearance_for(rolled.thickness);
    let faults_at = |z: f64| -> Vec<JointFault> {
        keep.iter()
            .enumerate()
            .filter(|(_, k)| z > k.z.0 - clearance && z < k.z.1 + clearance)
            .map(|(i, k)| (i, z, z > k.z.0 && z < k.z.1))
            .collect()
    };
    let score = |f: &[JointFault]| (f.iter().filter(|x| x.2).count(), f.len());
    let attempt = |n: usize| -> (Vec<f64>, Vec<JointFault>) {
        let mut joints = vec![z0];
        let mut faults = Vec::new();
        for j in 1..n {
            let prev = *joints.last().expect("starts with z0");
            let remaining = (n - j) as f64;
            let lo = (z1 - remaining * width).max(prev + 1e-3);
            let hi = (prev + width).min(z1 - 1e-3);
            let preferred = (z0 + (z1 - z0) * j as f64 / n as f64).clamp(lo, hi);
            let mut candidates = vec![preferred];
            for k in keep {
                for z in [
                    k.z.0 - clearance,
                    k.z.1 + clearance,
                    k.z.0 - 1e-3,
                    k.z.1 + 1e-3,
                ] {
                    if (lo..=hi).contains(&z) {
                        candidates.push(z);
                    }
                }
            }
            let z = candidates
                .iter()
                .copied()
                .min_by(|&a, &b| {
                    let (fa, fb) = (faults_at(a), faults_at(b));
                    score(&fa)
                        .cmp(&score(&fb))
                        .then((a - preferred).abs().total_cmp(&(b - preferred).abs()))
                })
                .expect("the preferred height is a candidate");
            faults.extend(faults_at(z));
            joints.push(z);
        }
        joints.push(z1);
        (joints, faults)
    };
    let mut best = attempt(fewest);
    for n in fewest + 1..=fewest + 2 {
        if best.1.is_empty() {
            break;
        }
        let next = attempt(n);
        if score(&next.1) < score(&best.1) {
            best = next;
        }
    }
    best
}

/// Chooses the longitudinal seams of one course.
#[expect(clippy::too_many_arguments, reason = "one course's whole context")]
fn place_seams(
    tag: &str,
    rolled_index: usize,
    id: String,
    band: (f64, f64),
    rolled: &Rolled,
    keep: &[Keep],
    below: Option<(&Course, &Rolled)>,
    shop: &Shop,
    layout: &mut PartSeams,
) -> Course {
    let r_max = rolled.radius_at(band.0).max(rolled.radius_at(band.1));
    let r_min = rolled.radius_at(band.0).min(rolled.radius_at(band.1));
    let plates = ((TAU * r_max / shop.max_plate_length) - 1e-9)
        .ceil()
        .max(1.0) as usize;
    let pitch = TAU / plates as f64;
    let clearance = shop.clearance_for(rolled.thickness);
    // Angular intervals (centre, half-width) a seam must avoid, each with
    // what it belongs to.
    struct Avoid {
        centre: f64,
        half: f64,
        what: String,
        crossing_half: f64,
        path: String,
        kind: AvoidKind,
    }
    let mut avoid: Vec<Avoid> = Vec::new();
    for k in keep {
        let near: Vec<f64> = k
            .points
            .iter()
            .filter(|p| p.y >= band.0 - clearance && p.y <= band.1 + clearance)
            .map(|p| p.x)
            .collect();
        if near.is_empty() {
            continue;
        }
        let (a, b) = near
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), &t| {
                (lo.min(t), hi.max(t))
            });
        // The θ-range of the loop inside the band proper: a seam there crosses it.
        let inside: Vec<f64> = k
            .points
            .iter()
            .filter(|p| p.y >= band.0 && p.y <= band.1)
            .map(|p| p.x)
            .collect();
        let crossing_half = if inside.is_empty() {
            -1.0
        } else {
            let (ia, ib) = inside
                .iter()
                .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), &t| {
                    (lo.min(t), hi.max(t))
                });
            0.5 * (ib - ia)
        };
        avoid.push(Avoid {
            centre: 0.5 * (a + b),
            half: 0.5 * (b - a) + clearance / r_min,
            what: k.entity.clone(),
            crossing_half,
            path: k.path.to_string(),
            kind: AvoidKind::Loop,
        });
    }
    if let Some((lower, lower_rolled)) = below {
        let joint_r = lower_rolled
            .radius_at(lower.z.0)
            .min(lower_rolled.radius_at(lower.z.1))
            .min(r_min);
        let stagger = shop.stagger_for(rolled.thickness.max(lower_rolled.thickness));
        for k in 0..lower.plates {
            // Into this part's local angles.
            let va = vessel_angle(lower_rolled, lower.seam(k));
            let local = rolled.frame.matrix3.inverse() * DVec3::new(va.cos(), va.sin(), 0.0);
            avoid.push(Avoid {
                centre: local.y.atan2(local.x),
                half: stagger / joint_r,
                what: lower_rolled.id.clone() + "/" + &lower.seam_id(k),
                crossing_half: -1.0,
                path: lower_rolled.path.clone(),
                kind: AvoidKind::Seam,
            });
        }
    }
    let preferred = match below {
        Some((lower, lower_rolled)) => {
            let va = vessel_angle(lower_rolled, lower.seam(0) + 0.5 * lower.pitch());
            let local = rolled.frame.matrix3.inverse() * DVec3::new(va.cos(), va.sin(), 0.0);
            local.y.atan2(local.x).rem_euclid(pitch)
        }
        None => 0.0,
    };
    // What a start angle breaks: (seams across a loop, rules broken).
    let broken = |start: f64| -> (usize, Vec<usize>) {
        let mut crossings = 0;
        let mut out = Vec::new();
        for (i, a) in avoid.iter().enumerate() {
            let gaps = (0..plates).map(|k| angle_gap(start + k as f64 * pitch, a.centre));
            let nearest = gaps.fold(f64::INFINITY, f64::min);
            if nearest < a.half {
                out.push(i);
            }
            if nearest < a.crossing_half {
                crossings += 1;
            }
        }
        (crossings, out)
    };
    let step = (1.0 / r_max).min(pitch / 8.0);
    let tries = (pitch / step).ceil() as usize;
    let mut best: Option<(f64, (usize, Vec<usize>))> = None;
    for i in 0..=tries {
        // 0, +1, -1, +2, -2, … steps from the preferred angle.
        let offset = if i % 2 == 1 {
            (i / 2 + 1) as f64
        } else {
            -((i / 2) as f64)
        };
        let start = (preferred + offset * step).rem_euclid(pitch);
        let b = broken(start);
        if b.1.is_empty() {
            best = Some((start, b));
            break;
        }
        let better = |old: &(usize, Vec<usize>)| (b.0, b.1.len()) < (old.0, old.1.len());
        if best.as_ref().is_none_or(|(_, old)| better(old)) {
            best = Some((start, b));
        }
    }
    let (start, (_, broken)) = best.expect("at least one try");
    let course = Course {
        rolled: rolled_index,
        id,
        z: band,
        start,
        plates,
    };
    for i in broken {
        let a = &avoid[i];
        let (k, gap) = (0..plates)
            .map(|k| (k, angle_gap(course.seam(k), a.centre)))
            .min_by(|x, y| x.1.total_cmp(&y.1))
            .expect("a course has a seam");
        let seam = format!("{}/{}", rolled.id, course.seam_id(k));
        match a.kind {
            AvoidKind::Loop if gap < a.crossing_half => layout.errors.push(RuleViolation {
                path: a.path.clone(),
                entity: a.what.clone(),
                field: "orientation".into(),
                value: format!("{:.3}", a.centre.to_degrees()),
                rule: format!(
                    "crosses longitudinal seam {seam}: no plate layout of course {} keeps it inside one plate",
                    course.id
                ),
            }),
            AvoidKind::Loop => layout.deficiencies.push(RuleViolation {
                path: a.path.clone(),
                entity: a.what.clone(),
                field: "orientation".into(),
                value: format!("{:.3}", a.centre.to_degrees()),
                rule: format!(
                    "longitudinal seam {seam} is closer than the clearance {clearance} mm (max(50, 2.5·t) or the shop's)"
                ),
            }),
            AvoidKind::Seam => layout.deficiencies.push(RuleViolation {
                path: rolled.path.clone(),
                entity: format!("{tag}/{}", rolled.id),
                field: "seams".into(),
                value: format!("{:.1} mm", gap * r_min),
                rule: format!(
                    "longitudinal seam {seam} is staggered from {} by less than max(5·t, {} mm)",
                    a.what, shop.min_stagger
                ),
            }),
        }
    }
    course
}

#[derive(Clone, Copy, PartialEq, Eq)]
enum AvoidKind {
    Loop,
    Seam,
}

/// Loop validity: openings and pads of one part against its course joints
/// and each other.
fn check_loops(rolled: &Rolled, keep: &[Keep], part: &mut PartSeams) {
    // Course joints, part ends included.
    let mut ours: Vec<&Course> = part.courses.iter().collect();
    ours.sort_by(|a, b| a.z.0.total_cmp(&b.z.0));
    let mut joints: Vec<(f64, String)> = Vec::new();
    for c in &ours {
        joints.push((c.z.0, format!("{}/{} bottom", rolled.id, c.id)));
    }
    if let Some(c) = ours.last() {
        joints.push((c.z.1, format!("{}/{} top", rolled.id, c.id)));
    }
    for k in keep {
        for (z, name) in &joints {
            if k.z.0 < *z && k.z.1 > *z {
                part.errors.push(RuleViolation {
                    path: k.path.to_string(),
                    entity: k.entity.clone(),
                    field: "elevation".into(),
                    value: format!("{:.3}", k.centre.y),
                    rule: format!(
                        "crosses the circumferential seam at {name} (z = {z:.1} mm of {})",
                        rolled.id
                    ),
                });
            }
        }
    }
    for (i, a) in keep.iter().enumerate() {
        for b in &keep[i + 1..] {
            if a.path == b.path {
                continue;
            }
            if loops_meet(a.points, b.points) {
                part.errors.push(RuleViolation {
                    path: a.path.to_string(),
                    entity: a.entity.clone(),
                    field: "position".into(),
                    value: format!("({:.3} deg, {:.1} mm)", a.centre.x.to_degrees(), a.centre.y),
                    rule: format!("overlaps {} (loops must not cross or nest)", b.entity),
                });
            }
        }
    }
}

/// Whether two closed loops in surface coordinates cross or one holds the
/// other (angles compared within π of each other).
pub fn loops_meet(a: &[DVec2], b: &[DVec2]) -> bool {
    // Each loop is continuous in θ; move `b` as a whole by whole turns to
    // lie nearest `a`.
    let mean = |p: &[DVec2]| p.iter().map(|q| q.x).sum::<f64>() / p.len() as f64;
    let turns = ((mean(a) - mean(b)) / TAU).round();
    let b: Vec<DVec2> = b
        .iter()
        .map(|p| DVec2::new(p.x + turns * TAU, p.y))
        .collect();
    let bbox = |p: &[DVec2]| {
        p.iter().fold(
            (DVec2::splat(f64::INFINITY), DVec2::splat(f64::NEG_INFINITY)),
            |(lo, hi), q| (lo.min(*q), hi.max(*q)),
        )
    };
    let (alo, ahi) = bbox(a);
    let (blo, bhi) = bbox(&b);
    if alo.x > bhi.x || blo.x > ahi.x || alo.y > bhi.y || blo.y > ahi.y {
        return false;
    }
    if inside(a[0], &b) || inside(b[0], a) {
        return true;
    }
    let n = a.len();
    let m = b.len();
    for i in 0..n {
        let (p, q) = (a[i], a[(i + 1) % n]);
        for j in 0..m {
            let (r, s) = (b[j], b[(j + 1) % m]);
            if segments_cross(p, q, r, s) {
                return true;
            }
        }
    }
    false
}

fn segments_cross(p: DVec2, q: DVec2, r: DVec2, s: DVec2) -> bool {
    let d1 = (q - p).perp_dot(r - p);
    let d2 = (q - p).perp_dot(s - p);
    let d3 = (s - r).perp_dot(p - r);
    let d4 = (s - r).perp_dot(q - r);
    d1 * d2 < 0.0 && d3 * d4 < 0.0
}

/// Even-odd point in polygon.
pub fn inside(p: DVec2, poly: &[DVec2]) -> bool {
    let mut odd = false;
    let n = poly.len();
    for i in 0..n {
        let (a, b) = (poly[i], poly[(i + 1) % n]);
        if (a.y > p.y) != (b.y > p.y) {
            let x = a.x + (p.y - a.y) / (b.y - a.y) * (b.x - a.x);
            if x > p.x {
                odd = !odd;
            }
        }
    }
    odd
}
