//! A skirt under weight, wind and earthquake ([`super::lateral`]): its
//! longitudinal stress at the base and at the top, the base ring's thickness and
//! the anchor-bolt load.
//!
//! - Skirt (mean diameter D, nominal thickness t, no corrosion allowance: the
//!   skirt is outside the process): σ = 4M/(π·D²·t) ± W/(π·D·t). Tension
//!   4M/(π·D²·t) − W/(π·D·t) ≤ S·E, compression 4M/(π·D²·t) + W/(π·D·t) ≤
//!   min(S, B), B of UG-23(b) at A = 0.125·t/Ro (elastic line capped at Sy/4,
//!   as [`super::saddles::compressive_b`]); both allowables × 1.2 in a case with
//!   wind or earthquake (UG-23(d)). E is the design's joint efficiency.
//! - Base ring: the bearing annulus from the skirt's inside to the ring's edge
//!   (outer diameter Db + 2·l, l the ring's width beyond the skirt) carries
//!   fc = W/A + M/Z; the ring, a cantilever of span l under fc, needs
//!   t = l·√(3·fc/S) (strip bending, 6·(fc·l²/2)/t² = S). The ring is the
//!   design's `base_ring_thickness` (default the skirt's); a thicker requirement
//!   is a deficiency.
//! - Anchor bolts, N on the circle through the ring's middle (diameter
//!   Db + l): P = 4M/(N·Dbc) − W/N per bolt (W the case's factored weight, so
//!   0.6·D in the uplift cases); without N, per mm of the circle:
//!   4M/(π·Dbc²) − W/(π·Dbc). Negative: no uplift.

use serde::Serialize;

use super::Conditions;
use super::lateral::{Lateral, LoadCase};
use super::saddles::{Check, compressive_b};
use crate::parts::Skirt;

/// The skirt in one load combination at one plane.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct SkirtCase {
    /// Where: `base` or `top`.
    pub plane: &'static str,
    /// The combination.
    pub load: LoadCase,
    /// Checks of the longitudinal stress.
    pub checks: Vec<Check>,
}

/// A skirt calculated.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct SkirtCalc {
    /// Part id.
    pub id: String,
    /// Mean diameter at the base, mm.
    pub base_diameter: f64,
    /// Thickness, mm.
    pub thickness: f64,
    /// Base ring thickness, mm.
    pub ring_thickness: f64,
    /// The cases at base and top.
    pub cases: Vec<SkirtCase>,
    /// Largest bearing pressure under the ring, MPa (None without a ring).
    pub bearing: Option<f64>,
    /// Required base ring thickness, mm (None without a ring).
    pub ring_required: Option<f64>,
    /// Bolt circle diameter, mm.
    pub bolt_circle: f64,
    /// Number of anchor bolts, when the design gives it.
    pub bolts: Option<u32>,
    /// Largest anchor load: N per bolt with bolts, else N per mm of the circle;
    /// ≤ 0 when nothing lifts.
    pub bolt_load: f64,
    /// The combination that gives it.
    pub bolt_case: &'static str,
}

impl SkirtCalc {
    /// The sentences of the checks that fail.
    pub fn deficiencies(&self) -> Vec<String> {
        let mut out: Vec<String> = self
            .cases
            .iter()
            .flat_map(|c| {
                c.checks.iter().filter(|k| !k.ok()).map(move |k| {
                    format!(
                        "{} at the {} ({}): {} = {:.1} MPa exceeds {} = {:.1} MPa (M = {:.1} kN·m, \
                         W = {:.1} kN)",
                        self.id,
                        c.plane,
                        c.load.name,
                        k.name,
                        k.stress,
                        k.rule,
                        k.allowable,
                        c.load.moment * 1e-6,
                        c.load.weight * 1e-3
                    )
                })
            })
            .collect();
        if let Some(r) = self.ring_required
            && r > self.ring_thickness
        {
            out.push(format!(
                "{}: base ring needs {:.1} mm (bearing {:.2} MPa), the ring is {:.1} mm",
                self.id,
                r,
                self.bearing.unwrap_or(0.0),
                self.ring_thickness
            ));
        }
        out
    }
}

/// Stress checks of a cylinder of mean diameter `d`, thickness `t` under `load`.
fn checks(d: f64, t: f64, load: &LoadCase, c: &Conditions) -> Vec<Check> {
    let bending = 4.0 * load.moment / (std::f64::consts::PI * d * d * t);
    let axial = load.weight / (std::f64::consts::PI * d * t);
    let up = if load.lateral { 1.2 } else { 1.0 };
    let b = compressive_b(t, (d + t) / 2.0, c.modulus, c.yield_strength);
    vec![
        Check {
            name: "longitudinal tension 4M/πD²t − W/πDt",
            stress: bending - axial,
            allowable: up * c.stress * c.joint_efficiency,
            rule: if load.lateral { "1.2·S·E" } else { "S·E" },
        },
        Check {
            name: "longitudinal compression 4M/πD²t + W/πDt",
            stress: bending + axial,
            allowable: up * c.stress.min(b),
            rule: if load.lateral {
                "1.2·min(S, B of UG-23(b))"
            } else {
                "min(S, B of UG-23(b))"
            },
        },
    ]
}

/// What a skirt's calculation needs beyond its geometry.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SkirtSetup {
    /// Axial span, vessel frame, mm (base, top).
    pub span: (f64, f64),
    /// Mass of the skirt itself, kg.
    pub mass: f64,
    /// Base ring thickness, mm.
    pub ring_thickness: f64,
    /// Number of anchor bolts, when the design gives it.
    pub bolts: Option<u32>,
}

/// Skirt `id` of geometry `s` set up by `setup`, under the loads of `lateral`.
pub fn skirt_calc(
    id: &str,
    s: &Skirt,
    setup: SkirtSetup,
    lateral: &Lateral,
    c: &Conditions,
) -> SkirtCalc {
    let SkirtSetup {
        span,
        mass,
        ring_thickness,
        bolts,
    } = setup;
    let t = s.thickness;
    let outside_base = s.top_diameter + 2.0 * s.height * s.flare_angle.to_radians().tan();
    let (d_base, d_top) = (outside_base - t, s.top_diameter - t);
    let mut cases = Vec::new();
    let base_cases = lateral.cases(span.0, 0.0);
    for load in &base_cases {
        cases.push(SkirtCase {
            plane: "base",
            load: load.clone(),
            checks: checks(d_base, t, load, c),
        });
    }
    for load in lateral.cases(span.1, mass * super::GRAVITY) {
        let checks = checks(d_top, t, &load, c);
        cases.push(SkirtCase {
            plane: "top",
            load,
            checks,
        });
    }
    let l = s.base_ring_width;
    let pi = std::f64::consts::PI;
    let (bearing, ring_required) = if l > 0.0 {
        let (di, dout) = (outside_base - 2.0 * t, outside_base + 2.0 * l);
        let area = pi * (dout * dout - di * di) / 4.0;
        let z = pi * (dout.powi(4) - di.powi(4)) / (32.0 * dout);
        let fc = base_cases
            .iter()
            .map(|k| k.weight / area + k.moment / z)
            .fold(0.0, f64::max);
        (Some(fc), Some(l * (3.0 * fc / c.stress).sqrt()))
    } else {
        (None, None)
    };
    let dbc = outside_base + l;
    let per = |k: &LoadCase| match bolts {
        Some(n) if n > 0 => bolt_load(n, dbc, k.moment, k.weight),
        _ => 4.0 * k.moment / (pi * dbc * dbc) - k.weight / (pi * dbc),
    };
    let (bolt_load, bolt_case) = base_cases
        .iter()
        .map(|k| (per(k), k.name))
        .max_by(|a, b| a.0.total_cmp(&b.0))
        .unwrap_or((0.0, "none"));
    SkirtCalc {
        id: id.to_string(),
        base_diameter: d_base,
        thickness: t,
        ring_thickness,
        cases,
        bearing,
        ring_required,
        bolt_circle: dbc,
        bolts,
        bolt_load,
        bolt_case,
    }
}

/// The anchor load per bolt of `n` bolts on a circle of diameter `dbc` (mm)
/// under moment `moment` (N·mm) and weight `weight` (N): 4M/(N·Dbc) − W/N.
pub fn bolt_load(n: u32, dbc: f64, moment: f64, weight: f64) -> f64 {
    let n = f64::from(n);
    4.0 * moment / (n * dbc) - weight / n
}
