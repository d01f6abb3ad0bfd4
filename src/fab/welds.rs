//! The weld map of one vessel: every weld with its ASME VIII-1 UW-3 category,
//! its length along the exact curve, the thickness it joins, its joint type and
//! the weld metal its preparation takes (`weld_prep`, preparations from the shop
//! rules).
//!
//! Categories (UW-3(a)): **A** longitudinal seams of courses and cones, and the
//! circumferential joint of a hemispherical head to its course; **B** the other
//! circumferential seams (course to course, to a cone, to a formed head other
//! than hemispherical); **C** a flange to its neck, a flat head to its course;
//! **D** a nozzle or a boot (a communicating chamber) to its host. Pads and
//! supports are attachments (UW-16, UG-82), outside UW-3: no category.
//!
//! Curves: long seams are straight generators of the outside surface; circ
//! seams are exact circles at the joint (radius at mid-thickness of the thinner
//! part, which sets the butt weld's thickness); nozzle, boot and pad welds are
//! the exact loops of `weld_curves`. A pad's inner fillet (pad to neck) is given
//! the neck's loop on the host (its loop on the pad's top differs by the pad's
//! thickness times the host's slope there). Support attachments: a skirt's top
//! circle; a saddle's wear-plate outline (2 × arc + 2 × width); legs, the leg
//! pipe's perimeter each; lugs, both sides of two gussets over their height each.
//!
//! Seams are the plate layout's ([`FabPlan::seams`], `fab::seams`): every
//! longitudinal seam of every course (`L-S1-C1-L2`, the generator of the
//! outside surface at the seam's angle, over the course's height), and the
//! circumferential seams between the courses of one part (`C-S1-C1-S1-C2`,
//! the exact circle at the joint's mid radius), category A and B on pressure
//! parts, none on a skirt. A boot's plates give its long seams
//! (`L-B1-1`, category A) and its head its circumferential seam
//! (`C-B1-B1-HEAD`, category by the head's shape as the stack's joints).

use std::f64::consts::{PI, TAU};

use glam::DVec3;
use serde::Serialize;

use super::boot::BootPlate;
use super::develop::{BootShell, RolledKind, boot_head_id};
use super::plan_error::PlanError;
use super::shop_rules::{PrepChoice, ShopRules};
use super::vessel_plan::FabPlan;
use super::weld_curves::{boot_curve, closed_length, nozzle_curves};
use super::weld_prep::cross_section;
use crate::constraints::PartGeometry;
use crate::design::{FlangeDesign, HeadShape, PartDesign, VesselDesign};
use crate::operating::profile::{StackPart, Surface, stack_profile};
use crate::operating::thickness;
use crate::parts::tables::pipe;
use crate::weights::metal::DEFAULT_PLATE;

/// UW-3 weld category.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash, Serialize)]
pub enum Category {
    /// Longitudinal seams; hemispherical head to shell.
    A,
    /// Circumferential seams.
    B,
    /// Flanges and flat heads.
    C,
    /// Nozzles and communicating chambers.
    D,
}

/// What a weld joins.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum WeldKind {
    /// Longitudinal seam of a rolled part.
    LongSeam,
    /// Circumferential seam between two pressure parts.
    CircSeam,
    /// Nozzle or boot to its host.
    Nozzle,
    /// Flange to neck.
    Flange,
    /// Pad to neck (inner fillet).
    PadInner,
    /// Pad to host (outer fillet).
    PadOuter,
    /// Support to the vessel.
    Support,
}

/// One weld.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Weld {
    /// Stable id: `L-S1` (long seam), `C-S1-H2`, `N-N1`, `F-N1`, `PI-N1`,
    /// `PO-N1`, `S-SK`.
    pub id: String,
    /// Kind.
    pub kind: WeldKind,
    /// UW-3 category; `None` for attachments.
    pub category: Option<Category>,
    /// The two things joined (part ids, nozzle marks, `mark/flange`, `mark/pad`).
    pub joins: [String; 2],
    /// The plan item whose operation makes this weld.
    pub item: String,
    /// Length, mm.
    pub length: f64,
    /// Thickness the weld is sized by, mm.
    pub thickness: f64,
    /// Preparation id.
    pub prep: String,
    /// Joint type.
    pub joint: String,
    /// Weld-metal volume, mm³.
    pub volume: f64,
    /// The weld's curve, vessel frame, mm (empty where not drawn).
    #[serde(skip)]
    pub path: Vec<DVec3>,
    /// Whether `path` closes.
    #[serde(skip)]
    pub closed: bool,
}

/// Thickness of part `id`, or `None`.
pub fn part_thickness(design: &VesselDesign, id: &str) -> Option<f64> {
    design
        .parts
        .iter()
        .find(|d| d.id() == id)
        .and_then(thickness)
}

/// Whether a part is in the pressure stack.
fn is_stack(g: &PartGeometry) -> bool {
    matches!(
        g,
        PartGeometry::Shell(_) | PartGeometry::Reducer(_) | PartGeometry::Head(_)
    )
}

struct Builder<'a> {
    rules: &'a ShopRules,
    welds: Vec<Weld>,
}

impl Builder<'_> {
    #[expect(
        clippy::too_many_arguments,
        reason = "one weld record's fields, named at each call"
    )]
    fn push(
        &mut self,
        id: String,
        kind: WeldKind,
        category: Option<Category>,
        joins: [String; 2],
        item: String,
        (length, thickness): (f64, f64),
        choice: &PrepChoice,
        (path, closed): (Vec<DVec3>, bool),
    ) {
        let prep_id = if thickness >= choice.thick_from {
            &choice.thick
        } else {
            &choice.thin
        };
        let (joint, area) = self.rules.prep(prep_id).map_or((String::new(), 0.0), |p| {
            (p.joint.clone(), cross_section(p, thickness))
        });
        self.welds.push(Weld {
            id,
            kind,
            category,
            joins,
            item,
            length,
            thickness,
            prep: prep_id.clone(),
            joint,
            volume: area * length,
            path,
            closed,
        });
    }
}

/// Samples of a circle of radius `r` about the axis at height `z` (centre
/// `(cx, cy)`), vessel frame.
fn circle(cx: f64, cy: f64, r: f64, z: f64) -> Vec<DVec3> {
    (0..96)
        .map(|i| {
            let a = TAU * f64::from(i) / 96.0;
            DVec3::new(cx + r * a.cos(), cy + r * a.sin(), z)
        })
        .collect()
}

/// The end of `part`'s mid-surface profile nearest `z`: (radius, centre).
fn joint_radius(part: StackPart, z: f64) -> Option<(f64, glam::DVec2)> {
    let profile = stack_profile(&[part], Surface::Middle, false).ok()?;
    let mut best: Option<(f64, f64, glam::DVec2)> = None;
    for (k, (piece, _)) in profile.pieces.iter().enumerate() {
        let (s0, s1) = piece.range();
        for s in [s0, s1] {
            let (r, pz) = piece.point(s);
            let d = (pz - z).abs();
            if best.is_none_or(|b| d < b.0) {
                best = Some((d, r, profile.centre(k).at(pz)));
            }
        }
    }
    best.map(|(_, r, c)| (r, c))
}

/// The shape of boot `id`'s head in `design`.
fn boot_head_shape(design: &VesselDesign, id: &str) -> Option<HeadShape> {
    design.parts.iter().find_map(|d| match d {
        PartDesign::Boot(b) if b.id == id => Some(b.head),
        _ => None,
    })
}

/// A boot's long seams (one per plate, at its first edge, as long as the
/// plate's generator there) and its circumferential seam to its head
/// (category by the head's shape, as the stack's joints).
fn boot_seams(b: &mut Builder, shell: &BootShell, plates: &[BootPlate], head: Option<HeadShape>) {
    let pf = b.rules.prep_for.clone();
    let at = |phi: f64, r: f64, z: f64| {
        shell
            .frame
            .transform_point3(DVec3::new(r * phi.cos(), r * phi.sin(), z))
    };
    for p in plates.iter().filter(|p| p.part == shell.id) {
        let high = p.outline.last().map_or(0.0, |q| q.y);
        let path = vec![
            at(p.from, shell.outside, shell.tangent),
            at(p.from, shell.outside, shell.tangent - high),
        ];
        b.push(
            format!("L-{}-{}", shell.id, p.index + 1),
            WeldKind::LongSeam,
            Some(Category::A),
            [shell.id.clone(), shell.id.clone()],
            shell.id.clone(),
            (high, shell.thickness),
            &pf.long_seam,
            (path, false),
        );
    }
    let head_id = boot_head_id(&shell.id);
    let category = match head {
        Some(HeadShape::Flat) => Category::C,
        Some(HeadShape::Hemispherical) => Category::A,
        _ => Category::B,
    };
    let ring = (0..96)
        .map(|k| at(TAU * f64::from(k) / 96.0, shell.radius, shell.tangent))
        .collect();
    b.push(
        format!("C-{}-{head_id}", shell.id),
        WeldKind::CircSeam,
        Some(category),
        [shell.id.clone(), head_id.clone()],
        format!("{}+{head_id}", shell.id),
        (TAU * shell.radius, shell.thickness),
        &pf.circ_seam,
        (ring, true),
    );
}

/// The weld map of the vessel planned as `fab`.
///
/// # Errors
///
/// [`PlanError::Model`] naming a nozzle or boot whose opening cannot be cut.
pub fn weld_map(fab: &FabPlan, rules: &ShopRules) -> Result<Vec<Weld>, PlanError> {
    let (design, resolved) = (&fab.vessel, &fab.resolved);
    let mut b = Builder {
        rules,
        welds: Vec::new(),
    };
    let pf = &rules.prep_for;
    let model_error = |entity: &str, message: String| PlanError::Model {
        vessel: resolved.tag.clone(),
        entity: entity.to_string(),
        message,
    };
    // Long seams of every course, and the circumferential seams between the
    // courses of one part, from the plate layout.
    for (ci, course) in fab.seams.courses.iter().enumerate() {
        let rolled = &fab.developments.rolled[course.rolled];
        let pressure = rolled.kind != RolledKind::Skirt;
        let (z0, z1) = course.z;
        for k in 0..course.plates {
            let angle = course.seam(k);
            let at = |z: f64| {
                let r = rolled.outside_at(z);
                rolled.frame.transform_point3(rolled.point(angle, z, r))
            };
            let (p0, p1) = (at(z0), at(z1));
            b.push(
                format!("L-{}", course.seam_id(k)),
                WeldKind::LongSeam,
                pressure.then_some(Category::A),
                [rolled.id.clone(), rolled.id.clone()],
                rolled.id.clone(),
                (p0.distance(p1), rolled.thickness),
                &pf.long_seam,
                (vec![p0, p1], false),
            );
        }
        // The joint with the next course of the same part.
        let next = fab.seams.courses[ci + 1..]
            .iter()
            .find(|c| c.rolled == course.rolled && (c.z.0 - z1).abs() < 1e-9);
        if let Some(next) = next {
            let r = rolled.radius_at(z1);
            let ring = (0..96)
                .map(|i| {
                    let a = TAU * f64::from(i) / 96.0;
                    rolled.frame.transform_point3(rolled.point(a, z1, r))
                })
                .collect();
            let item = format!("{}+{}", course.id, next.id);
            b.push(
                format!("C-{}-{}", course.id, next.id),
                WeldKind::CircSeam,
                pressure.then_some(Category::B),
                [rolled.id.clone(), rolled.id.clone()],
                item,
                (TAU * r, rolled.thickness),
                &pf.circ_seam,
                (ring, true),
            );
        }
    }
    // Circumferential seams between neighbours of the stack, design order.
    let stack: Vec<usize> = (0..resolved.parts.len())
        .filter(|&i| is_stack(&resolved.parts[i].geometry) && resolved.parts[i].host.is_none())
        .collect();
    for pair in stack.windows(2) {
        let (a, bb) = (&resolved.parts[pair[0]], &resolved.parts[pair[1]]);
        let (ta, tb) = (
            part_thickness(design, &a.id).unwrap_or(0.0),
            part_thickness(design, &bb.id).unwrap_or(0.0),
        );
        let z = if (a.span.1 - bb.span.0).abs() <= (bb.span.1 - a.span.0).abs() {
            a.span.1
        } else {
            a.span.0
        };
        let (thin, t) = if ta <= tb { (a, ta) } else { (bb, tb) };
        let sp = StackPart {
            id: &thin.id,
            geometry: &thin.geometry,
            frame: thin.frame,
            thickness: t,
        };
        let Some((r, c)) = joint_radius(sp, z) else {
            continue;
        };
        let head_shape = |id: &str| {
            design.parts.iter().find_map(|d| match d {
                PartDesign::Head(h) if h.id == id => Some(h.shape),
                _ => None,
            })
        };
        let shapes = [head_shape(&a.id), head_shape(&bb.id)];
        let category = if shapes.contains(&Some(HeadShape::Flat)) {
            Category::C
        } else if shapes.contains(&Some(HeadShape::Hemispherical)) {
            Category::A
        } else {
            Category::B
        };
        let item = format!("{}+{}", a.id, bb.id);
        b.push(
            format!("C-{}-{}", a.id, bb.id),
            WeldKind::CircSeam,
            Some(category),
            [a.id.clone(), bb.id.clone()],
            item,
            (TAU * r, t),
            &pf.circ_seam,
            (circle(c.x, c.y, r, z), true),
        );
    }
    // Nozzles, their flanges and pads.
    for (i, (n, nd)) in resolved.nozzles.iter().zip(&design.nozzles).enumerate() {
        let Some(host) = resolved.parts.get(n.host) else {
            continue;
        };
        let host_t = part_thickness(design, &host.id).unwrap_or(0.0);
        let curves = nozzle_curves(resolved, i).map_err(|m| model_error(&n.mark, m))?;
        let neck_len = closed_length(&curves.neck);
        b.push(
            format!("N-{}", n.mark),
            WeldKind::Nozzle,
            Some(Category::D),
            [n.mark.clone(), host.id.clone()],
            n.mark.clone(),
            (neck_len, host_t),
            &pf.nozzle,
            (curves.neck.clone(), true),
        );
        let row = pipe(n.geometry.nps);
        let wall = row.wall(n.geometry.schedule).unwrap_or(0.0);
        let (ro, ri) = (
            row.outside_diameter / 2.0,
            row.outside_diameter / 2.0 - wall,
        );
        let weld_z = n.geometry.neck_length().unwrap_or(0.0);
        let ring = circle(0.0, 0.0, ro, weld_z)
            .into_iter()
            .map(|p| n.frame.transform_point3(p))
            .collect();
        let length = match nd.flange {
            FlangeDesign::SlipOn => TAU * (ro + ri),
            _ => PI * (ro + ri),
        };
        b.push(
            format!("F-{}", n.mark),
            WeldKind::Flange,
            Some(Category::C),
            [format!("{}/flange", n.mark), n.mark.clone()],
            n.mark.clone(),
            (length, wall),
            if nd.flange == FlangeDesign::SlipOn {
                &pf.attachment
            } else {
                &pf.flange
            },
            (ring, true),
        );
        if let (Some((_, pad_t)), Some(outer)) = (n.pad, curves.pad) {
            let pad = format!("{}/pad", n.mark);
            b.push(
                format!("PI-{}", n.mark),
                WeldKind::PadInner,
                None,
                [pad.clone(), n.mark.clone()],
                pad.clone(),
                (neck_len, pad_t.min(wall)),
                &pf.attachment,
                (curves.neck, true),
            );
            b.push(
                format!("PO-{}", n.mark),
                WeldKind::PadOuter,
                None,
                [pad.clone(), host.id.clone()],
                pad,
                (closed_length(&outer), pad_t.min(host_t)),
                &pf.attachment,
                (outer, true),
            );
        }
    }
    // Boots and supports.
    let boot_plates = fab.boot_plates();
    for (i, part) in resolved.parts.iter().enumerate() {
        let host_t = |host: Option<usize>| {
            host.and_then(|h| resolved.parts.get(h))
                .and_then(|h| part_thickness(design, &h.id))
                .unwrap_or(DEFAULT_PLATE)
        };
        let support = |b: &mut Builder, host: String, length: f64, t: f64, path: Vec<DVec3>| {
            let closed = path.len() > 2;
            b.push(
                format!("S-{}", part.id),
                WeldKind::Support,
                None,
                [part.id.clone(), host],
                part.id.clone(),
                (length, t),
                &pf.attachment,
                (path, closed),
            );
        };
        let host_of = |z: f64| {
            stack
                .iter()
                .map(|&k| &resolved.parts[k])
                .min_by(|p, q| {
                    let d = |p: &crate::constraints::ResolvedPart| {
                        (p.span.0 - z).max(z - p.span.1).max(0.0)
                    };
                    d(p).total_cmp(&d(q))
                })
                .map(|p| (p.id.clone(), part_thickness(design, &p.id).unwrap_or(0.0)))
                .unwrap_or_default()
        };
        match &part.geometry {
            PartGeometry::Boot(_) => {
                let host = part.host.and_then(|h| resolved.parts.get(h));
                let curve = boot_curve(resolved, i).map_err(|m| model_error(&part.id, m))?;
                b.push(
                    format!("N-{}", part.id),
                    WeldKind::Nozzle,
                    Some(Category::D),
                    [
                        part.id.clone(),
                        host.map(|h| h.id.clone()).unwrap_or_default(),
                    ],
                    part.id.clone(),
                    (closed_length(&curve), host_t(part.host)),
                    &pf.nozzle,
                    (curve, true),
                );
                if let Some(shell) = fab.developments.boots.iter().find(|s| s.part == i) {
                    boot_seams(
                        &mut b,
                        shell,
                        &boot_plates,
                        boot_head_shape(design, &part.id),
                    );
                }
            }
            PartGeometry::Skirt(s) => {
                let top = part.frame.transform_point3(DVec3::new(0.0, 0.0, s.height));
                let (host, ht) = host_of(top.z);
                let r = s.top_diameter / 2.0 - s.thickness / 2.0;
                support(
                    &mut b,
                    host,
                    TAU * r,
                    s.thickness.min(ht.max(0.0)).max(0.0),
                    circle(top.x, top.y, r, top.z),
                );
            }
            PartGeometry::Saddle(s) => {
                let (host, ht) = host_of(0.5 * (part.span.0 + part.span.1));
                let arc = s.contact_angle.to_radians() * s.shell_diameter / 2.0;
                support(
                    &mut b,
                    host,
                    2.0 * (arc + s.width),
                    s.web_thickness.min(ht),
                    Vec::new(),
                );
            }
            PartGeometry::Legs(l) => {
                let (host, ht) = host_of(part.span.1);
                support(
                    &mut b,
                    host,
                    f64::from(l.count) * PI * l.pipe_diameter,
                    DEFAULT_PLATE.min(ht),
                    Vec::new(),
                );
            }
            PartGeometry::Lugs(l) => {
                let (host, ht) = host_of(0.5 * (part.span.0 + part.span.1));
                support(
                    &mut b,
                    host,
                    f64::from(l.count) * 4.0 * l.height,
                    DEFAULT_PLATE.min(ht),
                    Vec::new(),
                );
            }
            _ => {}
        }
    }
    Ok(b.welds)
}
