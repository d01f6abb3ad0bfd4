//! One pressure part of a vessel calculated: its shape for the formulas (inside
//! dimensions from the resolved outside geometry less the wall), the pressure on
//! it (design pressure plus the static head of the liquid above its lowest
//! point), the required thickness hot and corroded, the UG-16(b) minimum, the
//! MAWP hot and corroded and new and cold, and a deficiency when the nominal wall
//! is thinner than required. Parts that carry no pressure (supports) have no
//! calculation.

use serde::Serialize;

use super::api650::one_foot;
use super::external::External;
use super::vessel::{GRAVITY, minimum_thickness};
use super::{Conditions, Formula, Liquid, Mdmt, Shape, Strength, mawp, required_thickness};
use crate::constraints::PartGeometry;
use crate::parts::ReducerAlignment;
use crate::parts::Shell;
use crate::parts::heads::{Head, HeadKind};

/// One input of a calculation, for the report.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Input {
    /// Symbol, e.g. `P`, `R`, `S`.
    pub name: &'static str,
    /// Value.
    pub value: f64,
    /// Unit, e.g. `MPa`.
    pub unit: &'static str,
}

/// The calculation of one pressure part.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct PartCalc {
    /// Part id.
    pub id: String,
    /// Part kind (`shell`, `head`, `reducer`).
    pub kind: &'static str,
    /// The shape as the formulas see it (`cylinder`, `ellipsoidal head`, …).
    pub shape: &'static str,
    /// Pressure on the part: design pressure + static head, MPa.
    pub pressure: f64,
    /// Static head of the liquid at the part's lowest point, MPa.
    pub static_head: f64,
    /// Nominal wall thickness, mm (`None` when the design gives none).
    pub thickness: Option<f64>,
    /// Required thickness, hot and corroded, corrosion allowance included.
    pub required: Formula,
    /// Required thickness at E = 1 (seamless), mm: UG-45's t_b1 for its nozzles
    /// and, less the corrosion allowance, UG-37's tr.
    pub required_seamless: f64,
    /// Inside diameter, new (a head's skirt, a reducer's large end), mm.
    pub inside_diameter: f64,
    /// UG-16(b) minimum thickness, corrosion allowance included, mm.
    pub minimum: f64,
    /// MAWP at the part, hot and corroded, MPa.
    pub mawp: Option<Formula>,
    /// MAWP at the part, new and cold (no corrosion, stress at the test temperature), MPa.
    pub mawp_new_cold: Option<f64>,
    /// The formulas' inputs (corroded inside dimensions).
    pub inputs: Vec<Input>,
    /// Marks of the nozzles whose openings are in this part, in design order.
    pub openings: Vec<String>,
    /// UCS-66 MDMT of the part, when its material has a Fig. UCS-66 curve and
    /// its nominal thickness is given.
    pub mdmt: Option<Mdmt>,
    /// UG-28 / UG-33 under the design's external pressure, corroded, when it
    /// gives one: the figures, or why they are not computed.
    pub external: Option<Result<External, String>>,
    /// The corroded wall UG-28 / UG-33 require under the design's external
    /// pressure (UG-37(d)'s tr for openings in the part), mm, or why it is not
    /// computed; `None` without external pressure.
    pub external_required: Option<Result<f64, String>>,
    /// Why the part fails, when it does.
    pub deficiency: Option<String>,
}

/// A part's formula shape from its resolved geometry and wall `t` mm (0 when
/// not given: the outside dimensions are taken). `None` for a part that carries
/// no pressure (skirt, saddles, legs, lugs) or is not calculated (boot).
///
/// Choices where the code leaves them to the designer: an ellipsoidal head keeps
/// its ratio D/2h on the inside; a flat head is attached as Fig. UG-34 sketch (a)
/// (C = 0.17) when flanged and sketch (f) (C = 0.33) otherwise; a toriconical head
/// and a reducer take the cone formula at the large end's inside diameter, an
/// eccentric reducer with its steepest generatrix.
pub fn pressure_shape(geometry: &PartGeometry, t: f64) -> Option<Shape> {
    Some(match geometry {
        PartGeometry::Shell(s) => Shape::Cylinder {
            inside_radius: s.outside_diameter / 2.0 - t,
        },
        PartGeometry::Head(h) => {
            let id = h.outside_diameter - 2.0 * t;
            match h.kind {
                HeadKind::Hemispherical => Shape::Sphere {
                    inside_radius: id / 2.0,
                },
                HeadKind::Ellipsoidal { ratio } => Shape::Ellipsoidal {
                    inside_diameter: id,
                    inside_depth: id / (2.0 * ratio),
                },
                HeadKind::Torispherical {
                    crown_radius,
                    knuckle_radius,
                } => Shape::Torispherical {
                    crown_radius: crown_radius - t,
                    knuckle_radius: knuckle_radius - t,
                },
                HeadKind::Toriconical { half_angle, .. } | HeadKind::Conical { half_angle, .. } => {
                    Shape::Cone {
                        inside_diameter: id,
                        half_apex_angle: half_angle,
                    }
                }
                HeadKind::Flat { knuckle_radius } => Shape::Flat {
                    diameter: id,
                    attachment_factor: if knuckle_radius > 0.0 { 0.17 } else { 0.33 },
                },
            }
        }
        PartGeometry::Reducer(r) => {
            let drop = r.large_diameter - r.small_diameter;
            let run = match r.alignment {
                ReducerAlignment::Concentric => 2.0 * r.length,
                ReducerAlignment::Eccentric { .. } => r.length,
            };
            Shape::Cone {
                inside_diameter: r.large_diameter - 2.0 * t,
                half_apex_angle: (drop / run).atan().to_degrees(),
            }
        }
        _ => return None,
    })
}

fn inside_diameter(geometry: &PartGeometry, t: f64) -> f64 {
    match geometry {
        PartGeometry::Shell(s) => s.outside_diameter - 2.0 * t,
        PartGeometry::Head(h) => h.outside_diameter - 2.0 * t,
        PartGeometry::Reducer(r) => r.large_diameter - 2.0 * t,
        _ => 0.0,
    }
}

fn shape_inputs(shape: &Shape) -> Vec<Input> {
    let i = |name, value| Input {
        name,
        value,
        unit: "mm",
    };
    match *shape {
        Shape::Cylinder { inside_radius } | Shape::Sphere { inside_radius } => {
            vec![i("R", inside_radius)]
        }
        Shape::Ellipsoidal {
            inside_diameter,
            inside_depth,
        } => vec![i("D", inside_diameter), i("h", inside_depth)],
        Shape::Torispherical {
            crown_radius,
            knuckle_radius,
        } => vec![i("L", crown_radius), i("r", knuckle_radius)],
        Shape::Cone {
            inside_diameter,
            half_apex_angle,
        } => vec![
            i("D", inside_diameter),
            Input {
                name: "α",
                value: half_apex_angle,
                unit: "°",
            },
        ],
        Shape::Flat {
            diameter,
            attachment_factor,
        } => vec![
            i("d", diameter),
            Input {
                name: "C",
                value: attachment_factor,
                unit: "",
            },
        ],
    }
}

/// Calculates part `id` of `kind` with resolved `geometry`, nominal wall
/// `thickness`, under `conditions` plus `static_head` MPa of `liquid`. A tank's
/// shell course follows API 650 instead (`tank_part`). `Ok(None)` for a part
/// that carries no pressure; `Err` with the reason when a formula cannot be
/// applied (out of its paragraph's scope, bad proportions).
pub fn part_calc(
    id: &str,
    geometry: &PartGeometry,
    thickness: Option<f64>,
    static_head: f64,
    liquid: Option<&Liquid>,
    openings: Vec<String>,
    c: &Conditions,
) -> Result<Option<PartCalc>, String> {
    if c.code == "API 650" {
        return tank_part(id, geometry, thickness, static_head, liquid, openings, c);
    }
    let Some(shape) = pressure_shape(geometry, thickness.unwrap_or(0.0)) else {
        return Ok(None);
    };
    let fail = |e: super::CalcError| format!("{id}: {e}");
    let hot = Strength {
        stress: c.stress,
        joint_efficiency: c.joint_efficiency,
        corrosion_allowance: c.corrosion_allowance,
    };
    let pressure = c.pressure + static_head;
    let seamless = Strength {
        joint_efficiency: 1.0,
        ..hot
    };
    let (required, required_seamless) = if pressure > 0.0 {
        (
            required_thickness(&shape, pressure, &hot).map_err(fail)?,
            required_thickness(&shape, pressure, &seamless)
                .map_err(fail)?
                .value,
        )
    } else {
        // Vacuum only and no liquid on the part: no internal-pressure thickness;
        // UG-28 / UG-33 (below) and the UG-16(b) minimum govern.
        let none = Formula {
            value: c.corrosion_allowance,
            paragraph: "UG-28",
            formula: "no internal pressure: t = CA; the wall is checked under external pressure",
        };
        (none, c.corrosion_allowance)
    };
    let minimum = minimum_thickness(c.corrosion_allowance)
        .map_err(fail)?
        .value;
    let (mawp_hot, mawp_cold) = match thickness {
        Some(t) if t > c.corrosion_allowance => {
            let cold = Strength {
                stress: c.stress_test,
                corrosion_allowance: 0.0,
                ..hot
            };
            (
                Some(mawp(&shape, t, &hot).map_err(fail)?),
                Some(mawp(&shape, t, &cold).map_err(fail)?.value),
            )
        }
        _ => (None, None),
    };
    let governing = required.value.max(minimum);
    let external = thickness
        .filter(|_| c.external_pressure > 0.0)
        .map(|t| external_check(geometry, t - c.corrosion_allowance, c));
    let external_short = match &external {
        Some(Ok(x)) if x.allowable < c.external_pressure => Some(format!(
            "{id}: allowable external pressure {:.4} MPa ({}) is below the design's {:.4} MPa",
            x.allowable, x.paragraph, c.external_pressure
        )),
        _ => None,
    };
    let deficiency = thickness.and_then(|t| {
        (t < governing).then(|| {
            let why = if required.value >= minimum {
                format!("{} {}", required.paragraph, required.formula)
            } else {
                "UG-16(b) minimum".to_string()
            };
            format!(
                "{id}: wall {t} mm is thinner than the required {governing:.2} mm ({why}, \
                 P = {:.4} MPa incl. static head {:.4} MPa)",
                pressure, static_head
            )
        })
    });
    let mut inputs = vec![
        Input {
            name: "P",
            value: pressure,
            unit: "MPa",
        },
        Input {
            name: "S",
            value: c.stress,
            unit: "MPa",
        },
        Input {
            name: "E",
            value: c.joint_efficiency,
            unit: "",
        },
        Input {
            name: "CA",
            value: c.corrosion_allowance,
            unit: "mm",
        },
    ];
    inputs.extend(shape_inputs(&shape.corroded(c.corrosion_allowance)));
    let mdmt = c
        .ucs66_curve
        .as_deref()
        .zip(thickness)
        .map(|(curve, t)| super::mdmt::mdmt(curve, t, coincident_ratio(required.value, t, c)));
    Ok(Some(PartCalc {
        id: id.to_string(),
        kind: geometry.kind(),
        shape: shape.name(),
        pressure,
        static_head,
        thickness,
        required,
        required_seamless,
        inside_diameter: inside_diameter(geometry, thickness.unwrap_or(0.0)),
        minimum,
        mawp: mawp_hot,
        mawp_new_cold: mawp_cold,
        inputs,
        openings,
        mdmt,
        external,
        external_required: (c.external_pressure > 0.0).then(|| external_required(geometry, c)),
        deficiency: match (deficiency, external_short) {
            (Some(a), Some(b)) => Some(format!("{a}; {b}")),
            (a, b) => a.or(b),
        },
    }))
}

/// UCS-66.1's coincident ratio Rts = tr E* / (tn − c) of a part of nominal wall
/// `t` whose required thickness, corrosion allowance included, is `required`:
/// tr the required thickness corroded (less the allowance), E* the joint
/// efficiency but not less than 0.80, tn − c the nominal wall less the
/// allowance; `None` when no wall is left after the allowance.
fn coincident_ratio(required: f64, t: f64, c: &Conditions) -> Option<f64> {
    let left = t - c.corrosion_allowance;
    let tr = (required - c.corrosion_allowance).max(0.0);
    (left > 0.0).then(|| tr * c.joint_efficiency.max(0.8) / left)
}

/// A storage tank's part under API 650: a shell course by the one-foot method
/// (5.6.3.2) with the design liquid level at the top of the shell and the 5.6.1.1
/// minimum; a head is its bottom or roof plate (`tank_plate`).
fn tank_part(
    id: &str,
    geometry: &PartGeometry,
    thickness: Option<f64>,
    static_head: f64,
    liquid: Option<&Liquid>,
    openings: Vec<String>,
    c: &Conditions,
) -> Result<Option<PartCalc>, String> {
    let PartGeometry::Shell(shell) = geometry else {
        return match geometry {
            PartGeometry::Head(h) => {
                tank_plate(id, h, thickness, static_head, openings, c).map(Some)
            }
            _ => Ok(None),
        };
    };
    let liquid = liquid.ok_or_else(|| format!("{id}: API 650: the tank has no shell courses"))?;
    let t = thickness.unwrap_or(0.0);
    // D: the centreline diameter of the course (5.6.1.1 Note 1 takes the bottom
    // course's; every course here has its own, the same in a straight tank).
    let d = (shell.outside_diameter - t) * 1e-3;
    let gravity = liquid.density / 1000.0;
    let level = static_head / (liquid.density * GRAVITY) * 1e6;
    let course = one_foot(
        d,
        level,
        gravity,
        c.stress,
        c.stress_test,
        c.corrosion_allowance,
    )
    .map_err(|e| format!("{id}: {e}"))?;
    let (paragraph, formula) = if course.required == course.minimum {
        ("API 650 5.6.1.1", "minimum nominal thickness by diameter")
    } else if course.required == course.design {
        ("API 650 5.6.3.2", "t_d = 4.9·D·(H − 0.3)·G / Sd + CA")
    } else {
        ("API 650 5.6.3.2", "t_t = 4.9·D·(H − 0.3) / St")
    };
    let deficiency = thickness.and_then(|t| {
        (t < course.required).then(|| {
            format!(
                "{id}: course {t} mm is thinner than API 650's {:.2} mm (t_d {:.2}, t_t {:.2}, \
                 minimum {:.0} mm; D = {d:.3} m, H = {level:.3} m, G = {gravity:.3})",
                course.required, course.design, course.test, course.minimum
            )
        })
    });
    let input = |name, value, unit| Input { name, value, unit };
    Ok(Some(PartCalc {
        id: id.to_string(),
        kind: geometry.kind(),
        shape: "tank shell course",
        pressure: static_head,
        static_head,
        thickness,
        required: Formula {
            value: course.required,
            paragraph,
            formula,
        },
        required_seamless: course.required,
        inside_diameter: shell.outside_diameter - 2.0 * t,
        minimum: course.minimum,
        mawp: None,
        mawp_new_cold: None,
        inputs: vec![
            input("D", d, "m"),
            input("H", level, "m"),
            input("G", gravity, ""),
            input("Sd", c.stress, "MPa"),
            input("St", c.stress_test, "MPa"),
            input("CA", c.corrosion_allowance, "mm"),
            input("t_d", course.design, "mm"),
            input("t_t", course.test, "mm"),
        ],
        openings,
        mdmt: None,
        external: None,
        external_required: None,
        deficiency,
    }))
}

/// UG-28 / UG-33 of a part of corroded wall `t` mm. Choice: a shell's
/// unsupported length L is its own length plus Do/3, the largest UG-28(b) head
/// allowance (one third of a hemisphere's depth at each end), which can only
/// lower the result; stiffening rings and cones are not taken.
fn external_check(geometry: &PartGeometry, t: f64, c: &Conditions) -> Result<External, String> {
    use super::external::{cylinder, head};
    let (e, sy) = (c.modulus, c.yield_strength);
    match geometry {
        PartGeometry::Shell(s) => cylinder(s.outside_diameter, t, unsupported_length(s), e, sy),
        PartGeometry::Head(h) => head(external_head_radius(h)?, t, e, sy),
        _ => Err(NOT_EXTERNAL.into()),
    }
}

/// The corroded wall a part of `geometry` needs under the external pressure of
/// `c`, mm: UG-28 inverted for a shell (the unsupported length of
/// `external_check`), UG-33 for the heads it computes.
fn external_required(geometry: &PartGeometry, c: &Conditions) -> Result<f64, String> {
    use super::external::{required_cylinder, required_head};
    let (e, sy, p) = (c.modulus, c.yield_strength, c.external_pressure);
    match geometry {
        PartGeometry::Shell(s) => {
            required_cylinder(s.outside_diameter, unsupported_length(s), e, sy, p)
        }
        PartGeometry::Head(h) => required_head(external_head_radius(h)?, e, sy, p),
        _ => Err(NOT_EXTERNAL.into()),
    }
}

/// What external pressure does not compute.
const NOT_EXTERNAL: &str =
    "UG-28/UG-33: reducers and cones under external pressure are not computed";

/// A shell's unsupported length for UG-28: its length plus the heads'
/// allowance (one third of a hemisphere's depth at each end).
fn unsupported_length(s: &Shell) -> f64 {
    s.length + s.outside_diameter / 3.0
}

/// A head's outside radius Ro for UG-33 (the crown radius of a torispherical
/// head, the equivalent sphere of an ellipsoidal one).
fn external_head_radius(h: &Head) -> Result<f64, String> {
    match h.kind {
        HeadKind::Hemispherical => Ok(h.outside_diameter / 2.0),
        HeadKind::Ellipsoidal { ratio } => {
            super::external::ellipsoidal_ro(h.outside_diameter, ratio)
        }
        HeadKind::Torispherical { crown_radius, .. } => Ok(crown_radius),
        _ => Err(
            "UG-33: only hemispherical, 2:1 ellipsoidal and torispherical heads are computed"
                .into(),
        ),
    }
}

/// A tank's bottom or roof by `api650::plate`: the bottom is the head under the
/// liquid (static head > 0; the design liquid level is the top of the shell, so
/// the roof carries none).
fn tank_plate(
    id: &str,
    h: &crate::parts::heads::Head,
    thickness: Option<f64>,
    static_head: f64,
    openings: Vec<String>,
    c: &Conditions,
) -> Result<PartCalc, String> {
    let bottom = static_head > 0.0;
    let p = super::api650::plate(h.kind, h.outside_diameter, bottom, c.corrosion_allowance)
        .map_err(|e| format!("{id}: {e}"))?;
    let deficiency = thickness.and_then(|t| {
        (t < p.required).then(|| {
            format!(
                "{id}: {} {t} mm is thinner than {}'s {:.2} mm ({})",
                p.shape, p.paragraph, p.required, p.formula
            )
        })
    });
    let mut inputs = vec![Input {
        name: "D",
        value: h.outside_diameter * 1e-3,
        unit: "m",
    }];
    if bottom {
        inputs.push(Input {
            name: "CA",
            value: c.corrosion_allowance,
            unit: "mm",
        });
    }
    if let Some(t) = p.self_supporting {
        inputs.push(Input {
            name: "t self-supporting (5.10.5.1, info)",
            value: t,
            unit: "mm",
        });
    }
    Ok(PartCalc {
        id: id.to_string(),
        kind: "head",
        shape: p.shape,
        pressure: static_head,
        static_head,
        thickness,
        required: Formula {
            value: p.required,
            paragraph: p.paragraph,
            formula: p.formula,
        },
        required_seamless: p.required,
        inside_diameter: h.outside_diameter - 2.0 * thickness.unwrap_or(0.0),
        minimum: p.required,
        mawp: None,
        mawp_new_cold: None,
        inputs,
        openings,
        mdmt: None,
        external: None,
        external_required: None,
        deficiency,
    })
}
