//! A nozzle calculated: UG-45 neck thickness, UG-37 reinforcement of its opening
//! (with its pad from the model, [`super::reinforcement`]) and the B16.5 rating
//! of its flange ([`super::flange`]).
//!
//! UG-45 nozzle neck thickness: the neck must be at least the larger of t_a (the
//! neck's own UG-27 thickness under the pressure on its host, plus corrosion) and
//! t_b, the smaller of the host's required thickness at E = 1 (not less than the
//! UG-16(b) minimum) and the standard-wall pipe less its 12.5 % mill tolerance,
//! each plus corrosion. The neck's available wall is its schedule's nominal wall
//! less the same 12.5 % tolerance (UG-16(d)).

use serde::Serialize;

use super::external::required_long_cylinder;
use super::flange::flange_rating;
use super::reinforcement::{Opening, reinforcement, reinforcement_external};
use super::shells::circumferential_thickness;
use super::vessel::UG16_MINIMUM;
use super::{Conditions, FlangeRating, PartCalc, Reinforcement};
use crate::parts::Nozzle;
use crate::parts::tables::{PipeSchedule, pipe};

/// Mill undertolerance of pipe, ASTM A106 / A53: the wall may be 12.5 % thin.
pub const PIPE_UNDERTOLERANCE: f64 = 0.125;

/// The UG-45 check of one nozzle neck.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct NozzleCalc {
    /// Nozzle mark.
    pub mark: String,
    /// Host part id.
    pub host: String,
    /// Pressure on the host, MPa.
    pub pressure: f64,
    /// Neck outside diameter, mm.
    pub neck_od: f64,
    /// Neck nominal wall (its schedule), mm.
    pub nominal: f64,
    /// Nominal wall less the mill tolerance, mm.
    pub available: f64,
    /// t_a: the neck's UG-27(c)(1) thickness + CA, mm.
    pub t_a: f64,
    /// t_b1: the host's required thickness at E = 1 (at least UG-16(b)) + CA, mm.
    pub t_b1: f64,
    /// t_b3: standard wall less 12.5 % + CA, mm.
    pub t_b3: f64,
    /// UG-45 required neck thickness max(t_a, min(t_b1, t_b3)), mm.
    pub required: f64,
    /// Why the neck fails UG-45, when it does.
    pub deficiency: Option<String>,
    /// UG-37(c) reinforcement of the opening under internal pressure, when it
    /// could be calculated.
    pub reinforcement: Option<Reinforcement>,
    /// UG-37(d)(1) reinforcement of the opening under the design's external
    /// pressure, when it gives one and it could be calculated.
    pub reinforcement_external: Option<Reinforcement>,
    /// Why the reinforcement fails, when it does.
    pub reinforcement_deficiency: Option<String>,
    /// B16.5 rating of the flange, when its group's table is shipped.
    pub flange: Option<FlangeRating>,
    /// What was not calculated for this nozzle, and why.
    pub notes: Vec<String>,
}

impl NozzleCalc {
    /// Every deficiency of the nozzle: UG-45, UG-37, B16.5.
    pub fn deficiencies(&self) -> impl Iterator<Item = &String> {
        self.deficiency
            .iter()
            .chain(&self.reinforcement_deficiency)
            .chain(self.flange.iter().filter_map(|f| f.deficiency.as_ref()))
    }
}

/// UG-45, UG-37 and B16.5 of `nozzle` (mark `mark`, reinforcing `pad` as
/// `(outside diameter, thickness)`) on `host`, calculated under `c`. The neck, its
/// pad and its flange are taken of the vessel's material (the flange in its B16.5
/// group), the neck seamless (E = 1).
pub fn nozzle_calc(
    mark: &str,
    nozzle: &Nozzle,
    pad: Option<(f64, f64)>,
    host: &PartCalc,
    c: &Conditions,
) -> Result<NozzleCalc, String> {
    let fail = |e: String| format!("{mark}: {e}");
    if c.code == "API 650" {
        return Err(fail(if host.kind == "shell" {
            "API 650 shell nozzles (5.7, Tables 5-6 to 5-8) are not calculated".into()
        } else if host.shape == "tank bottom plate" {
            "API 650 bottom connections (5.7, Fig. 5-14 to 5-16) are not calculated".into()
        } else {
            "API 650 roof nozzles (5.8.5, Tables 5-16 to 5-19) are not calculated".into()
        }));
    }
    let row = pipe(nozzle.nps);
    let nominal = row.wall(nozzle.schedule).map_err(|e| fail(e.to_string()))?;
    let std_wall = row
        .wall(PipeSchedule::Std)
        .map_err(|e| fail(e.to_string()))?;
    let ca = c.corrosion_allowance;
    let od = row.outside_diameter;
    let inside_radius = od / 2.0 - nominal + ca;
    let t_a = circumferential_thickness(inside_radius, host.pressure, c.stress)
        .map_err(|e| fail(e.to_string()))?
        .value
        + ca;
    let t_b1 = host.required_seamless.max(UG16_MINIMUM + ca);
    let t_b3 = (1.0 - PIPE_UNDERTOLERANCE) * std_wall + ca;
    let required = t_a.max(t_b1.min(t_b3));
    let available = (1.0 - PIPE_UNDERTOLERANCE) * nominal;
    let deficiency = (available < required).then(|| {
        format!(
            "{mark}: neck wall {nominal} mm less 12.5 % = {available:.2} mm is thinner than UG-45's \
             {required:.2} mm (t_a {t_a:.2}, t_b1 {t_b1:.2}, t_b3 {t_b3:.2} mm)"
        )
    });
    let mut notes = Vec::new();
    let opening = match host.thickness {
        _ if host.pressure <= 0.0 => None,
        _ if host.shape == "flat head" => {
            notes.push(format!(
                "{mark}: UG-39 (openings in flat heads) is not calculated"
            ));
            None
        }
        None => {
            notes.push(format!(
                "{mark}: UG-37 needs the host {}'s thickness",
                host.id
            ));
            None
        }
        Some(wall) => match reinforcement(&Opening {
            pressure: host.pressure,
            stress: c.stress,
            corrosion_allowance: ca,
            neck_od: od,
            neck_wall: nominal,
            wall,
            wall_required: host.required_seamless - ca,
            host_diameter: host.inside_diameter,
            pad,
        }) {
            Ok(r) => Some(r),
            Err(e) => {
                notes.push(format!("{mark}: UG-37: {e}"));
                None
            }
        },
    };
    let external = match (&host.external_required, host.thickness) {
        _ if host.shape == "flat head" => None,
        (None, _) => None,
        (Some(Err(e)), _) => {
            notes.push(format!(
                "{mark}: UG-37(d) not calculated: the wall of {} under external pressure: {e}",
                host.id
            ));
            None
        }
        (Some(Ok(_)), None) => {
            notes.push(format!(
                "{mark}: UG-37(d) needs the host {}'s thickness",
                host.id
            ));
            None
        }
        (Some(Ok(tr)), Some(wall)) => {
            let opening = Opening {
                pressure: c.external_pressure,
                stress: c.stress,
                corrosion_allowance: ca,
                neck_od: od,
                neck_wall: nominal,
                wall,
                wall_required: *tr,
                host_diameter: host.inside_diameter,
                pad,
            };
            match required_long_cylinder(od, c.modulus, c.yield_strength, c.external_pressure)
                .map_err(|e| format!("the neck's wall under external pressure: {e}"))
                .and_then(|trn| reinforcement_external(&opening, trn).map_err(|e| e.to_string()))
            {
                Ok(r) => Some(r),
                Err(e) => {
                    notes.push(format!("{mark}: UG-37(d): {e}"));
                    None
                }
            }
        }
    };
    if host.pressure <= 0.0 && external.is_none() && host.external_required.is_none() {
        notes.push(format!(
            "{mark}: no pressure on {}: UG-37 not calculated",
            host.id
        ));
    }
    if let Some(note) = opening
        .as_ref()
        .or(external.as_ref())
        .and_then(|r| r.note.clone())
    {
        notes.push(format!("{mark}: {note}"));
    }
    let short = |r: &Reinforcement| {
        format!(
            "{mark}: {} area available {:.0} mm² is less than the {:.0} mm² required \
             (A1 {:.0}, A2 {:.0}, A41 {:.0}, A42 {:.0}, A5 {:.0} mm²)",
            r.paragraph, r.a_available, r.a_required, r.a1, r.a2, r.a41, r.a42, r.a5
        )
    };
    let shorts: Vec<String> = opening
        .iter()
        .chain(&external)
        .filter(|r| r.deficient())
        .map(short)
        .collect();
    let reinforcement_deficiency = (!shorts.is_empty()).then(|| shorts.join("; "));
    let flange = match &c.flange_group {
        None => {
            notes.push(format!(
                "{mark}: B16.5: the material {} has no flange group in the table",
                c.material
            ));
            None
        }
        Some(group) => {
            match flange_rating(mark, nozzle.class, group, host.pressure, c.temperature) {
                Ok(f) => Some(f),
                Err(e) => {
                    notes.push(format!("{mark}: B16.5 not rated: {e}"));
                    None
                }
            }
        }
    };
    Ok(NozzleCalc {
        mark: mark.to_string(),
        host: host.id.clone(),
        pressure: host.pressure,
        neck_od: od,
        nominal,
        available,
        t_a,
        t_b1,
        t_b3,
        required,
        deficiency,
        reinforcement: opening,
        reinforcement_external: external,
        reinforcement_deficiency,
        flange,
        notes,
    })
}
