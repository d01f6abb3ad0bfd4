//! A horizontal vessel's two saddles checked by Zick's method ([`super::zick`])
//! in two load cases from the one weight model: **operating** (operating weight,
//! design pressure, hot and corroded walls, S at the design temperature) and
//! **hydrotest** (full of water, the UG-99(b) test pressure at the top, new walls,
//! S at the test temperature). Each saddle's load is its reaction by statics
//! from the case's centre of gravity along the axis.
//!
//! Allowables (Zick's, as Moss Procedure 3-9 and Megyesy list them):
//! - S1 in tension plus the longitudinal pressure stress P·R/(2·ts) ≤ S·E;
//! - S1 in compression (pressure off) ≤ min(S, B), B of UG-23(b) at
//!   A = 0.125·ts/R. Choice: B is taken as min(A·E/2, Sy/4) — the chart's elastic
//!   line, capped where that line reaches half the yield strength (the limit
//!   `external` uses); the material charts (licensed) only rise above that cap,
//!   so the figure can only be low;
//! - S2 (shell and head) ≤ 0.8·S;
//! - the head's additional stress plus its pressure stress ≤ 1.25·S. Choice: the
//!   pressure stress is taken as P·R/th, which no dished head's crown membrane
//!   stress exceeds (a torispherical head with crown radius D reaches it);
//! - |S3| at the horn ≤ 1.5·S;
//! - |S4| at the bottom ≤ 0.5·Sy.
//!
//! Other choices: R is the mean radius of the course under the saddle (corroded
//! in the operating case); H is the outside depth of the dished end nearer the
//! saddle at the saddle, and of the shallower end at midspan (each the safe side
//! of its formula); a wear plate is counted only where the design gives one
//! (`wear_plate`, reaching R/10 above the horns).

use serde::Serialize;

use super::zick::{Saddle, Stresses, stresses};
use super::{Conditions, GRAVITY};
use crate::constraints::{PartGeometry, ResolvedVessel};
use crate::design::{PartDesign, VesselDesign, VesselKind};
use crate::operating::thickness;
use crate::weights::Weights;

/// One allowable-stress check.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Check {
    /// What is checked, e.g. `S3 at the horn`.
    pub name: &'static str,
    /// The stress (absolute value for compression), MPa.
    pub stress: f64,
    /// The allowable, MPa.
    pub allowable: f64,
    /// The allowable's rule, e.g. `1.5·S`.
    pub rule: &'static str,
}

impl Check {
    /// Whether the stress is within the allowable.
    pub fn ok(&self) -> bool {
        self.stress <= self.allowable
    }
}

/// One saddle in one load case.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct SaddleCase {
    /// The saddle's part id.
    pub saddle: String,
    /// `operating` or `hydrotest`.
    pub case: &'static str,
    /// The case's weight, kg.
    pub mass: f64,
    /// Pressure at the top in the case, MPa.
    pub pressure: f64,
    /// Zick's inputs (load in N).
    pub input: Saddle,
    /// Zick's stresses.
    pub stresses: Stresses,
    /// The checks against the allowables.
    pub checks: Vec<Check>,
}

impl SaddleCase {
    /// The sentences of the checks that fail.
    pub fn deficiencies(&self) -> impl Iterator<Item = String> + '_ {
        self.checks.iter().filter(|c| !c.ok()).map(move |c| {
            format!(
                "{} ({}): Zick {} = {:.1} MPa exceeds {} = {:.1} MPa (Q = {:.1} kN, A = {:.0} mm)",
                self.saddle,
                self.case,
                c.name,
                c.stress,
                c.rule,
                c.allowable,
                self.input.load * 1e-3,
                self.input.a
            )
        })
    }
}

/// Where a saddle sits and what it carries, from the design.
struct Seat {
    id: String,
    position: f64,
    width: f64,
    theta: f64,
    wear_plate: f64,
    shell_od: f64,
    shell_t: f64,
    head_t: f64,
    head_depth: f64,
}

fn seats(design: &VesselDesign, resolved: &ResolvedVessel) -> Result<Vec<Seat>, String> {
    let thickness_of = |id: &str| {
        design
            .parts
            .iter()
            .find(|p| p.id() == id)
            .and_then(thickness)
    };
    let heads: Vec<(f64, f64, f64)> = resolved
        .parts
        .iter()
        .filter_map(|p| match &p.geometry {
            PartGeometry::Head(h) => Some((
                (p.span.0 + p.span.1) / 2.0,
                h.depth().ok()?,
                thickness_of(&p.id)?,
            )),
            _ => None,
        })
        .collect();
    let mut out = Vec::new();
    for p in &resolved.parts {
        let PartGeometry::Saddle(s) = &p.geometry else {
            continue;
        };
        let position = (p.span.0 + p.span.1) / 2.0;
        let course = resolved.parts.iter().find(|c| {
            matches!(c.geometry, PartGeometry::Shell(_))
                && c.span.0 <= position
                && position <= c.span.1
        });
        let Some(course) = course else {
            return Err(format!("{}: no shell course over the saddle", p.id));
        };
        let shell_t = thickness_of(&course.id)
            .ok_or_else(|| format!("{}: course {} has no thickness", p.id, course.id))?;
        let Some(&(_, head_depth, head_t)) = heads
            .iter()
            .min_by(|a, b| (a.0 - position).abs().total_cmp(&(b.0 - position).abs()))
        else {
            return Err(format!(
                "{}: the vessel has no dished heads with a thickness",
                p.id
            ));
        };
        let wear_plate = design
            .parts
            .iter()
            .find_map(|d| match d {
                PartDesign::Saddle(d) if d.id == p.id => d.wear_plate,
                _ => None,
            })
            .unwrap_or(0.0);
        out.push(Seat {
            id: p.id.clone(),
            position,
            width: s.width,
            theta: s.contact_angle,
            wear_plate,
            shell_od: s.shell_diameter,
            shell_t,
            head_t,
            head_depth,
        });
    }
    Ok(out)
}

/// UG-23(b)'s B at A = 0.125·t/R, taken on the elastic line and capped at Sy/4
/// (see the module documentation), MPa.
pub fn compressive_b(t: f64, r: f64, modulus: f64, yield_strength: f64) -> f64 {
    let a = 0.125 * t / r;
    (a * modulus / 2.0).min(yield_strength / 4.0)
}

/// The saddles of a horizontal vessel checked in both cases; `Ok(empty)` for a
/// vessel without saddles; `Err` with the reason when Zick's method does not
/// apply (not two saddles, a saddle off the shell, a missing thickness).
pub fn saddle_cases(
    design: &VesselDesign,
    resolved: &ResolvedVessel,
    c: &Conditions,
    weights: &Weights,
    hydrotest: Option<f64>,
) -> Result<Vec<SaddleCase>, String> {
    if design.kind != VesselKind::Horizontal {
        return Ok(Vec::new());
    }
    let seats = seats(design, resolved)?;
    if seats.is_empty() {
        return Ok(Vec::new());
    }
    if seats.len() != 2 {
        return Err(format!(
            "Zick's method is for two saddles; the vessel has {}",
            seats.len()
        ));
    }
    let l = resolved.tangent_length;
    let local = resolved.frame.inverse();
    let axial = |cog: [f64; 3]| local.transform_point3(glam::DVec3::from(cog)).z;
    let h_mid = seats
        .iter()
        .map(|s| s.head_depth)
        .fold(f64::INFINITY, f64::min);
    let mut cases = Vec::new();
    let test = hydrotest.map(|p| ("hydrotest", weights.test, weights.cog_test, p));
    for (case, mass, cog, pressure) in [(
        "operating",
        weights.operating,
        weights.cog_operating,
        c.pressure,
    )]
    .into_iter()
    .chain(test)
    {
        let (x1, x2) = (seats[0].position, seats[1].position);
        if (x2 - x1).abs() < 1e-9 {
            return Err("Zick: the two saddles stand at the same position".into());
        }
        let xg = axial(cog);
        let weight = mass * GRAVITY;
        let q1 = weight * (x2 - xg) / (x2 - x1);
        let reactions = [q1, weight - q1];
        let corroded = case == "operating";
        let ca = if corroded { c.corrosion_allowance } else { 0.0 };
        let stress = if corroded { c.stress } else { c.stress_test };
        for (seat, q) in seats.iter().zip(reactions) {
            let ts = seat.shell_t - ca;
            let th = seat.head_t - ca;
            let r = (seat.shell_od - ts) / 2.0;
            let a = seat.position.min(l - seat.position);
            let input = Saddle {
                load: q,
                a,
                l,
                r,
                ts,
                th,
                h: seat.head_depth,
                b: seat.width,
                theta: seat.theta,
                wear_plate: seat.wear_plate,
            };
            let at_saddle = stresses(&input).map_err(|e| format!("{}: {e}", seat.id))?;
            // Midspan with the shallower head (larger sagging moment).
            let mid =
                stresses(&Saddle { h: h_mid, ..input }).map_err(|e| format!("{}: {e}", seat.id))?;
            let longitudinal = pressure * r / (2.0 * ts);
            let b = compressive_b(ts, r, c.modulus, c.yield_strength);
            let mut checks = vec![
                Check {
                    name: "S1 at the saddle + P·R/2ts (tension)",
                    stress: at_saddle.s1_saddle_top.max(at_saddle.s1_saddle_bottom) + longitudinal,
                    allowable: stress * c.joint_efficiency,
                    rule: "S·E",
                },
                Check {
                    name: "S1 at midspan + P·R/2ts (tension)",
                    stress: mid.s1_midspan.abs() + longitudinal,
                    allowable: stress * c.joint_efficiency,
                    rule: "S·E",
                },
                Check {
                    name: "S1 (compression)",
                    stress: (-at_saddle.s1_saddle_bottom)
                        .max(-at_saddle.s1_saddle_top)
                        .max(mid.s1_midspan.abs()),
                    allowable: stress.min(b),
                    rule: "min(S, B of UG-23(b))",
                },
                Check {
                    name: "S2 in the shell (shear)",
                    stress: at_saddle.s2_shell,
                    allowable: 0.8 * stress,
                    rule: "0.8·S",
                },
            ];
            if let (Some(s2h), Some(add)) = (at_saddle.s2_head, at_saddle.head_additional) {
                checks.push(Check {
                    name: "S2 in the head (shear)",
                    stress: s2h,
                    allowable: 0.8 * stress,
                    rule: "0.8·S",
                });
                checks.push(Check {
                    name: "head additional + P·R/th",
                    stress: add + pressure * r / th,
                    allowable: 1.25 * stress,
                    rule: "1.25·S",
                });
            }
            checks.push(Check {
                name: "S3 at the horn",
                stress: at_saddle.s3_horn.abs(),
                allowable: 1.5 * stress,
                rule: "1.5·S",
            });
            checks.push(Check {
                name: "S4 at the bottom",
                stress: at_saddle.s4_bottom.abs(),
                allowable: 0.5 * c.yield_strength,
                rule: "0.5·Sy",
            });
            let mut st = at_saddle;
            st.m_midspan = mid.m_midspan;
            st.s1_midspan = mid.s1_midspan;
            cases.push(SaddleCase {
                saddle: seat.id.clone(),
                case,
                mass,
                pressure,
                input,
                stresses: st,
                checks,
            });
        }
    }
    Ok(cases)
}
