//! The shape of a pressure part as the formulas see it (inside dimensions, new),
//! the strength inputs (S, E, corrosion allowance), the [`Formula`] result, and
//! the two entry points: [`required_thickness`] and [`mawp`].

use super::error::{non_negative, positive};
use super::{CalcError, heads, shells};

/// A pressure part's shape, inside dimensions in the new (uncorroded) state, mm.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Shape {
    /// Cylindrical shell, UG-27(c): both the circumferential and the
    /// longitudinal stress are checked and the governing one reported.
    Cylinder {
        /// Inside radius R, mm.
        inside_radius: f64,
    },
    /// Sphere or hemispherical head, UG-27(d) / UG-32(f).
    Sphere {
        /// Inside radius R, mm.
        inside_radius: f64,
    },
    /// Ellipsoidal head, UG-32(d) when 2:1, else Appendix 1-4(c) with K.
    Ellipsoidal {
        /// Inside diameter D of the skirt, mm.
        inside_diameter: f64,
        /// Inside depth h of the head (not counting the skirt), mm.
        inside_depth: f64,
    },
    /// Torispherical head, Appendix 1-4(d) with M (UG-32(e) is its L/r = 16⅔ case).
    Torispherical {
        /// Inside crown radius L, mm.
        crown_radius: f64,
        /// Inside knuckle radius r, mm.
        knuckle_radius: f64,
    },
    /// Conical shell or head without knuckle, UG-32(g).
    Cone {
        /// Inside diameter D at the large end, perpendicular to the axis, mm.
        inside_diameter: f64,
        /// Half apex angle α, degrees (UG-32(g) covers α ≤ 30°).
        half_apex_angle: f64,
    },
    /// Flat unstayed head or cover, UG-34(c)(2) formula (1).
    Flat {
        /// Diameter d as Fig. UG-34 defines it for the attachment, mm.
        diameter: f64,
        /// Attachment factor C of Fig. UG-34 (e.g. 0.17, 0.20, 0.33).
        attachment_factor: f64,
    },
}

impl Shape {
    /// The shape's name in messages.
    pub fn name(&self) -> &'static str {
        match self {
            Shape::Cylinder { .. } => "cylinder",
            Shape::Sphere { .. } => "sphere",
            Shape::Ellipsoidal { .. } => "ellipsoidal head",
            Shape::Torispherical { .. } => "torispherical head",
            Shape::Cone { .. } => "cone",
            Shape::Flat { .. } => "flat head",
        }
    }

    /// The shape after corrosion `ca` mm on the inside: every inside dimension
    /// grows by `ca` measured normal to the wall (a cone's diameter by
    /// 2·ca / cos α). A flat head's d grows by 2·ca (the shell it sits in corrodes).
    /// An ellipsoidal head keeps its proportion D/2h (so K, and a 2:1 head's
    /// UG-32(d), are those of the head as ordered).
    pub fn corroded(&self, ca: f64) -> Shape {
        match *self {
            Shape::Cylinder { inside_radius } => Shape::Cylinder {
                inside_radius: inside_radius + ca,
            },
            Shape::Sphere { inside_radius } => Shape::Sphere {
                inside_radius: inside_radius + ca,
            },
            Shape::Ellipsoidal {
                inside_diameter,
                inside_depth,
            } => Shape::Ellipsoidal {
                inside_diameter: inside_diameter + 2.0 * ca,
                inside_depth: inside_depth * (inside_diameter + 2.0 * ca) / inside_diameter,
            },
            Shape::Torispherical {
                crown_radius,
                knuckle_radius,
            } => Shape::Torispherical {
                crown_radius: crown_radius + ca,
                knuckle_radius: knuckle_radius + ca,
            },
            Shape::Cone {
                inside_diameter,
                half_apex_angle,
            } => Shape::Cone {
                inside_diameter: inside_diameter + 2.0 * ca / half_apex_angle.to_radians().cos(),
                half_apex_angle,
            },
            Shape::Flat {
                diameter,
                attachment_factor,
            } => Shape::Flat {
                diameter: diameter + 2.0 * ca,
                attachment_factor,
            },
        }
    }

    fn validate(&self) -> Result<(), CalcError> {
        let n = self.name();
        match *self {
            Shape::Cylinder { inside_radius } | Shape::Sphere { inside_radius } => {
                positive(n, "inside_radius", inside_radius)?;
            }
            Shape::Ellipsoidal {
                inside_diameter,
                inside_depth,
            } => {
                positive(n, "inside_diameter", inside_diameter)?;
                positive(n, "inside_depth", inside_depth)?;
            }
            Shape::Torispherical {
                crown_radius,
                knuckle_radius,
            } => {
                positive(n, "crown_radius", crown_radius)?;
                positive(n, "knuckle_radius", knuckle_radius)?;
            }
            Shape::Cone {
                inside_diameter,
                half_apex_angle,
            } => {
                positive(n, "inside_diameter", inside_diameter)?;
                positive(n, "half_apex_angle", half_apex_angle)?;
            }
            Shape::Flat {
                diameter,
                attachment_factor,
            } => {
                positive(n, "diameter", diameter)?;
                positive(n, "attachment_factor", attachment_factor)?;
            }
        }
        Ok(())
    }
}

/// The strength side of a calculation.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Strength {
    /// Allowable stress S at the design temperature, MPa.
    pub stress: f64,
    /// Joint efficiency E (UW-12), 0 < E ≤ 1.
    pub joint_efficiency: f64,
    /// Corrosion allowance, mm.
    pub corrosion_allowance: f64,
}

impl Strength {
    /// S·E after checking the inputs.
    pub(crate) fn se(&self, entity: &str) -> Result<f64, CalcError> {
        let s = positive(entity, "allowable_stress", self.stress)?;
        let e = positive(entity, "joint_efficiency", self.joint_efficiency)?;
        if e > 1.0 {
            return Err(CalcError::Input {
                entity: entity.into(),
                field: "joint_efficiency".into(),
                value: e,
                rule: "UW-12 joint efficiency is at most 1".into(),
            });
        }
        non_negative(entity, "corrosion_allowance", self.corrosion_allowance)?;
        Ok(s * e)
    }
}

/// One computed figure with the code paragraph and formula that gave it.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct Formula {
    /// The value: a thickness in mm (corrosion allowance included) or a pressure in MPa.
    pub value: f64,
    /// Code paragraph, e.g. `UG-27(c)(1)`.
    pub paragraph: &'static str,
    /// The formula as printed in the code, e.g. `t = P·R / (S·E − 0.6·P)`.
    pub formula: &'static str,
}

/// The thickness a part needs under internal `pressure` MPa, hot and corroded,
/// corrosion allowance included, mm. A cylinder reports the governing of UG-27(c)(1)
/// and (c)(2).
pub fn required_thickness(
    shape: &Shape,
    pressure: f64,
    strength: &Strength,
) -> Result<Formula, CalcError> {
    shape.validate()?;
    let se = strength.se(shape.name())?;
    positive(shape.name(), "pressure", pressure)?;
    let ca = strength.corrosion_allowance;
    let mut f = match shape.corroded(ca) {
        Shape::Cylinder { inside_radius } => {
            let c = shells::circumferential_thickness(inside_radius, pressure, se)?;
            let l = shells::longitudinal_thickness(inside_radius, pressure, se)?;
            if l.value > c.value { l } else { c }
        }
        Shape::Sphere { inside_radius } => shells::sphere_thickness(inside_radius, pressure, se)?,
        Shape::Cone {
            inside_diameter,
            half_apex_angle,
        } => shells::cone_thickness(inside_diameter, half_apex_angle, pressure, se)?,
        Shape::Ellipsoidal {
            inside_diameter,
            inside_depth,
        } => heads::ellipsoidal_thickness(inside_diameter, inside_depth, pressure, se)?,
        Shape::Torispherical {
            crown_radius,
            knuckle_radius,
        } => heads::torispherical_thickness(crown_radius, knuckle_radius, pressure, se)?,
        Shape::Flat {
            diameter,
            attachment_factor,
        } => heads::flat_thickness(diameter, attachment_factor, pressure, se)?,
    };
    f.value += ca;
    Ok(f)
}

/// The maximum allowable working pressure of a part of nominal `thickness` mm,
/// hot and corroded (the thickness less the corrosion allowance, on the corroded
/// shape), MPa. A cylinder reports the lesser of UG-27(c)(1) and (c)(2).
pub fn mawp(shape: &Shape, thickness: f64, strength: &Strength) -> Result<Formula, CalcError> {
    shape.validate()?;
    let se = strength.se(shape.name())?;
    positive(shape.name(), "thickness", thickness)?;
    let ca = strength.corrosion_allowance;
    let t = thickness - ca;
    if t <= 0.0 {
        return Err(CalcError::Input {
            entity: shape.name().into(),
            field: "thickness".into(),
            value: thickness,
            rule: format!("must exceed the corrosion allowance {ca} mm"),
        });
    }
    match shape.corroded(ca) {
        Shape::Cylinder { inside_radius } => {
            let c = shells::circumferential_mawp(inside_radius, t, se)?;
            let l = shells::longitudinal_mawp(inside_radius, t, se)?;
            Ok(if l.value < c.value { l } else { c })
        }
        Shape::Sphere { inside_radius } => shells::sphere_mawp(inside_radius, t, se),
        Shape::Cone {
            inside_diameter,
            half_apex_angle,
        } => shells::cone_mawp(inside_diameter, half_apex_angle, t, se),
        Shape::Ellipsoidal {
            inside_diameter,
            inside_depth,
        } => heads::ellipsoidal_mawp(inside_diameter, inside_depth, t, se),
        Shape::Torispherical {
            crown_radius,
            knuckle_radius,
        } => heads::torispherical_mawp(crown_radius, knuckle_radius, t, se),
        Shape::Flat {
            diameter,
            attachment_factor,
        } => heads::flat_mawp(diameter, attachment_factor, t, se),
    }
}
