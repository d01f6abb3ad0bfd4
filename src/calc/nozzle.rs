//! UG-45 nozzle neck thickness: the neck must be at least the larger of t_a (the
//! neck's own UG-27 thickness under the pressure on its host, plus corrosion) and
//! t_b, the smaller of the host's required thickness at E = 1 (not less than the
//! UG-16(b) minimum) and the standard-wall pipe less its 12.5 % mill tolerance,
//! each plus corrosion. The neck's available wall is its schedule's nominal wall
//! less the same 12.5 % tolerance (UG-16(d)).

use serde::Serialize;

use super::shells::circumferential_thickness;
use super::vessel::UG16_MINIMUM;
use super::{Conditions, PartCalc};
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
    /// Why the neck fails, when it does.
    pub deficiency: Option<String>,
}

/// UG-45 of `nozzle` (mark `mark`) on `host`, calculated under `c`. The neck is
/// taken of the vessel's material, seamless (E = 1).
pub fn nozzle_calc(
    mark: &str,
    nozzle: &Nozzle,
    host: &PartCalc,
    c: &Conditions,
) -> Result<NozzleCalc, String> {
    let fail = |e: String| format!("{mark}: {e}");
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
    })
}
