//! A whole vessel calculated: the static head on each part from the liquid at
//! its level, every pressure part and nozzle, and the vessel's figures — MAWP at
//! the top (the least part MAWP less its static head, UG-98), the UG-99(b)
//! hydrotest pressure, and the list of deficiencies. [`calculate`] is the pure
//! function `vesselcad calc`, `check` and `info` use; the ECS system
//! `systems::update_calculations` computes the same figures part by part.

use serde::Serialize;

use super::annular::{Annular, FirstCourse, annular};
use super::lateral::Lateral;
use super::legs::{LegsCalc, LugsCalc, legs_calc, lugs_calc};
use super::saddles::{SaddleCase, saddle_cases};
use super::skirt::{SkirtCalc, SkirtSetup, skirt_calc};
use super::vessel::{PartPressure, hydrotest_pressure, static_head, vessel_mawp};
use super::{
    Conditions, Formula, MaterialTable, NozzleCalc, PartCalc, code_of, conditions, nozzle_calc,
    part_calc,
};
use crate::constraints::{PartGeometry, ResolvedVessel};
use crate::design::{OperatingDesign, VesselDesign, VesselKind, WATER_DENSITY};
use crate::operating::thickness;
use crate::weights::weights;

/// The liquid a vessel holds, as the static head needs it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Liquid {
    /// Density, kg/m³.
    pub density: f64,
    /// Horizontal vessel: the level above the lowest inside point, mm. Vertical:
    /// the elevation of the surface in the vessel frame, mm.
    pub surface: f64,
    /// Vertical vessel: the lowest inside point in the vessel frame, mm.
    pub bottom: f64,
    /// Whether the vessel is horizontal.
    pub horizontal: bool,
}

impl Liquid {
    /// The liquid of a vessel of `kind` with `operating` data, whose parts that
    /// bound it ([`Liquid::bounds`]) span `parts` (`(start, end)` in the vessel
    /// frame, wall thickness) along the axis; `None` when the vessel is empty. A
    /// tank is always full to the top of its shell with its operating liquid (or
    /// water): API 650's design liquid level.
    pub fn of(
        kind: VesselKind,
        operating: Option<OperatingDesign>,
        parts: impl IntoIterator<Item = ((f64, f64), f64)>,
    ) -> Option<Liquid> {
        if kind == VesselKind::Tank {
            // API 650 5.6.3.2: the design liquid level is the top of the shell.
            let density = operating
                .and_then(|o| o.liquid_density)
                .unwrap_or(WATER_DENSITY);
            let (bottom, top) = parts.into_iter().fold(
                (f64::INFINITY, f64::NEG_INFINITY),
                |(b, t), ((start, end), _)| (b.min(start), t.max(end)),
            );
            return (bottom < top).then_some(Liquid {
                density,
                surface: top,
                bottom,
                horizontal: false,
            });
        }
        let o = operating.filter(|o| o.liquid_level > 0.0)?;
        let density = o.liquid_density.unwrap_or(WATER_DENSITY);
        let lowest = parts.into_iter().min_by(|a, b| a.0.0.total_cmp(&b.0.0))?;
        let bottom = lowest.0.0 + lowest.1;
        let horizontal = kind == VesselKind::Horizontal;
        Some(Liquid {
            density,
            surface: if horizontal {
                o.liquid_level
            } else {
                bottom + o.liquid_level
            },
            bottom,
            horizontal,
        })
    }

    /// Whether a part of `geometry` bounds the liquid of a vessel of `kind`: a
    /// pressure part, and for a tank one of its shell courses (the top of the shell
    /// is the design liquid level).
    pub fn bounds(kind: VesselKind, geometry: &PartGeometry) -> bool {
        super::pressure_shape(geometry, 0.0).is_some()
            && (kind != VesselKind::Tank || matches!(geometry, PartGeometry::Shell(_)))
    }

    /// Static head at the lowest inside point of a part spanning from `start`
    /// (vessel frame, mm), MPa.
    pub fn head_at(&self, start: f64) -> f64 {
        let depth = if self.horizontal {
            self.surface
        } else {
            (self.surface - start.max(self.bottom)).max(0.0)
        };
        static_head(self.density, depth).unwrap_or(0.0)
    }
}

/// The vessel-level figures.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct VesselCalc {
    /// Tag.
    pub tag: String,
    /// The code calculated to.
    pub code: &'static str,
    /// The conditions used, when the vessel could be calculated.
    pub conditions: Option<Conditions>,
    /// MAWP at the top, hot and corroded, MPa.
    pub mawp: Option<f64>,
    /// The part whose MAWP governs.
    pub governing: Option<String>,
    /// UG-99(b) hydrotest pressure at the top, MPa.
    pub hydrotest: Option<Formula>,
    /// Every deficiency of a part or nozzle.
    pub deficiencies: Vec<String>,
    /// What could not be calculated, and why.
    pub problems: Vec<String>,
    /// The saddles checked by Zick's method, per saddle and load case (empty
    /// for a vessel without saddles); filled by [`support_calcs`].
    pub saddles: Vec<SaddleCase>,
    /// A vertical vessel's wind and earthquake at its base, when the design
    /// gives them; filled by [`support_calcs`].
    pub lateral: Option<LateralFigures>,
    /// Skirts under weight, wind and earthquake.
    pub skirts: Vec<SkirtCalc>,
    /// Legs under weight, wind and earthquake.
    pub legs: Vec<LegsCalc>,
    /// Lugs under weight, wind and earthquake.
    pub lugs: Vec<LugsCalc>,
    /// An API 650 tank's annular bottom plates (5.5) from its first course, or
    /// why they are not computed; `None` for a pressure vessel.
    pub annular: Option<Result<Annular, String>>,
}

/// A vertical vessel's wind and earthquake figures at its base (unfactored).
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct LateralFigures {
    /// Height of the base above grade, mm.
    pub base_elevation: f64,
    /// Wind shear (N) and moment (N·mm) at the base, with qz at the top (Pa).
    pub wind: Option<(f64, f64, f64)>,
    /// Cs, its equation, the exponent k, base shear (N) and moment (N·mm).
    pub seismic: Option<(f64, &'static str, f64, f64, f64)>,
}

impl VesselCalc {
    /// Gathers the vessel figures from its parts' and nozzles' calculations.
    pub fn gather(
        tag: &str,
        kind: VesselKind,
        conditions: Result<Conditions, String>,
        parts: &[&PartCalc],
        nozzles: &[&NozzleCalc],
        mut problems: Vec<String>,
    ) -> VesselCalc {
        let mut deficiencies: Vec<String> =
            parts.iter().filter_map(|p| p.deficiency.clone()).collect();
        deficiencies.extend(nozzles.iter().flat_map(|n| n.deficiencies().cloned()));
        problems.extend(nozzles.iter().flat_map(|n| n.notes.iter().cloned()));
        let conditions = match conditions {
            Ok(c) => Some(c),
            Err(e) => {
                problems.insert(0, e);
                None
            }
        };
        let pressures: Vec<PartPressure> = parts
            .iter()
            .filter_map(|p| {
                Some(PartPressure {
                    id: p.id.clone(),
                    mawp: p.mawp.as_ref()?.value,
                    static_head: p.static_head,
                })
            })
            .collect();
        let top = vessel_mawp(&pressures).ok().filter(|(m, _)| *m > 0.0);
        let hydrotest = match (&top, &conditions) {
            (_, Some(c)) if c.vacuum_only() => Some(Formula {
                value: 1.3 * c.external_pressure,
                paragraph: "UG-99(f)",
                formula: "vacuum only: internal test P_test = 1.3 · (atmospheric − minimum \
                          internal absolute pressure) = 1.3 · P_external",
            }),
            (Some((m, _)), Some(c)) => hydrotest_pressure(*m, &[(c.stress_test, c.stress)]).ok(),
            _ => None,
        };
        if let Some(h) = &hydrotest {
            for n in nozzles {
                let Some(f) = &n.flange else { continue };
                if h.value > f.test_limit {
                    deficiencies.push(format!(
                        "{}: hydrotest {:.3} MPa at the top exceeds the B16.5 Class {} shell test \
                         1.5 × {:.3} = {:.3} MPa",
                        n.mark,
                        h.value,
                        f.class,
                        f.test_limit / 1.5,
                        f.test_limit
                    ));
                }
            }
        }
        let annular = conditions
            .as_ref()
            .filter(|c| c.code == "API 650")
            .and_then(|c| tank_annular(parts, c));
        VesselCalc {
            annular,
            tag: tag.to_string(),
            code: code_of(kind),
            conditions,
            mawp: top.as_ref().map(|t| t.0),
            governing: top.map(|t| t.1),
            hydrotest,
            deficiencies,
            problems,
            saddles: Vec::new(),
            lateral: None,
            skirts: Vec::new(),
            legs: Vec::new(),
            lugs: Vec::new(),
        }
    }
}

/// The annular plates of a tank whose parts are `parts`, from its first course:
/// the shell course under the most liquid. `None` for a tank without courses.
fn tank_annular(parts: &[&PartCalc], c: &Conditions) -> Option<Result<Annular, String>> {
    let first = parts
        .iter()
        .filter(|p| p.shape == "tank shell course")
        .max_by(|a, b| a.static_head.total_cmp(&b.static_head))?;
    let input = |name: &str| {
        first
            .inputs
            .iter()
            .find(|i| i.name == name)
            .map_or(f64::NAN, |i| i.value)
    };
    let course = FirstCourse {
        thickness: first.thickness.unwrap_or(first.required.value),
        design: input("t_d"),
        test: input("t_t"),
        corrosion_allowance: c.corrosion_allowance,
        design_stress: c.stress,
        test_stress: c.stress_test,
        level: input("H"),
        gravity: input("G"),
    };
    Some(
        annular(&course, c.api650_group.as_deref())
            .map_err(|e| format!("{} (first course): {e}", first.id)),
    )
}

/// Adds the supports' calculations of vessel `design` resolved as `resolved` to
/// its gathered figures `vessel`: the weights of the one weight model, and for a
/// horizontal vessel on two saddles Zick's stresses in the operating and
/// hydrotest cases; failures become deficiencies, what cannot be computed a
/// problem. Nothing for a vessel without conditions or supports.
pub fn support_calcs(
    design: &VesselDesign,
    resolved: &ResolvedVessel,
    table: &MaterialTable,
    vessel: &mut VesselCalc,
) {
    let Some(c) = &vessel.conditions else {
        return;
    };
    if design.kind == VesselKind::Vertical {
        vertical_supports(design, resolved, table, vessel);
        return;
    }
    let has_saddles = resolved
        .parts
        .iter()
        .any(|p| matches!(p.geometry, PartGeometry::Saddle(_)));
    if !has_saddles || design.kind != VesselKind::Horizontal {
        return;
    }
    let w = match weights(design, resolved) {
        Ok(w) => w,
        Err(e) => {
            vessel
                .problems
                .push(format!("saddles: no weights for Zick's method: {e}"));
            return;
        }
    };
    let test = vessel.hydrotest.as_ref().map(|h| h.value);
    match saddle_cases(design, resolved, c, &w, test) {
        Ok(cases) => {
            for case in &cases {
                vessel.deficiencies.extend(case.deficiencies());
            }
            vessel.saddles = cases;
        }
        Err(e) => vessel.problems.push(format!("saddles: {e}")),
    }
}

/// Whether a vessel of `kind` with `parts` has supports [`support_calcs`] checks.
pub fn has_calculated_supports(kind: VesselKind, parts: &[&crate::design::PartDesign]) -> bool {
    use crate::design::PartDesign as P;
    parts.iter().any(|p| match p {
        P::Saddle(_) => kind == VesselKind::Horizontal,
        P::Skirt(_) | P::Legs(_) | P::Lugs(_) => kind == VesselKind::Vertical,
        _ => false,
    })
}

/// The skirts, legs and lugs of a vertical vessel under its weight, wind and
/// earthquake ([`Lateral`]).
fn vertical_supports(
    design: &VesselDesign,
    resolved: &ResolvedVessel,
    table: &MaterialTable,
    vessel: &mut VesselCalc,
) {
    let Some(c) = vessel.conditions.clone() else {
        return;
    };
    let supported = resolved.parts.iter().any(|p| {
        matches!(
            p.geometry,
            PartGeometry::Skirt(_) | PartGeometry::Legs(_) | PartGeometry::Lugs(_)
        )
    });
    if !supported {
        return;
    }
    let w = match weights(design, resolved) {
        Ok(w) => w,
        Err(e) => {
            vessel
                .problems
                .push(format!("supports: no weights for the support loads: {e}"));
            return;
        }
    };
    let lateral = Lateral::of(design, resolved, &w);
    vessel.lateral = Some(LateralFigures {
        base_elevation: lateral.datum + lateral.base,
        wind: lateral.wind_at(lateral.base).map(|(v, m)| {
            let top = lateral.bands.iter().map(|b| b.top).fold(0.0, f64::max);
            (v, m, lateral.wind.as_ref().map_or(0.0, |f| f.qz(top)))
        }),
        seismic: lateral.seismic.as_ref().and_then(|(_, k)| {
            let (v, _, m) = lateral.seismic_at(lateral.base)?;
            Some((k.cs, k.equation, k.k, v, m))
        }),
    });
    let thickness_of = |id: &str| {
        design
            .parts
            .iter()
            .find(|p| p.id() == id)
            .and_then(thickness)
    };
    for p in &resolved.parts {
        let Some(d) = design.parts.iter().find(|d| d.id() == p.id) else {
            continue;
        };
        match (&p.geometry, d) {
            (PartGeometry::Skirt(s), crate::design::PartDesign::Skirt(sd)) => {
                let mass = w
                    .items
                    .iter()
                    .find(|i| i.id == p.id)
                    .map_or(0.0, |i| i.mass);
                let ring = sd.base_ring_thickness.unwrap_or(s.thickness);
                let calc = skirt_calc(
                    &p.id,
                    s,
                    SkirtSetup {
                        span: p.span,
                        mass,
                        ring_thickness: ring,
                        bolts: sd.anchor_bolts,
                    },
                    &lateral,
                    &c,
                );
                vessel.deficiencies.extend(calc.deficiencies());
                vessel.skirts.push(calc);
            }
            (PartGeometry::Legs(l), crate::design::PartDesign::Legs(ld)) => {
                match legs_calc(&p.id, l, ld.size, p.span.0.min(p.span.1), &lateral, table) {
                    Ok(calc) => {
                        vessel.deficiencies.extend(calc.deficiencies());
                        vessel.legs.push(calc);
                    }
                    Err(e) => vessel.problems.push(format!("legs: {e}")),
                }
            }
            (PartGeometry::Lugs(l), crate::design::PartDesign::Lugs(ld)) => {
                let plane = ld.elevation;
                let course = resolved.parts.iter().find(|q| {
                    matches!(q.geometry, PartGeometry::Shell(_))
                        && q.span.0 <= plane
                        && plane <= q.span.1
                });
                let Some(ts) = course.and_then(|q| thickness_of(&q.id)) else {
                    vessel.problems.push(format!(
                        "lugs: {}: no shell course with a thickness at the lugs",
                        p.id
                    ));
                    continue;
                };
                match lugs_calc(
                    &p.id,
                    l,
                    plane,
                    ts - c.corrosion_allowance,
                    &lateral,
                    &c,
                    table,
                ) {
                    Ok(calc) => {
                        vessel.deficiencies.extend(calc.deficiencies());
                        vessel.lugs.push(calc);
                    }
                    Err(e) => vessel.problems.push(format!("lugs: {e}")),
                }
            }
            _ => {}
        }
    }
}

/// A vessel's calculation: the vessel figures, its pressure parts and nozzles in
/// design order.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Calculation {
    /// Vessel figures.
    pub vessel: VesselCalc,
    /// Pressure parts.
    pub parts: Vec<PartCalc>,
    /// Nozzles (UG-45).
    pub nozzles: Vec<NozzleCalc>,
}

/// Calculates vessel `design` resolved as `resolved` with the materials of `table`.
pub fn calculate(
    design: &VesselDesign,
    resolved: &ResolvedVessel,
    table: &MaterialTable,
) -> Calculation {
    let conds = conditions(&design.design, design.kind, table);
    let thickness_of = |id: &str| {
        design
            .parts
            .iter()
            .find(|p| p.id() == id)
            .and_then(thickness)
    };
    let mut parts = Vec::new();
    let mut nozzles = Vec::new();
    let mut problems = Vec::new();
    if let Ok(c) = &conds {
        let liquid = Liquid::of(
            design.kind,
            design.operating,
            resolved
                .parts
                .iter()
                .filter(|p| Liquid::bounds(design.kind, &p.geometry))
                .map(|p| (p.span, thickness_of(&p.id).unwrap_or(0.0))),
        );
        let mut host_calc: Vec<Option<usize>> = vec![None; resolved.parts.len()];
        for (i, p) in resolved.parts.iter().enumerate() {
            let openings = resolved
                .nozzles
                .iter()
                .filter(|n| n.host == i)
                .map(|n| n.mark.clone())
                .collect();
            let head = liquid.map_or(0.0, |l| l.head_at(p.span.0));
            match part_calc(
                &p.id,
                &p.geometry,
                thickness_of(&p.id),
                head,
                liquid.as_ref(),
                openings,
                c,
            ) {
                Ok(Some(calc)) => {
                    host_calc[i] = Some(parts.len());
                    parts.push(calc);
                }
                Ok(None) => {}
                Err(e) => problems.push(e),
            }
        }
        for n in &resolved.nozzles {
            let Some(host) = host_calc.get(n.host).copied().flatten() else {
                continue;
            };
            match nozzle_calc(&n.mark, &n.geometry, n.pad, &parts[host], c) {
                Ok(calc) => nozzles.push(calc),
                Err(e) => problems.push(e),
            }
        }
    }
    let mut vessel = VesselCalc::gather(
        &design.tag,
        design.kind,
        conds,
        &parts.iter().collect::<Vec<_>>(),
        &nozzles.iter().collect::<Vec<_>>(),
        problems,
    );
    support_calcs(design, resolved, table, &mut vessel);
    Calculation {
        vessel,
        parts,
        nozzles,
    }
}
