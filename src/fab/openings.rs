//! Nozzle openings, reinforcing pads and neck saddle cuts, developed from the
//! exact intersection of the cutting cylinder with the plate's surface.
//!
//! A neck is a cylinder about its axis; a shell course is a cylinder about
//! the part's axis. For every angle φ about the neck axis the point of the
//! cutting cylinder (radius ρ) on the course's cylinder (radius R) is the
//! larger root of a quadratic in the distance along the neck axis, so every
//! point of a developed outline is a point of the exact intersection curve
//! (`crossing`), unrolled by `u = R·θ`, `v = z`. The outlines are sampled
//! densely enough for the shop's chord tolerance (the curve between two
//! samples stays within it).
//!
//! - **Opening** in the course: the cutting cylinder is the neck's outside
//!   plus the bevel allowance (set-in) or its bore (set-on), on the
//!   course's mid-surface.
//! - **Pad**: the pad is the region of the shell's outside covered by a
//!   cylinder of the pad's diameter; it is developed on its own mid-surface
//!   (radius `R_o + t_pad/2`) with the neck's hole in it; its footprint on
//!   the shell's outside is what seams keep clear of.
//! - **Saddle**: the neck's end, developed on the neck's own mid-surface
//!   (`x = r·φ`): the length from the cut to the flange's back at each φ,
//!   the cut being where the neck meets the shell's inside (set-in) or
//!   outside (set-on).
//!
//! - **Boot**: a boot is cut into its course like a set-in (or set-on) neck
//!   ([`cut_boot`]): its opening in the course's plate, and its host end
//!   developed on its own mid-surface, measured from its head's tangent line.
//!
//! Openings on cones, concentric or eccentric reducers' oblique ones, are
//! developed onto the cone's plates the same way, on the cone's
//! mid-surface ([`super::cone_openings`]); openings on heads are marked on
//! the head's blank and cut after forming ([`super::head_map`]).

use std::f64::consts::TAU;

use glam::DVec2;

use super::cone_openings;
use super::cut::saddle;
pub use super::cut::{NozzleCut, PadPiece, polygon_area};
use super::develop::{BootShell, Developments, RolledKind};
pub use super::neck_axis::{NeckAxis, SurfaceLoop, samples, theta_near};
use super::shop::{Attachment, Shop};
use crate::constraints::ResolvedVessel;
use crate::format::RuleViolation;
use crate::parts::tables::pipe;

/// A nozzle whose opening is cut after forming.
#[derive(Clone, Debug, PartialEq)]
pub struct FormedOpening {
    /// Mark.
    pub mark: String,
    /// Host part id.
    pub host: String,
    /// Its opening (and pad) mapped onto the head's blank (by
    /// [`super::vessel_plan::plan_vessel`] with `head_map::blank_mark`),
    /// `None` on a head without blank.
    pub blank: Option<BlankMark>,
}

/// A head opening mapped onto the head's blank by the forming rule of
/// [`super::head_map`]: blank coordinates, centre at the pole, +x along the
/// head's local +X.
#[derive(Clone, Debug, PartialEq)]
pub struct BlankMark {
    /// Index of the nozzle in the resolved vessel.
    pub nozzle: usize,
    /// Radius of the cutting cylinder, mm.
    pub cut_radius: f64,
    /// Where the nozzle axis meets the mid-surface, mapped, mm.
    pub centre: DVec2,
    /// The opening (cutting cylinder ∩ mid-surface), mapped, mm.
    pub outline: Vec<DVec2>,
    /// The pad's outline (pad cylinder ∩ mid-surface), mapped, mm.
    pub pad: Option<Vec<DVec2>>,
}

/// The openings of one vessel.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Openings {
    /// Cuts on cylindrical courses, in nozzle order.
    pub cuts: Vec<NozzleCut>,
    /// Openings on heads, cut after forming.
    pub formed: Vec<FormedOpening>,
    /// Openings on cones (concentric, and eccentric reducers' oblique
    /// ones), developed onto their plates, in nozzle order.
    pub cones: Vec<NozzleCut>,
    /// Boots cut into their courses, in part order.
    pub boots: Vec<NozzleCut>,
}

/// The loop where the cylinder of radius `rho` about `neck` meets the
/// cylinder of radius `big`, in surface coordinates about `centre_theta`;
/// `None` where part of it misses.
pub fn surface_loop(
    neck: &NeckAxis,
    rho: f64,
    big: f64,
    centre_theta: f64,
    n: usize,
) -> Option<SurfaceLoop> {
    (0..n)
        .map(|i| {
            let phi = TAU * i as f64 / n as f64;
            neck.crossing(rho, big, phi)
                .map(|(p, _)| DVec2::new(theta_near(p, centre_theta), p.z))
        })
        .collect()
}

/// What one nozzle gives: a cut developed on its course, or an opening cut
/// after forming.
#[derive(Clone, Debug, PartialEq)]
pub enum NozzleOutcome {
    /// On a cylindrical course.
    Cut(Box<NozzleCut>),
    /// On a cone (concentric or oblique), developed onto its plate.
    Cone(Box<NozzleCut>),
    /// On a head.
    Formed(FormedOpening),
}

impl Openings {
    /// Every cut in a course: the nozzles' then the boots'.
    pub fn all(&self) -> impl Iterator<Item = &NozzleCut> {
        self.cuts.iter().chain(&self.boots)
    }

    /// Adds one nozzle's outcome in its list.
    pub fn push(&mut self, o: NozzleOutcome) {
        match o {
            NozzleOutcome::Cut(c) => self.cuts.push(*c),
            NozzleOutcome::Cone(c) => self.cones.push(*c),
            NozzleOutcome::Formed(f) => self.formed.push(f),
        }
    }
}

/// Finds every nozzle's cuts (head openings unmapped: `plan_vessel` maps
/// them onto their blanks).
///
/// # Errors
///
/// A violation per nozzle whose neck or pad does not lie wholly on its
/// course, or whose pipe schedule is not listed.
pub fn cut_openings(
    vessel_index: usize,
    resolved: &ResolvedVessel,
    developments: &Developments,
    shop: &Shop,
) -> Result<Openings, Vec<RuleViolation>> {
    let mut out = Openings::default();
    let mut errors = Vec::new();
    for index in 0..resolved.nozzles.len() {
        match cut_nozzle(vessel_index, resolved, developments, shop, index) {
            Ok(o) => out.push(o),
            Err(e) => errors.push(e),
        }
    }
    if errors.is_empty() {
        Ok(out)
    } else {
        Err(errors)
    }
}

/// The index in `developments.rolled` of the course nozzle `index` of
/// `resolved` is cut into, if its host is a cylindrical course.
pub fn host_course(
    resolved: &ResolvedVessel,
    developments: &Developments,
    index: usize,
) -> Option<usize> {
    let host = resolved.nozzles[index].host;
    developments
        .rolled
        .iter()
        .position(|r| r.part == host && r.kind == RolledKind::Course)
}

/// Develops the cuts of nozzle `index` of `resolved`.
///
/// # Errors
///
/// A violation naming the nozzle when its neck or pad does not lie wholly on
/// its course, or its pipe schedule is not listed.
pub fn cut_nozzle(
    vessel_index: usize,
    resolved: &ResolvedVessel,
    developments: &Developments,
    shop: &Shop,
    index: usize,
) -> Result<NozzleOutcome, RuleViolation> {
    let nozzle = &resolved.nozzles[index];
    let path = format!("vessels[{vessel_index}].nozzles[{index}]");
    let entity = format!("{}/{}", resolved.tag, nozzle.mark);
    let host = &resolved.parts[nozzle.host];
    if let Some(cone) = cone_openings::host_cone(resolved, developments, index) {
        return cone_openings::cut_cone_nozzle(
            vessel_index,
            resolved,
            developments,
            shop,
            index,
            cone,
        )
        .map(|c| NozzleOutcome::Cone(Box::new(c)));
    }
    let Some(rolled_index) = host_course(resolved, developments, index) else {
        return Ok(NozzleOutcome::Formed(FormedOpening {
            mark: nozzle.mark.clone(),
            host: host.id.clone(),
            // Mapped onto a head's blank by `head_map::blank_mark`.
            blank: None,
        }));
    };
    let course = &developments.rolled[rolled_index];
    let bad = |field: &str, value: String, rule: String| RuleViolation {
        path: format!("{path}.{field}"),
        entity: entity.clone(),
        field: field.into(),
        value,
        rule,
    };
    let g = &nozzle.geometry;
    let dims = pipe(g.nps);
    let wall = match dims.wall(g.schedule) {
        Ok(w) => w,
        Err(e) => return Err(bad("schedule", g.schedule.label().into(), e.to_string())),
    };
    let od = dims.outside_diameter;
    let cut_radius = shop.cut_radius(od, wall);
    let neck = NeckAxis::new(course.frame, nozzle.frame);
    let r_mid = course.radius.0;
    let r_out = course.outside.0;
    let misses = |what: &str| {
        bad(
            "offset",
            "-".into(),
            format!(
                "the {what} must lie wholly on course {}/{} to be developed",
                resolved.tag, course.id
            ),
        )
    };
    let Some((centre, _)) = neck.crossing(0.0, r_mid, 0.0) else {
        return Err(misses("nozzle axis"));
    };
    let theta = centre.y.atan2(centre.x);
    let n = samples(cut_radius, shop.chord_tolerance);
    let Some(hole) = surface_loop(&neck, cut_radius, r_mid, theta, n) else {
        return Err(misses("opening"));
    };
    let pad = match nozzle.pad {
        None => None,
        Some((pad_od, pad_t)) => {
            let r_pad = r_out + 0.5 * pad_t;
            let n_pad = samples(0.5 * pad_od, shop.chord_tolerance);
            let footprint = surface_loop(&neck, 0.5 * pad_od, r_out, theta, n_pad);
            let develop = |rho: f64, n: usize| -> Option<Vec<DVec2>> {
                let (c, _) = neck.crossing(0.0, r_pad, 0.0)?;
                let tc = c.y.atan2(c.x);
                let curve = surface_loop(&neck, rho, r_pad, tc, n)?;
                Some(
                    curve
                        .iter()
                        .map(|q| DVec2::new(r_pad * (q.x - tc), q.y - c.z))
                        .collect(),
                )
            };
            let outline = develop(0.5 * pad_od, n_pad);
            let pad_hole = develop(0.5 * od + shop.bevel_allowance, n);
            match (footprint, outline, pad_hole) {
                (Some(footprint), Some(outline), Some(hole)) => Some(PadPiece {
                    od: pad_od,
                    thickness: pad_t,
                    footprint,
                    outline,
                    hole,
                    apex: None,
                }),
                _ => return Err(misses("pad")),
            }
        }
    };
    // The neck meets the shell's inside (set-in) or outside (set-on).
    let meets = match shop.attachment {
        Attachment::SetIn => r_out - course.thickness,
        Attachment::SetOn => r_out,
    };
    let neck_mid = 0.5 * (od - wall);
    let back = g.projection - g.flange_length().unwrap_or(0.0);
    let saddle = saddle(n, neck_mid, back, |phi| {
        neck.crossing(neck_mid, meets, phi).map(|(_, s)| s)
    });
    let Some(saddle) = saddle else {
        return Err(misses("neck"));
    };
    Ok(NozzleOutcome::Cut(Box::new(NozzleCut {
        nozzle: index,
        mark: nozzle.mark.clone(),
        path,
        rolled: rolled_index,
        neck,
        cut_radius,
        centre: DVec2::new(theta, centre.z),
        hole,
        pad,
        saddle,
    })))
}

/// Cuts boot `boot` into its host course: its opening developed on the
/// course's mid-surface (the cutting cylinder the boot's outside plus the
/// bevel allowance set-in, its bore set-on), and its host end developed on
/// the boot's mid-surface, `(r·φ, length from the cut to the head's tangent
/// line)`, the cut where the boot meets the course's inside (set-in) or
/// outside (set-on). The host end is sampled at a multiple of the boot's
/// plate count ([`BootShell::plate_count`]) so every plate seam is a
/// sample.
///
/// # Errors
///
/// A violation naming the boot when its host is not a cylindrical course or
/// the boot does not lie wholly on it.
pub fn cut_boot(
    resolved: &ResolvedVessel,
    developments: &Developments,
    shop: &Shop,
    boot: &BootShell,
) -> Result<NozzleCut, RuleViolation> {
    let host = &resolved.parts[boot.host];
    let bad = |rule: String| RuleViolation {
        path: format!("{}.position", boot.path),
        entity: format!("{}/{}", resolved.tag, boot.id),
        field: "position".into(),
        value: "-".into(),
        rule,
    };
    let Some(rolled) = developments
        .rolled
        .iter()
        .position(|r| r.part == boot.host && r.kind == RolledKind::Course)
    else {
        return Err(bad(format!(
            "a boot is developed on a cylindrical course; its host {}/{} is not one",
            resolved.tag, host.id
        )));
    };
    let course = &developments.rolled[rolled];
    let misses = |what: &str| {
        bad(format!(
            "the boot's {what} must lie wholly on course {}/{} to be developed",
            resolved.tag, course.id
        ))
    };
    let neck = NeckAxis::new(course.frame, boot.frame);
    let cut_radius = match shop.attachment {
        Attachment::SetIn => boot.outside + shop.bevel_allowance,
        Attachment::SetOn => boot.outside - boot.thickness,
    };
    let (r_mid, r_out) = (course.radius.0, course.outside.0);
    let Some((centre, _)) = neck.crossing(0.0, r_mid, 0.0) else {
        return Err(misses("axis"));
    };
    let theta = centre.y.atan2(centre.x);
    let n = samples(cut_radius, shop.chord_tolerance);
    let Some(hole) = surface_loop(&neck, cut_radius, r_mid, theta, n) else {
        return Err(misses("opening"));
    };
    let meets = match shop.attachment {
        Attachment::SetIn => r_out - course.thickness,
        Attachment::SetOn => r_out,
    };
    let plates = boot.plate_count(shop.max_plate_length);
    let m = n.div_ceil(plates) * plates;
    let saddle: Option<Vec<DVec2>> = (0..=m)
        .map(|i| {
            let phi = TAU * i as f64 / m as f64;
            neck.crossing(boot.radius, meets, phi)
                .map(|(_, s)| DVec2::new(boot.radius * phi, boot.tangent - s))
        })
        .collect();
    let Some(saddle) = saddle else {
        return Err(misses("host end"));
    };
    Ok(NozzleCut {
        nozzle: boot.part,
        mark: boot.id.clone(),
        path: boot.path.clone(),
        rolled,
        neck,
        cut_radius,
        centre: DVec2::new(theta, centre.z),
        hole,
        pad: None,
        saddle,
    })
}
