//! Pipe legs and support lugs under weight, wind and earthquake
//! ([`super::lateral`]).
//!
//! **Legs** (N legs of standard-wall pipe, as the weight model takes them, on
//! the circle Dl = shell OD + pipe OD; SA-106-B): reactions at the floor
//! P = W/N ± 4M/(N·Dl) (the largest leg load and the uplift), each leg's shear
//! H = V/N. Each leg is a column fixed to the vessel with a pinned, anchored
//! foot, free to sway: K = 2.0 (AISC commentary, case (f)), bending H·L at the
//! top. AISC *Specification for Structural Steel Buildings — ASD* (9th ed.,
//! 1989): Fa by E2-1 (KL/r ≤ Cc = √(2π²E/Fy)) or E2-2; Fb = 0.66·Fy for a compact
//! pipe (D/t ≤ 3300/Fy in ksi, Table B5.1), else 0.60·Fy; interaction H1-3 when
//! fa/Fa ≤ 0.15, else H1-1 (Cm = 0.85, sway) and H1-2.
//!
//! **Lugs** (N lugs on the circle through the bolt at mid-projection,
//! Dl = shell OD + projection; plates of the weight model's 12 mm; SA-36):
//! reaction Q = W/N + 4M/(N·Dl) at the bearing plane. Checked, **simplified**:
//! the bearing plate as a simple beam between the gussets under Q at its middle
//! (6·Q·g/4 / (p·t²) ≤ 0.75·Fy, AISC F2 for a plate bent about its weak axis),
//! and the shell under the lug's couple Q·e (e = projection/2) taken as two
//! horizontal forces Q·e/h at the gussets' ends, each spread over the lug's width
//! plus 1.56·√(R·ts) as a membrane stress ≤ S. That last rule is not WRC 107 or
//! Bijlaard: it has no local bending of the shell and is not conservative for
//! thin shells; use WRC 107/537 for the final design.

use std::f64::consts::PI;

use serde::Serialize;

use super::lateral::{Lateral, LoadCase};
use super::saddles::Check;
use super::{Conditions, MaterialTable};
use crate::parts::tables::{Nps, PipeSchedule, pipe};
use crate::parts::{Legs, Lugs};
use crate::weights::metal::DEFAULT_PLATE;

/// The material the legs are taken of.
pub const LEG_MATERIAL: &str = "SA-106-B";
/// The material the lugs are taken of.
pub const LUG_MATERIAL: &str = "SA-36";
/// Effective length factor of a leg.
pub const LEG_K: f64 = 2.0;

/// AISC ASD allowable axial stress Fa (MPa) at slenderness `klr` for yield `fy`
/// and modulus `e` (MPa): E2-1 or E2-2.
pub fn allowable_axial(klr: f64, fy: f64, e: f64) -> f64 {
    let cc = (2.0 * PI * PI * e / fy).sqrt();
    if klr <= cc {
        let r = klr / cc;
        let fs = 5.0 / 3.0 + 3.0 / 8.0 * r - r.powi(3) / 8.0;
        (1.0 - r * r / 2.0) * fy / fs
    } else {
        12.0 * PI * PI * e / (23.0 * klr * klr)
    }
}

/// One leg check in one combination.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct LegCase {
    /// The combination.
    pub load: LoadCase,
    /// Largest leg load (compression), N.
    pub reaction: f64,
    /// Smallest leg load (negative: uplift), N.
    pub uplift: f64,
    /// Shear per leg, N.
    pub shear: f64,
    /// fa, MPa.
    pub fa: f64,
    /// fb, MPa.
    pub fb: f64,
    /// Fa, MPa.
    pub allowable_axial: f64,
    /// Fb, MPa.
    pub allowable_bending: f64,
    /// The interaction ratio (≤ 1) and its equation.
    pub check: Check,
}

/// Legs calculated.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct LegsCalc {
    /// Part id.
    pub id: String,
    /// Pipe OD and wall, mm.
    pub pipe: (f64, f64),
    /// KL/r.
    pub slenderness: f64,
    /// Leg circle, mm.
    pub circle: f64,
    /// Per combination.
    pub cases: Vec<LegCase>,
}

impl LegsCalc {
    /// The sentences of the checks that fail.
    pub fn deficiencies(&self) -> Vec<String> {
        self.cases
            .iter()
            .filter(|c| !c.check.ok())
            .map(|c| {
                format!(
                    "{} ({}): leg {} = {:.2} exceeds 1 (P = {:.1} kN, fa {:.1} of Fa {:.1} MPa, fb \
                     {:.1} of Fb {:.1} MPa)",
                    self.id,
                    c.load.name,
                    c.check.rule,
                    c.check.stress,
                    c.reaction * 1e-3,
                    c.fa,
                    c.allowable_axial,
                    c.fb,
                    c.allowable_bending
                )
            })
            .collect()
    }
}

/// Legs `id` of geometry `l` and NPS `size` under `lateral` at their feet
/// (vessel-frame height `floor`).
pub fn legs_calc(
    id: &str,
    l: &Legs,
    size: f64,
    floor: f64,
    lateral: &Lateral,
    table: &MaterialTable,
) -> Result<LegsCalc, String> {
    let steel = table.get(LEG_MATERIAL).map_err(|e| e.to_string())?;
    let (fy, e) = (steel.yield_strength.value, steel.modulus.value);
    let nps = Nps::try_new(size).map_err(|e| format!("{id}: {e}"))?;
    let row = pipe(nps);
    let t = row
        .wall(PipeSchedule::Std)
        .map_err(|e| format!("{id}: {e}"))?;
    let d = l.pipe_diameter;
    let (ro, ri) = (d / 2.0, d / 2.0 - t);
    let area = PI * (ro * ro - ri * ri);
    let inertia = PI * (ro.powi(4) - ri.powi(4)) / 4.0;
    let section = inertia / ro;
    let r = (inertia / area).sqrt();
    let klr = LEG_K * l.length / r;
    let fa_allow = allowable_axial(klr, fy, e);
    let compact = d / t <= 22_750.0 / fy;
    let fb_allow = if compact { 0.66 * fy } else { 0.60 * fy };
    let fe = 12.0 * PI * PI * e / (23.0 * klr * klr);
    let n = f64::from(l.count);
    let circle = l.shell_diameter + d;
    let cases = lateral
        .cases(floor, 0.0)
        .into_iter()
        .map(|load| {
            let couple = 4.0 * load.moment / (n * circle);
            let reaction = load.weight / n + couple;
            let uplift = load.weight / n - couple;
            let shear = load.shear / n;
            let fa = reaction.max(0.0) / area;
            let fb = shear * l.length / section;
            let (ratio, rule) = if fa / fa_allow <= 0.15 {
                (fa / fa_allow + fb / fb_allow, "fa/Fa + fb/Fb (H1-3)")
            } else {
                let h1 = fa / fa_allow + 0.85 * fb / ((1.0 - fa / fe) * fb_allow);
                let h2 = fa / (0.6 * fy) + fb / fb_allow;
                if h1 >= h2 {
                    (h1, "fa/Fa + Cm·fb/((1 − fa/F'e)·Fb) (H1-1)")
                } else {
                    (h2, "fa/0.6Fy + fb/Fb (H1-2)")
                }
            };
            LegCase {
                load,
                reaction,
                uplift,
                shear,
                fa,
                fb,
                allowable_axial: fa_allow,
                allowable_bending: fb_allow,
                check: Check {
                    name: "leg interaction",
                    stress: ratio,
                    allowable: 1.0,
                    rule,
                },
            }
        })
        .collect();
    Ok(LegsCalc {
        id: id.to_string(),
        pipe: (d, t),
        slenderness: klr,
        circle,
        cases,
    })
}

/// Lugs calculated.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct LugsCalc {
    /// Part id.
    pub id: String,
    /// Lug circle, mm.
    pub circle: f64,
    /// Largest reaction per lug, N, and its combination.
    pub reaction: f64,
    /// The combination of the largest reaction.
    pub case: &'static str,
    /// The checks at the largest reaction.
    pub checks: Vec<Check>,
}

impl LugsCalc {
    /// The sentences of the checks that fail.
    pub fn deficiencies(&self) -> Vec<String> {
        self.checks
            .iter()
            .filter(|k| !k.ok())
            .map(|k| {
                format!(
                    "{} ({}): {} = {:.1} MPa exceeds {} = {:.1} MPa (Q = {:.1} kN per lug)",
                    self.id,
                    self.case,
                    k.name,
                    k.stress,
                    k.rule,
                    k.allowable,
                    self.reaction * 1e-3
                )
            })
            .collect()
    }
}

/// Lugs `id` of geometry `l` at vessel-frame height `plane` on a shell of wall
/// `ts` (corroded), under `lateral`.
pub fn lugs_calc(
    id: &str,
    l: &Lugs,
    plane: f64,
    ts: f64,
    lateral: &Lateral,
    c: &Conditions,
    table: &MaterialTable,
) -> Result<LugsCalc, String> {
    let steel = table.get(LUG_MATERIAL).map_err(|e| e.to_string())?;
    let fy = steel.yield_strength.value;
    let n = f64::from(l.count);
    let circle = l.shell_diameter + l.projection;
    let (reaction, case) = lateral
        .cases(plane, 0.0)
        .into_iter()
        .map(|k| (k.weight / n + 4.0 * k.moment / (n * circle), k.name))
        .max_by(|a, b| a.0.total_cmp(&b.0))
        .unwrap_or((0.0, "none"));
    let t = DEFAULT_PLATE;
    let plate = 6.0 * (reaction * l.width / 4.0) / (l.projection * t * t);
    let r = (l.shell_diameter - ts) / 2.0;
    let couple = reaction * l.projection / 2.0 / l.height;
    let strip = l.width + 2.0 * t + 1.56 * (r * ts).sqrt();
    Ok(LugsCalc {
        id: id.to_string(),
        circle,
        reaction,
        case,
        checks: vec![
            Check {
                name: "bearing plate bending 6·(Q·g/4)/(p·t²)",
                stress: plate,
                allowable: 0.75 * fy,
                rule: "0.75·Fy",
            },
            Check {
                name: "shell under the lug couple (simplified) Q·e/h/(ts·(w + 2t + 1.56√(R·ts)))",
                stress: couple / (ts * strip),
                allowable: c.stress,
                rule: "S",
            },
        ],
    })
}
